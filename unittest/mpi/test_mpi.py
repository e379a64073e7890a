# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Exact hard-sphere dynamics across MPI ranks (fix hardsphere/ed parallel domain).

The scenes of in.scenes start from one initial state (written on one rank: velocity create
sums over ranks) and run on 1 to 16 ranks. Domain-decomposed windows give the serial
trajectory bit for bit (final states written with %.17g and compared as text) after 100 and
more collisions per particle, with conflicts redone, and across a restart file read on another
number of ranks. The chain scene is the constructed failure case: one step carries a pulse
through a chain that crosses the subdomain boundary, so the rank on the far side cannot know it
from its copies; the check must detect the conflict and redo the window (and without the check,
the result is wrong). Long runs on 1 and 2 ranks agree in their averages. A run killed with
kill -9 and continued from its last restart file is the uninterrupted run, bit for bit.
"""
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "tools"))
from granfric import lammpslog  # noqa: E402

LMP = os.path.join(ROOT, "tools", "lmp")
SCENES = os.path.join(HERE, "in.scenes")


def command(np_, log="none", **var):
    """tools/lmp running in.scenes on np_ ranks with the given variables."""
    cmd = [LMP] + (["-np", str(np_)] if np_ > 1 else []) + ["-in", SCENES, "-screen", "none"]
    cmd += ["-log", log]
    for k, v in var.items():
        cmd += ["-var", k, str(v)]
    return cmd


def lmp(work, np_, **var):
    p = subprocess.run(command(np_, **var), cwd=work, capture_output=True, text=True)
    assert p.returncode == 0, (p.stdout + p.stderr)[-3000:]


def state(path):
    """id x y vx vy omegaz ix iy, sorted by id."""
    return np.loadtxt(path, skiprows=9)


def scaled_difference(a, b, box):
    """Largest difference of unwrapped positions (per box length), velocities and spins (per
    their rms), and whether image flags and IDs agree."""
    assert np.array_equal(a[:, 0], b[:, 0])
    ua = a[:, 1:3] + a[:, 6:8] * box
    ub = b[:, 1:3] + b[:, 6:8] * box
    dx = np.abs(ua - ub).max() / box.max()
    vs = np.sqrt((a[:, 3:5] ** 2).mean())
    ws = np.sqrt((a[:, 5] ** 2).mean())
    dv = np.abs(a[:, 3:5] - b[:, 3:5]).max() / vs
    dw = np.abs(a[:, 5] - b[:, 5]).max() / ws
    return max(dx, dv, dw)


def box_of(log):
    with open(log) as f:
        for line in f:
            if line.startswith("Created orthogonal box") or "orthogonal box =" in line:
                w = line.replace("(", " ").replace(")", " ").split()
                nums = [float(x) for x in w if x.replace(".", "").replace("-", "").replace("e", "").isdigit()]
                lo, hi = np.array(nums[0:3]), np.array(nums[3:6])
                return (hi - lo)[:2]
    raise ValueError("no box in " + log)


# steps: a few collisions per particle (checked below), short enough that chaos has not yet
# amplified rounding beyond 1e-9
CASES = {"dilute": 6, "dense": 20, "driven": 10, "vibrated": 10}


@pytest.mark.parametrize("scene", list(CASES))
def test_same_trajectory_on_1_2_4_ranks(tmp_path, scene):
    w = str(tmp_path)
    lmp(w, 1, scene=scene, steps=0, out="s0", restart_out="init", log="log.init")
    box = box_of(os.path.join(w, "log.init"))
    for n in (1, 2, 4):
        lmp(w, n, scene=scene, steps=CASES[scene], every=1, restart_in="init", out=f"s{n}",
            log=f"log{n}")
    a = state(os.path.join(w, "s1"))
    d = lammpslog.read_thermo(os.path.join(w, "log2"))
    per_particle = 2.0 * d["f_ed[2]"][-1] / len(a)
    assert per_particle >= 1.5, f"only {per_particle:.2f} collisions per particle"
    assert d["f_ed[12]"][-1] > 0, "no window was done by domain decomposition"
    for n in (2, 4):
        # windows after the first keep the core of the last one: only some particles (the
        # copies whose state arrived different) are predicted afresh (element 18)
        d = lammpslog.read_thermo(os.path.join(w, f"log{n}"))
        predicted = d["f_ed[18]"][d["Step"] > 0]
        assert predicted[0] >= len(a), "the first window did not start afresh"
        assert predicted.min() < 0.5 * predicted[0], f"{n} ranks: no window kept its core"
    for n in (2, 4):
        diff = scaled_difference(a, state(os.path.join(w, f"s{n}")), box)
        assert diff < 1e-9, f"{scene}: {n} ranks differ from 1 rank by {diff:.2e}"


# Domain windows on any rank count give the serial run bit for bit: at least 100 collisions per
# particle (the dilute discs elastic and smooth, the dense ones nearly smooth and less inelastic
# with a longer step, so that they do not cool to a halt), the dense and driven scenes with
# conflicts and gathered redos
BITWISE = {"dilute": dict(steps=420, r=1.0, rt=-1.0),
           "dense": dict(steps=400, dt=0.1, rd=0.98, bd=-0.9),
           "driven": dict(steps=200), "vibrated": dict(steps=1000), "shaken": dict(steps=1000),
           "couette": dict(steps=400)}


def identical(w, a, b, least=100):
    """IDs of the atoms whose lines differ in dumps a and b (x, v, omega written with %.17g)"""
    with open(os.path.join(w, a)) as fa, open(os.path.join(w, b)) as fb:
        sa, sb = fa.read().splitlines()[9:], fb.read().splitlines()[9:]
    assert len(sa) == len(sb) > least
    return [x.split()[0] for x, y in zip(sa, sb) if x != y]


@pytest.mark.parametrize("scene", list(BITWISE))
def test_domain_windows_equal_serial_bit_for_bit(tmp_path, scene):
    w = str(tmp_path)
    lmp(w, 1, scene=scene, steps=0, out="s0", restart_out="init")
    var = dict(BITWISE[scene], scene=scene, restart_in="init")
    lmp(w, 1, out="s1", log="log1", **var)
    d = lammpslog.read_thermo(os.path.join(w, "log1"))
    natoms = len(state(os.path.join(w, "s1")))
    assert 2.0 * d["f_ed[2]"][-1] / natoms >= 100, "fewer than 100 collisions per particle"
    redone = 0
    for n in (2, 3, 4):
        lmp(w, n, out=f"s{n}", log=f"log{n}", **var)
        d = lammpslog.read_thermo(os.path.join(w, f"log{n}"))
        # every window by domain decomposition, conflicts repaired by the ranks (none gathered)
        assert d["f_ed[12]"][-1] == var["steps"], f"{n} ranks: a window was redone gathered"
        redone += d["f_ed[15]"][-1]
        differ = identical(w, "s1", f"s{n}")
        assert not differ, f"{n} ranks: {len(differ)} atoms differ, the first IDs {differ[:5]}"
    if scene in ("dense", "driven"):
        assert redone > 0, "no conflict was repaired"


def test_sheared_box_equal_serial_bit_for_bit(tmp_path):
    """Simple shear (fix deform xy erate, remap v) over 100 and more collisions per particle
    and several box flips: 2, 3 and 4 ranks give the serial state bit for bit (the windows
    of a sheared box are gathered on every rank)"""
    w = str(tmp_path)
    lmp(w, 1, scene="shear", steps=0, out="s0", restart_out="init")
    var = dict(scene="shear", restart_in="init", steps=800)
    lmp(w, 1, out="s1", log="log1", **var)
    d = lammpslog.read_thermo(os.path.join(w, "log1"))
    assert 2.0 * d["f_ed[2]"][-1] / len(state(os.path.join(w, "s1"))) >= 100, "fewer than 100 collisions per particle"
    for n in (2, 3, 4):
        lmp(w, n, out=f"s{n}", **var)
        differ = identical(w, "s1", f"s{n}")
        assert not differ, f"{n} ranks: {len(differ)} atoms differ, the first IDs {differ[:5]}"


@pytest.mark.parametrize("scene", ["driven", "vibrated", "shear"])
def test_restarted_on_other_rank_counts_equals_serial_bit_for_bit(tmp_path, scene):
    """A serial run that writes a restart file at step 60 (it then starts a new epoch from the
    atoms, as a run read from the file does), continued from that file on 3 ranks: the serial
    run's state at step 120, bit for bit."""
    w = str(tmp_path)
    lmp(w, 1, scene=scene, steps=0, out="s0", restart_out="init")
    common = dict(scene=scene, restart_every=60)
    lmp(w, 1, steps=120, restart_in="init", out="straight", **common)
    lmp(w, 2, steps=60, restart_in="init", out="half", **common)
    lmp(w, 3, steps=60, restart_in="rst60", out="continued", **common)
    differ = identical(w, "straight", "continued")
    assert not differ, f"{len(differ)} atoms differ at step 120, the first IDs {differ[:5]}"


