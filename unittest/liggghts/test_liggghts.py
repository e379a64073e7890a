# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""The LIGGGHTS host against the LAMMPS host (tools/liggghts, tools/lmp).

The scenes of in.hosts (free cooling of rough discs; discs driven by kicks with spin driving,
filling the box or its left half (on 2 ranks one starts with no atoms); a vibrated bed with walls, gravity, the Jenkins-Zhang law and the TC model; the cooling scene
also with LIGGGHTS's atom_style granular) run under both hosts
from the same initial state, serially and on 2 ranks. Every dumped number (positions,
velocities, spins at %.17g) is the same bit for bit at the start and after 200 steps (both hosts
wrap atoms into the box at every step: with their default reneighboring schedules, which
differ, positions as the hosts keep them differ in the last bits while the trajectory, which
goes on from the fix's stored states, is the same). Under either host a
run continued from a restart file ends where the writing run ends. LIGGGHTS's soft granular
walls and pair styles are refused next to fix hardsphere/ed, and pair exclusions warned. A bad keyword is
refused under LIGGGHTS with GRANFRIC's own message (LIGGGHTS 3.8 follows its error lines with a
line of stray bytes, decoded leniently here).
"""
import os
import subprocess

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
INPUT = os.path.join(HERE, "in.hosts")
HOSTS = {0: os.path.join(ROOT, "tools", "lmp"), 1: os.path.join(ROOT, "tools", "liggghts")}


def run(work, liggghts, np_, scene, steps=200, extra=()):
    out = os.path.join(work, f"state{liggghts}.txt")
    cmd = [HOSTS[liggghts]] + (["-np", str(np_)] if np_ > 1 else [])
    cmd += ["-in", INPUT, "-var", "liggghts", str(liggghts), "-var", "scene", scene,
            "-var", "steps", str(steps), "-var", "out", out, "-log", "none"] + list(extra)
    p = subprocess.run(cmd, cwd=work, capture_output=True, text=True, errors="replace")
    return p, out


def states(path):
    """the dumped states, one array (id x y vx vy omegaz, sorted by id) per timestep"""
    lines = open(path).read().split("\n")
    blocks, k = {}, 0
    while k < len(lines):
        if lines[k].startswith("ITEM: TIMESTEP"):
            n = int(lines[k + 3])
            rows = np.array([[float(v) for v in ln.split()] for ln in lines[k + 9:k + 9 + n]])
            blocks[int(lines[k + 1])] = rows
            k += 9 + n
        else:
            k += 1
    return blocks


@pytest.mark.parametrize("np_", [1, 2])
@pytest.mark.parametrize("scene", ["cooling", "driven", "half", "bed", "cooling-granular"])
def test_same_trajectory_under_both_hosts(tmp_path, scene, np_):
    """(cooling-granular: LIGGGHTS with its atom_style granular, LAMMPS with sphere)"""
    res = {}
    scene, _, style = scene.partition("-")
    for h in (0, 1):
        extra = ["-var", "atoms", style] if style and h == 1 else []
        p, out = run(str(tmp_path), h, np_, scene, extra=extra)
        assert p.returncode == 0, (p.stdout + p.stderr)[-3000:]
        res[h] = states(out)
    assert sorted(res[0]) == sorted(res[1]) == [0, 200]
    for step in (0, 200):
        a, b = res[0][step], res[1][step]
        assert a.shape == b.shape and a.shape[0] > 100
        assert np.array_equal(a[:, 0], b[:, 0])
        assert np.array_equal(a, b), f"the states differ at step {step}"
    # (the dynamics did something: velocities changed)
    assert not np.array_equal(res[1][0][:, 3:5], res[1][200][:, 3:5])


@pytest.mark.parametrize("liggghts", [0, 1])
@pytest.mark.parametrize("scene", ["cooling", "bed"])
def test_restart_continues_as_the_writing_run(tmp_path, liggghts, scene):
    """A run that writes a restart file after 100 steps and goes on for 100 more, and a run
    that reads the file and does the same 100 steps, end in the same state bit for bit (every
    dumped number), under either host; and the hosts agree with each other as above. The bed's
    base vibrates with the simulation time, which LIGGGHTS's read_restart starts from 0: fix
    hardsphere/ed restores it from its own restart data."""
    p, written = run(str(tmp_path), liggghts, 1, scene, steps=100, extra=["-var", "save", "1"])
    assert p.returncode == 0, (p.stdout + p.stderr)[-3000:]
    os.rename(written, os.path.join(str(tmp_path), "written.txt"))
    p, read = run(str(tmp_path), liggghts, 1, scene, steps=100, extra=["-var", "resume", "1"])
    assert p.returncode == 0, (p.stdout + p.stderr)[-3000:]
    a = states(os.path.join(str(tmp_path), "written.txt"))[200]
    b = states(read)[200]
    assert a.shape[0] > 100 and np.array_equal(a, b)


def readme_input():
    """the README's minimal input in LIGGGHTS's syntax (the block after its introduction)"""
    text = open(os.path.join(ROOT, "README.md")).read()
    start = text.index("```\n", text.index("The README's minimal input under LIGGGHTS")) + 4
    return text[start:text.index("```", start)]


def test_readme_input_runs_under_liggghts_as_under_lammps(tmp_path):
    """The README's minimal input under LIGGGHTS, and the same input under LAMMPS (its
    `atom_style sphere` and `comm_modify vel yes`), print the same thermo lines."""
    lig = readme_input()
    lmp = lig.replace("atom_style granular", "atom_style sphere").replace(
        "communicate single vel yes", "comm_modify vel yes")
    rows = {}
    for h, text in ((1, lig), (0, lmp)):
        path = tmp_path / f"in.readme{h}"
        path.write_text(text)
        p = subprocess.run([HOSTS[h], "-in", str(path), "-log", "none"], cwd=str(tmp_path),
                           capture_output=True, text=True, errors="replace")
        assert p.returncode == 0, (p.stdout + p.stderr)[-3000:]
        lines = p.stdout.split("\n")
        k = next(i for i, ln in enumerate(lines) if ln.split()[:1] == ["Step"])
        rows[h] = [ln.split() for ln in lines[k + 1:k + 3]]
    assert rows[0] == rows[1]
    assert int(rows[1][-1][-1]) > 10000    # collisions in 400 steps


GRANULAR_SETUP = """units lj
newton off
dimension 2
atom_style granular
communicate single vel yes
boundary p f p
region box block 0 10 0 20 -0.5 0.5 units box
create_box 1 box
create_atoms 1 single 2 5 0
create_atoms 1 single 6 10 0
set group all diameter 1.0
set group all mass 1.0
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.9
fix m4 all property/global coefficientFriction peratomtypepair 1 0.05
timestep 0.1
"""


@pytest.mark.parametrize("what, lines, message", [
    ("wall/gran", ["pair_style hardsphere/rough inertia disc", "pair_coeff * * 0.9 0.0",
                   "fix ed all hardsphere/ed",
                   "fix wg all wall/gran model hertz tangential history primitive type 1 yplane 0.0"],
     "Fix wg (wall/gran) is a soft granular wall, which the hard particles of fix hardsphere/ed ed "
     "do not feel: use fix hardsphere/wall"),
    ("pair gran", ["pair_style gran model hertz tangential history", "pair_coeff * *",
                   "fix ed all hardsphere/ed"],
     "Fix hardsphere/ed requires pair style hardsphere/rough, hardsphere/walton or hardsphere/jz "
     "(found gran)"),
])
def test_liggghts_granular_styles_refused(tmp_path, what, lines, message):
    """LIGGGHTS's soft granular walls and pair styles next to fix hardsphere/ed: a clear error"""
    path = tmp_path / "in.granular"
    path.write_text(GRANULAR_SETUP + "\n".join(lines) + "\nrun 0\n")
    p = subprocess.run([HOSTS[1], "-in", str(path), "-log", "none"], cwd=str(tmp_path),
                       capture_output=True, text=True, errors="replace")
    assert p.returncode != 0
    assert "ERROR: " + message in p.stdout, p.stdout[-2000:]


