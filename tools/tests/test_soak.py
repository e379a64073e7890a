# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""bench/soak: its checks find what they are meant to find (the soak itself runs in CTest as
soak.serial_np2)."""
import os
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "bench"))
import soak  # noqa: E402

LO, HI = np.array([0.0, 0.0]), np.array([10.0, 10.0])


def atoms(*xyr):
    """rows id radius x y ix iy"""
    return np.array([[k + 1, r, x, y, 0, 0] for k, (x, y, r) in enumerate(xyr)], dtype=float)


def test_gap_of_a_pair_across_the_periodic_boundary():
    rows = atoms((0.2, 5.0, 0.5), (9.7, 5.0, 0.5), (5.0, 5.0, 0.5))
    gap, _ = soak.smallest_gap(LO, HI, rows, True, None)
    assert abs(gap - 0.5) < 1e-12    # distance 0.5 through the boundary, contact 1.0
    gap, _ = soak.smallest_gap(LO, HI, rows, False, None)
    assert gap == np.inf             # without periodic images they are far apart


def test_gap_of_unequal_atoms_and_positions_outside_the_box():
    rows = atoms((10.3, 2.0, 0.25), (1.0, 2.0, 0.5))    # x = 10.3 is 0.3 in the box
    gap, _ = soak.smallest_gap(LO, HI, rows, True, None)
    assert abs(gap - 0.7 / 0.75) < 1e-12


def test_atom_through_a_wall():
    rows = atoms((5.0, 0.4, 0.5), (5.0, 5.0, 0.5))
    _, through = soak.smallest_gap(LO, HI, rows, False, (0.0, 10.0, 0.0, 10.0))
    assert abs(through - 0.1) < 1e-12
    _, through = soak.smallest_gap(LO, HI, rows, False, (0.0, 10.0, -0.1, 10.0))
    assert through == 0.0


def test_dump_snapshots_are_read(tmp_path):
    text = ""
    for step, shift in ((0, 0.0), (10, 1.0)):
        text += (f"ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp pp pp\n"
                 "0 10\n0 10\n-0.5 0.5\nITEM: ATOMS id radius x y ix iy\n"
                 f"1 0.5 {1 + shift} 1 0 0\n2 0.5 {3 + shift} 1 0 -1\n")
    path = tmp_path / "d.dump"
    path.write_text(text)
    snaps = soak.read_dumps(str(path))
    assert len(snaps) == 2
    lo, hi, rows = snaps[1]
    assert np.array_equal(hi, [10.0, 10.0]) and rows[1, 2] == 4.0 and rows[1, 5] == -1
