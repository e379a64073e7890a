# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Smoke tests of the Python tools: collision-law demonstration, LAMMPS log reader."""
import os

import numpy as np
import pytest

from granfric import collision_demo, core, lammpslog


def test_collision_demo_writes_table_and_figure(tmp_path):
    collision_demo.main(["--out", str(tmp_path)])
    assert (tmp_path / "collision_laws.png").stat().st_size > 10000
    table = (tmp_path / "collision_table.md").read_text()
    assert table.count("\n") == 2 + 3 * len(collision_demo.CASES)


def test_ctypes_core_head_on():
    c = core.collide("walton", (0.9, 0.5, 0.4), core.Body(v=(-1, 0, 0), q=0.5), core.Body(q=0.5),
                     (1, 0, 0))
    # equal masses, head on: g_n' = -r g_n
    assert (c.v1 - c.v2)[0] == pytest.approx(0.9, rel=1e-15)
    assert c.dE < 0 and not c.sliding


def test_wall_limit_through_ctypes():
    c = core.collide("rough", (0.8, -1.0), core.Body(v=(0, -1, 0)), core.Body.wall(), (0, 1, 0))
    assert c.v1[1] == pytest.approx(0.8, rel=1e-15)


def test_read_thermo(tmp_path):
    log = tmp_path / "log"
    log.write_text("LAMMPS\nStep Time c_T[1]\n0 0 1.0\n10 1.0 0.5\nLoop time of 1 on 1 procs\n"
                   "Step Time c_T[1]\n10 1.0 0.5\n20 2.0 0.25\nLoop time of 1 on 1 procs\n")
    d = lammpslog.read_thermo(str(log))
    assert list(d["Step"]) == [10, 20] and list(d["c_T[1]"]) == [0.5, 0.25]
    d0 = lammpslog.read_thermo(str(log), block=0)
    assert list(d0["Time"]) == [0, 1.0]


def test_compaction_is_strongest_near_kappa_0p3(tmp_path):
    """Risso Fig. 2: the bed on a thermal base is most compact where the loss per collision is
    largest (kappa ~ 0.3). Measured: Y_cm ~ 40 at kappa = 0.01 and 3, ~ 22 at 0.3."""
    from granfric import risso
    y = {k: risso.compaction(k, str(tmp_path / f"log.{k}"), tend=15000.0) for k in (0.01, 0.3, 3.0)}
    assert y[0.3][0] < y[0.01][0] - 5 and y[0.3][0] < y[3.0][0] - 5, y