def test_bad_keyword_refused_with_granfrics_message(tmp_path):
    with open(tmp_path / "in.bad", "w") as f:
        f.write(open(INPUT).read().replace("fix             ed all hardsphere/ed\nvariable        dt equal 0.5",
                                           "fix             ed all hardsphere/ed bogus 1\nvariable        dt equal 0.5"))
    p = subprocess.run([HOSTS[1], "-in", str(tmp_path / "in.bad"), "-var", "liggghts", "1",
                        "-log", "none"], cwd=str(tmp_path), capture_output=True, text=True,
                       errors="replace")
    assert p.returncode != 0
    assert "ERROR" in p.stdout and "hardsphere/ed" in p.stdout and "bogus" in p.stdout, p.stdout[-2000:]


def two_discs(liggghts, tail):
    """two rough discs in a periodic box with fix hardsphere/ed, in the host's syntax, then
    the lines tail"""
    return """units lj
dimension 2
atom_style sphere
{}
boundary p p p
region box block 0 10 0 10 -0.5 0.5 units box
create_box 1 box
create_atoms 1 single 2 5 0
create_atoms 1 single 6 5 0
set group all diameter 1.0
set group all mass 1.0
pair_style hardsphere/rough inertia disc
pair_coeff * * 0.9 0.0
fix ed all hardsphere/ed
timestep 0.1
""".format("communicate single vel yes" if liggghts else "comm_modify vel yes") + tail


def run_text(tmp_path, liggghts, text):
    """the input text run under the host (returns the finished process)"""
    path = tmp_path / "in.text"
    path.write_text(text)
    return subprocess.run([HOSTS[liggghts], "-in", str(path), "-log", "none"], cwd=str(tmp_path),
                          capture_output=True, text=True, errors="replace")


def test_pair_exclusions_warned_under_liggghts(tmp_path):
    """neigh_modify exclude removes no collision of hard particles: warned, as under LAMMPS
    (LIGGGHTS keeps its exclusion counts protected; the host program reads them)"""
    warning = "WARNING: neigh_modify exclude has no effect on fix hardsphere/ed ed"
    for exclude in ("", "neigh_modify exclude type 1 1\n"):
        p = run_text(tmp_path, 1, two_discs(1, exclude + "run 1\n"))
        assert p.returncode == 0, p.stdout[-2000:]
        assert (warning in p.stdout) == bool(exclude), p.stdout[-2000:]


@pytest.mark.parametrize("liggghts", [0, 1])
def test_run_on_after_every_atom_was_deleted(tmp_path, liggghts):
    """delete_atoms group all between runs leaves an empty box: the next run goes on under both
    hosts (LIGGGHTS's atom sorting divides by the pair cut-off, which is kept from when there
    were atoms)"""
    p = run_text(tmp_path, liggghts, two_discs(liggghts, "run 5\ndelete_atoms group all\nrun 10\n"))
    assert p.returncode == 0, p.stdout[-2000:]
    assert "10 steps with 0 atoms" in p.stdout, p.stdout[-2000:]