@pytest.mark.parametrize("scene", ["dense", "driven"])
def test_8_and_16_ranks_equal_serial_bit_for_bit(tmp_path, scene):
    """8 and 16 ranks (oversubscribed), conflicts provoked by a short reach (no widening of the
    shell beyond the speed bound) and repaired by the ranks involved, not gathered: the serial
    bits."""
    w = str(tmp_path)
    lmp(w, 1, scene=scene, steps=0, out="s0", restart_out="init")
    var = dict(scene=scene, restart_in="init", steps=60, reach=1.0)
    lmp(w, 1, out="s1", **var)
    for n in (8, 16):
        lmp(w, n, out=f"s{n}", log=f"log{n}", **var)
        d = lammpslog.read_thermo(os.path.join(w, f"log{n}"))
        assert d["f_ed[12]"][-1] == var["steps"], f"{n} ranks: a window was redone gathered"
        assert d["f_ed[15]"][-1] > 0, f"{n} ranks: no conflict was repaired"
        differ = identical(w, "s1", f"s{n}")
        assert not differ, f"{n} ranks: {len(differ)} atoms differ, the first IDs {differ[:5]}"
    # a repair involves the ranks near the conflict: on the 4 x 4 grid fewer windows are redone
    # than all ranks in all rounds (on 4 x 2 every rank neighbours every other). Not so with
    # kicks: an atom kicked beyond the speed bound fails the guard, and every rank widens
    if scene == "dense":
        assert d["f_ed[20]"][-1] < 16 * d["f_ed[19]"][-1], "16 ranks: every repair redid all"


