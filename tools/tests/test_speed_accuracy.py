# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""bench/speed_accuracy (speed against accuracy): the soft-sphere mapping and a smoke run of the benchmark.

The mapping (bench/speed_accuracy.py, soft_params; doc/choosing_a_method.rst) claims, for
pair_style granular with a hooke spring, coeff_restitution damping and a linear_history
tangential spring without damping:
  - the normal restitution equals r (exact for the linear spring-dashpot; only the time step
    changes it, by < 0.001 at dt = t_c/50);
  - for sticking contacts (mu huge) the tangential restitution equals the target rt, up to a
    first-order time-step bias of about +0.8 dt/t_c (measured; 0.016 at dt = t_c/50);
  - with a finite Coulomb limit mu, contacts that slide all through (grazing) give Walton's
    rt = -1 + mu (1+q)/q (1+r) |g_n|/|g_t| exactly; in between the soft law slides part of the time
    and its rt lies below Walton's (not claimed equal, checked to stay below).
Each check is a two-particle LAMMPS collision (bench/soft/in.pair2) averaged over the phase of
the first contact within a time step.
"""
import csv
import math
import os
import subprocess
import sys

import numpy as np
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "bench"))
import speed_accuracy as sa  # noqa: E402

TC = 1e-3          # contact time, short against the time for the line of centres to turn


def restitution(tmp_path, k, r, rt, mu, q, gt_over_gn, offsets=3):
    (rm, tm), _ = sa.pair_restitution(TC, k, r, rt, mu, q, gt_over_gn, offsets, str(tmp_path))
    return rm, tm


@pytest.mark.parametrize("r,q", [(0.9, 0.5), (0.7, 0.4)])
def test_normal_restitution_is_the_target(tmp_path, r, q):
    rm, _ = restitution(tmp_path, 50, r, 0.0, 1e8, q, 0.5)
    assert abs(rm - r) < 1e-3


@pytest.mark.parametrize("beta", [0.0, 0.5, -0.5])
def test_sticking_tangential_restitution_is_the_target(tmp_path, beta):
    _, b50 = restitution(tmp_path, 50, 0.9, beta, 1e8, 0.5, 0.5)
    assert abs(b50 - beta) < 0.03
    # the deviation is a time-step error: five times smaller steps, several times smaller error
    _, b10 = restitution(tmp_path, 10, 0.9, beta, 1e8, 0.5, 0.5)
    assert abs(b10 - beta) > 3 * abs(b50 - beta)


def test_sliding_contacts_follow_walton(tmp_path):
    r, mu, rtmax, q = 0.95, 0.5, 0.4, 0.4
    for x in (6.0, 10.0):            # grazing: slides during the whole contact
        _, tm = restitution(tmp_path, 50, r, rtmax, mu, q, x, offsets=2)
        assert abs(tm - sa.walton_rt(r, mu, rtmax, q, x)) < 0.01
    # intermediate angles: partial sliding, rt below Walton's (a different law, see the doc)
    _, tm = restitution(tmp_path, 50, r, rtmax, mu, q, 1.0, offsets=2)
    assert tm < sa.walton_rt(r, mu, rtmax, q, 1.0) - 0.05


def test_soft_params_contact_time_and_ratio():
    """kn gives the damped half period t_c; kt/kn follows from matching the tangential phase."""
    for r, rt, q in ((0.9, 0.0, 0.5), (0.95, 0.4, 0.4)):
        p = sa.soft_params(0.02, r, rt, q)
        wd = math.sqrt(p["kn"] / 0.5 * (1 - p["zeta"] ** 2))
        assert math.pi / wd == pytest.approx(0.02, rel=1e-12)
        mt = 0.5 * q / (1 + q)
        assert math.sqrt(p["kt"] / mt) * 0.02 == pytest.approx(math.acos(-rt), rel=1e-12)


def test_smoke_run_writes_chart_table_and_sane_rows(tmp_path):
    out = tmp_path / "sa"
    p = subprocess.run([os.path.join(ROOT, "bench", "speed_accuracy"), "--smoke", "--out", str(out)],
                       capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr[-2000:]
    for name in ("speed_accuracy.csv", "speed_accuracy.md", "speed_accuracy.png"):
        assert (out / name).stat().st_size > 0
    assert open(out / "speed_accuracy.png", "rb").read(8) == b"\x89PNG\r\n\x1a\n"
    rows = list(csv.DictReader(open(out / "speed_accuracy.csv")))
    cool = [r for r in rows if r["scene"] == "cooling"]
    assert {r["method"] for r in cool} == {"ED", "DEM", "MF"}
    assert any(r["scene"].startswith("driven") and r["method"] == "DEM" for r in rows)
    # exact ED: the same trajectory at every step, so the same T_tr at the comparison time
    ed = [float(r["Ttr"]) for r in cool if r["method"] == "ED"]
    assert len(ed) >= 2 and max(ed) - min(ed) < 1e-8 * max(ed)
    assert all(float(r["cost"]) > 0 for r in rows if r["method"] in ("ED", "DEM") and r["status"] == "ok")
    dem = {(float(r["tc_mft"]), round(1 / float(r["dt_over_tc"]), 1)): r for r in cool if r["method"] == "DEM"}
    # soft spheres with a contact as long as the mean free time: far off (> 30 %), much worse
    # than with a ten times stiffer contact
    soft, stiff = dem[(1.0, 20.0)], dem[(0.1, 10.0)]
    assert abs(float(soft["err_Ttr"])) > 0.3
    assert abs(float(soft["err_Ttr"])) > 3 * abs(float(stiff["err_Ttr"]))
    # a time step of 2/3 of the contact time is beyond the stability limit of velocity Verlet
    # (omega dt = 2): the energy blows up and the run is reported as failed
    assert dem[(0.1, 1.5)]["status"] == "failed"
    assert "Soft/ED cost ratio" in open(out / "speed_accuracy.md").read()


def test_ceiling_from_the_event_core_alone():
    """The ceiling on the DEM/ED ratio: DEM's cost per collision time over what the event core
    alone costs (half a collision per particle, plus every kick re-predicting every particle)."""
    d = dict(method="DEM", cost=0.06, dt_mft=0.001, tc_mft=0.01, dt_over_tc=0.1)
    floor = dict(coll=2e-6, kick=2e-7)
    # driven: 1000 steps per collision time, 10 kicks per collision time (f_dr = 2, mft = 5)
    text = sa.ceiling("driven 0.05", d, dict(N=4096, mft=5.0), floor)
    ed_floor = 1000.0 * (0.5 * 2e-6 + 10.0 * 2e-7)            # 0.003 s
    assert f"at most **{0.06 / ed_floor:.0f}**" in text        # 20
    assert "60 ns" in text and "100 DEM steps per kick" in text
    assert f"**{0.06 / (1000.0 * 10.0 * 2e-7):.0f}**" in text   # the kicks alone: 30
    # cooling: no kicks; steps per collision time from the run's length in collision times
    text = sa.ceiling("cooling", d, dict(N=4096, mft0=4.0, collision_times=4.0), floor)
    assert "1250 steps per collision time" in text and "per particle and kick" not in text
    assert f"at most **{0.06 / (1000.0 * 0.5 * 2e-6):.0f}**" in text    # 60


def test_core_floor_measures_collisions_and_kicks():
    """bench_kick (built with the project): the core's cost per collision and per particle and kick
    are parsed from its output and positive."""
    f = sa.core_floor(256, 0.05, "smoke")
    if f is None:
        pytest.skip("bench_kick is not built")
    assert 0 < f["coll"] < 1e-3 and 0 < f["kick"] < 1e-3
    assert "one kick costs" in f["line"]