def test_atom_replaced_between_runs(tmp_path):
    """Between two runs atom 218, far inside one rank's region (a copy on no other rank), is
    deleted and a new atom created where it was. The new atom has no stored state, so the
    second run begins a new epoch from LAMMPS's atoms on every rank count (serially too: the
    atoms are not those of the core) and every rank drops its core; the trajectories on 1, 2
    and 4 ranks are the same bit for bit."""
    w = str(tmp_path)
    lmp(w, 1, scene="dilute", steps=0, out="s0", restart_out="init", log="log.init")
    for n in (1, 2, 4):
        lmp(w, n, scene="dilute", steps=3, cut=3, every=1, restart_in="init", out=f"s{n}",
            log=f"log{n}")
    a = state(os.path.join(w, "s1"))
    assert 218 not in a[:, 0] and 901 in a[:, 0] and len(a) == 900
    for n in (1, 2, 4):
        d = lammpslog.read_thermo(os.path.join(w, f"log{n}"))    # (the second run)
        assert d["f_ed[18]"][1] >= len(a), f"{n} ranks: the second run kept a core"
    for n in (2, 4):
        differ = identical(w, "s1", f"s{n}")
        assert not differ, f"{n} ranks: {len(differ)} atoms differ, the first IDs {differ[:5]}"


@pytest.mark.parametrize("scene", ["dilute", "shear"])
def test_step_number_moved_between_runs(tmp_path, scene):
    """Between two runs reset_timestep moves the step number on by 3 steps. The second run's
    first window begins 3 steps later in time than the stored states of the first run's last
    window, so every rank count begins a new epoch from LAMMPS's atoms there (each rank
    predicts all its atoms afresh) instead of continuing them; 1 and 2 ranks end with the same
    bits. In a sheared box the new epoch starts from the positions as the last window wrote
    them, which LAMMPS's reneighboring had rounded, on one rank as on several."""
    w = str(tmp_path)
    lmp(w, 1, scene=scene, steps=0, out="s0", restart_out="init")
    natoms = len(state(os.path.join(w, "s0")))
    for n in (1, 2):
        lmp(w, n, scene=scene, steps=6, leap=3, every=1, restart_in="init", out=f"s{n}",
            log=f"log{n}")
        d = lammpslog.read_thermo(os.path.join(w, f"log{n}"))    # (the second run)
        assert d["Step"][0] == 9 and d["f_ed[18]"][1] >= natoms, f"{n} ranks: the epoch went on"
    differ = identical(w, "s1", "s2")
    assert not differ, f"2 ranks: {len(differ)} atoms differ, the first IDs {differ[:5]}"


@pytest.mark.parametrize("alter", ["mass", "diameter", "omega", "balance"])
def test_atoms_set_between_runs(tmp_path, alter):
    """Between two runs a set command changes the atoms' masses, diameters or spins (their
    positions and velocities stay). Serially the core no longer holds the atoms, so the second
    run begins a new epoch from LAMMPS's atoms; every rank of a domain window sees the change
    too and begins it alike. Or a balance command rounds positions in the last place and new
    coefficients start a new epoch: serially the positions are put back from the core, on
    several ranks from the stored states. 1, 2 and 3 ranks end with the same bits."""
    w = str(tmp_path)
    lmp(w, 1, scene="dilute", steps=0, out="s0", restart_out="init")
    for n in (1, 2, 3):
        lmp(w, n, scene="dilute", steps=20, alter=alter, restart_in="init", out=f"s{n}")
    for n in (2, 3):
        differ = identical(w, "s1", f"s{n}")
        assert not differ, f"{n} ranks: {len(differ)} atoms differ, the first IDs {differ[:5]}"


def test_chain_across_boundary_is_detected_and_redone(tmp_path):
    w = str(tmp_path)
    lmp(w, 1, scene="chain", steps=1, out="s1", log="log1")
    lmp(w, 2, scene="chain", steps=1, out="s2", log="log2")
    a, b = state(os.path.join(w, "s1")), state(os.path.join(w, "s2"))
    d = lammpslog.read_thermo(os.path.join(w, "log2"))
    assert d["f_ed[14]"][-1] > 0, "the conflict was not detected"
    assert d["f_ed[15]"][-1] == 1, "the window was not redone"
    assert np.abs(a - b).max() < 1e-12
    # the pulse went through: the last disc of the chain moves, the striker rests
    assert a[30, 3] == pytest.approx(1.0) and abs(a[31, 3]) < 1e-12
    # without the check the rank beyond the boundary never sees the pulse
    lmp(w, 2, scene="chain", check="no", steps=1, out="s2u", log="log2u")
    u = state(os.path.join(w, "s2u"))
    assert np.abs(a[:, 3] - u[:, 3]).max() > 0.5


def test_atom_faster_than_the_bound_is_guarded(tmp_path):
    """A collision within the step makes disc A faster than the speed bound D / dt the shell was
    built from (D = reach v_max dt = 3.6, shell W = 2 D + 1 = 8.2); A starts 8.4 from the other
    rank's atom, outside that rank's region, so it was not sent there. The guard must see
    that A's path (up to 3 sqrt 2 = 4.24) could have closed the gap (W + path - D = 8.84)
    and redo the window; the result is the serial one."""
    w = str(tmp_path)
    lmp(w, 1, scene="boost", steps=1, out="s1", log="log1")
    lmp(w, 2, scene="boost", steps=1, out="s2", log="log2")
    a, b = state(os.path.join(w, "s1")), state(os.path.join(w, "s2"))
    d = lammpslog.read_thermo(os.path.join(w, "log2"))
    assert d["f_ed[14]"][-1] == 1, "the guard did not fail the window"
    assert d["f_ed[15]"][-1] == 1, "the window was not redone"
    assert np.abs(a - b).max() < 1e-12
    # the collision happened: A leaves at (1, 1), B rests, the third disc never moved
    assert a[0, 3:5] == pytest.approx([1.0, 1.0]) and np.abs(a[1, 3:5]).max() < 1e-12
    assert np.abs(a[2, 3:5]).max() == 0.0


def test_long_runs_agree_statistically(tmp_path):
    """Driven steady state on 1 and 2 ranks: the trajectories part (chaos) but T_tr, T_rot and
    the collision rate agree within their statistical errors."""
    w = str(tmp_path)
    lmp(w, 1, scene="driven", steps=0, out="s0", restart_out="init")
    res = {}
    for n in (1, 2):
        lmp(w, n, scene="driven", steps=600, every=5, restart_in="init", out=f"s{n}", log=f"log{n}")
        d = lammpslog.read_thermo(os.path.join(w, f"log{n}"))
        sel = d["Step"] >= 200
        rate = np.diff(d["f_ed[2]"])[sel[1:]] / np.diff(d["Time"])[sel[1:]]
        res[n] = {"Ttr": lammpslog.block_mean(d["c_T[1]"][sel], 8),
                  "Trot": lammpslog.block_mean(d["c_T[2]"][sel], 8),
                  "rate": lammpslog.block_mean(rate, 8)}
    for key in ("Ttr", "Trot", "rate"):
        (m1, e1), (m2, e2) = res[1][key], res[2][key]
        assert abs(m1 - m2) < 4.0 * np.hypot(e1, e2), f"{key}: {m1} ± {e1} vs {m2} ± {e2}"
        assert abs(m1 - m2) < 0.05 * m1, f"{key}: {m1} vs {m2}"


@pytest.mark.parametrize("first,second", [(2, 1), (1, 2)])
def test_restart_across_rank_counts(tmp_path, first, second):
    w = str(tmp_path)
    lmp(w, 1, scene="dense", steps=0, out="s0", restart_out="init", log="log.init")
    box = box_of(os.path.join(w, "log.init"))
    lmp(w, 1, scene="dense", steps=20, restart_in="init", out="straight")
    lmp(w, first, scene="dense", steps=10, restart_in="init", out="half", restart_out="mid")
    lmp(w, second, scene="dense", steps=10, restart_in="mid", out="end")
    diff = scaled_difference(state(os.path.join(w, "straight")), state(os.path.join(w, "end")), box)
    assert diff < 1e-9


def run_until_killed(work, np_, wait_for, timeout=120.0, **var):
    """Start a run, wait until file wait_for exists, then kill -9 the whole process group (the
    launcher and every MPI rank), as a crashed node or a queue's time limit would."""
    p = subprocess.Popen(command(np_, **var), cwd=work, process_group=0,
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    target = os.path.join(work, wait_for)
    t0 = time.monotonic()
    try:
        while not os.path.exists(target):
            assert p.poll() is None, "the run ended before it was killed: " + p.stderr.read().decode()[-2000:]
            assert time.monotonic() - t0 < timeout, f"no {wait_for} after {timeout} s"
            time.sleep(0.05)
    finally:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGKILL)
        p.wait()
    assert p.returncode == -signal.SIGKILL


# kicks (driven), walls with a vibrating base and gravity (vibrated), the TC model (dense and
# vibrated); serial, and on 2 ranks in both parallel modes
@pytest.mark.parametrize("scene", ["driven", "vibrated", "dense"])
@pytest.mark.parametrize("np_,parallel", [(1, "domain"), (2, "domain"), (2, "gather")])
def test_restart_after_kill_continues_bit_for_bit(tmp_path, scene, np_, parallel):
    """A run killed (kill -9) after writing restart files, continued from the one of step 20,
    reaches step 40 in exactly the state of the uninterrupted run (which writes the same
    restart files)."""
    w = str(tmp_path)
    lmp(w, 1, scene=scene, steps=0, out="s0", restart_out="init")
    common = dict(scene=scene, restart_every=20, every=10, parallel=parallel)
    lmp(w, np_, steps=40, restart_in="init", out="straight", **common)
    for f in os.listdir(w):
        if f.startswith("rst"):
            os.remove(os.path.join(w, f))
    # (rst40 exists once rst20 is complete)
    run_until_killed(w, np_, "rst40", steps=100000, restart_in="init", out="never", **common)
    assert not os.path.exists(os.path.join(w, "never"))
    lmp(w, np_, steps=20, restart_in="rst20", out="continued", **common)
    with open(os.path.join(w, "straight")) as a, open(os.path.join(w, "continued")) as b:
        sa, sb = a.read().splitlines()[9:], b.read().splitlines()[9:]
    assert len(sa) > 100
    differ = [x.split()[0] for x, y in zip(sa, sb) if x != y]
    assert not differ, f"{len(differ)} atoms differ at step 40, the first IDs {differ[:5]}"


# Inhomogeneous scenes, in which ranks own no atoms (at the start, or from some step on), on 2,
# 3 and 4 ranks, unbalanced and balanced (balance before the run and fix balance every 5 steps,
# shift or rcb with comm_style tiled): the serial bits.
# - half: the atoms fill x < 19 of a 40-wide periodic box; LAMMPS splits it along x, so on 2
#   and 4 ranks the ranks right of x = 20 start empty (balancing moves the boundaries into
#   the gas); kicks, the Walton law.
# - settle: a 3d bed falls onto its floor under gravity (TC model, walls); LAMMPS splits the
#   40-high box along z, and the upper subdomains empty during the run (checked below on the
#   serial state: every atom ends below z = 10, the lowest of 4 layers).
# - lone: 3 atoms on up to 4 ranks, one of them fast and alone: every step it leaves a rank,
#   which then owns nothing, within one window.
EMPTY = {"half": dict(steps=100), "settle": dict(steps=150, bdims="z"), "lone": dict(steps=30)}


@pytest.mark.parametrize("balance", ["none", "shift", "rcb"])
@pytest.mark.parametrize("scene", list(EMPTY))
def test_empty_subdomains_equal_serial_bit_for_bit(tmp_path, scene, balance):
    w = str(tmp_path)
    lmp(w, 1, scene=scene, steps=0, out="s0", restart_out="init")
    var = dict(EMPTY[scene], scene=scene, restart_in="init")
    lmp(w, 1, out="s1", log="log1", **var)
    a = np.loadtxt(os.path.join(w, "s1"), skiprows=9, ndmin=2)
    if scene == "settle":
        assert a[:, 3].max() < 10.0, "the bed did not settle below the lowest subdomain boundary"
    if scene == "half":
        assert a[:, 1].max() > 20.0, "the gas did not spread into the empty half"
    least = 2 if scene == "lone" else 100
    for n in (2, 3, 4):
        lmp(w, n, out=f"s{n}", log=f"log{n}", balance=balance, **var)
        d = lammpslog.read_thermo(os.path.join(w, f"log{n}"))
        assert d["f_ed[12]"][-1] == var["steps"], f"{n} ranks: a window was redone gathered"
        differ = identical(w, "s1", f"s{n}", least)
        assert not differ, f"{n} ranks: {len(differ)} atoms differ, the first IDs {differ[:5]}"


@pytest.mark.parametrize("scene", ["half", "settle"])
def test_empty_subdomains_gathered_equal_serial(tmp_path, scene):
    """parallel gather, in which every rank runs the whole system, with ranks that own nothing
    (4 ranks), and balanced by shift (3 ranks: the rounding of the positions is undone there
    too)"""
    w = str(tmp_path)
    lmp(w, 1, scene=scene, steps=0, out="s0", restart_out="init")
    var = dict(EMPTY[scene], scene=scene, restart_in="init")
    lmp(w, 1, out="s1", **var)
    lmp(w, 4, out="s4", parallel="gather", **var)
    lmp(w, 3, out="s3", parallel="gather", balance="shift", **var)
    for n in (4, 3):
        differ = identical(w, "s1", f"s{n}")
        assert not differ, f"{n} ranks: {len(differ)} atoms differ, the first IDs {differ[:5]}"


def test_balanced_run_restarted_on_other_rank_counts(tmp_path):
    """The settling bed balanced by shift on 2 ranks, written to a restart file at step 60 and
    continued on 3 ranks balanced by rcb: the serial state at step 120, bit for bit."""
    w = str(tmp_path)
    lmp(w, 1, scene="settle", steps=0, out="s0", restart_out="init")
    common = dict(scene="settle", restart_every=60, bdims="z")
    lmp(w, 1, steps=120, restart_in="init", out="straight", **common)
    lmp(w, 2, steps=60, restart_in="init", out="half", balance="shift", **common)
    lmp(w, 3, steps=60, restart_in="rst60", out="continued", balance="rcb", **common)
    differ = identical(w, "straight", "continued")
    assert not differ, f"{len(differ)} atoms differ at step 120, the first IDs {differ[:5]}"


# Every example scene of examples/ with dynamics, its input as a user runs it (shortened by its
# own variables), serially and on 2-4 ranks, unbalanced and balanced (balance before the first
# run and fix balance every 10 steps, shift or rcb with comm_style tiled): the same final
# positions, velocities and spins, bit for bit. The test copies the example's directory and puts
# the balancing commands before the input's first run command and a dump of the final state at
# its end. LAMMPS's velocity command (create, scale) sums the momentum and the temperature over
# the ranks, which rounds otherwise on each rank count: the serial run writes the atoms with
# %.17g before its pair style is set (after the atoms are made) and after every velocity command
# after the first run, and the runs on several ranks read them there with read_dump.
EXAMPLE_SCENES = [
    ("cooling", "in.cooling2d", {"nside": 32, "tend": 40}),
    ("cooling", "in.cooling3d", {"nside": 10, "tend": 40}),
    ("driven", "in.driven", {"nside": 24, "tend": 20}),
    ("compaction", "in.compaction", {"tend": 400}),
    ("convection", "in.convection", {"periods": 100}),
    ("eos", "in.eos", {"dim": 2, "ncell": 3, "neq": 5, "nrun": 10}),
    ("eos", "in.eos", {"dim": 3, "ncell": 3, "neq": 5, "nrun": 10}),
]
EXAMPLE_RANKS = [(1, "none"), (2, "none"), (4, "none"), (3, "shift"), (4, "rcb")]


def example_copy(work, directory, script, n, balance, three_d):
    """The example's directory copied for a run on n ranks, with in.ranks: its input with the
    balancing commands, the serial velocities and the final dump (see above)."""
    import shutil
    src = os.path.join(ROOT, "examples", directory)
    dst = os.path.join(work, f"{directory}.{n}.{balance}")
    shutil.copytree(src, dst, ignore=shutil.ignore_patterns("log.*", "*.png"))
    with open(os.path.join(src, script)) as f:
        lines = f.read().splitlines()
    dims = "xyz" if three_d else "xy"
    fields = "x y z vx vy vz" if three_d else "x y vx vy"

    def state(k):
        if n == 1:
            return [f"write_dump all custom ../state{k}.dump id x y z vx vy vz modify sort id "
                    "format float %.17g"]
        return [f"read_dump ../state{k}.dump $(step) {fields} box no format native"]
    first = next(k for k, l in enumerate(lines) if l.split()[:1] == ["run"])
    made = next(k for k, l in enumerate(lines) if "pair_style" in l.split("#")[0])
    out = []
    for k, line in enumerate(lines):
        if k == made:
            out += state(0)
        if k == first:
            out += {"none": [],
                    "shift": [f"balance 1.0 shift {dims} 10 1.05",
                              f"fix bal all balance 10 1.0 shift {dims} 10 1.05"],
                    "rcb": ["comm_style tiled", "balance 1.0 rcb", "fix bal all balance 10 1.0 rcb"]}[balance]
        out.append(line)
        if k > first and line.split()[:1] == ["velocity"]:
            out += state(k)
    out.append("write_dump all custom final.txt id x y z vx vy vz omegax omegay omegaz "
               "modify sort id format float %.17g")
    with open(os.path.join(dst, "in.ranks"), "w") as f:
        f.write("\n".join(out) + "\n")
    return dst


@pytest.mark.parametrize("directory,script,var", EXAMPLE_SCENES,
                         ids=[f"{s[1][3:]}{s[2].get('dim', '')}" for s in EXAMPLE_SCENES])
def test_examples_on_1_to_4_ranks_balanced_equal_serial(tmp_path, directory, script, var):
    w = str(tmp_path)
    three_d = script == "in.cooling3d" or var.get("dim") == 3
    finals = {}
    for n, balance in EXAMPLE_RANKS:
        d = example_copy(w, directory, script, n, balance, three_d)
        cmd = [LMP] + (["-np", str(n)] if n > 1 else []) + ["-in", "in.ranks", "-screen", "none",
                                                              "-log", "log.ranks"]
        for k, v in var.items():
            cmd += ["-var", k, str(v)]
        p = subprocess.run(cmd, cwd=d, capture_output=True, text=True)
        if p.returncode != 0:
            with open(os.path.join(d, "log.ranks")) as f:
                errors = [l for l in f if "ERROR" in l]
            pytest.fail(f"{n} ranks, {balance}: {errors or p.stderr[-2000:]}")
        with open(os.path.join(d, "final.txt")) as f:
            finals[(n, balance)] = f.read().splitlines()[9:]
    serial = finals[(1, "none")]
    assert len(serial) > 100
    for key, rows in finals.items():
        differ = [a.split()[0] for a, b in zip(serial, rows) if a != b]
        assert len(rows) == len(serial) and not differ, \
            f"{key}: {len(differ)} atoms differ from the serial run, the first IDs {differ[:5]}"
