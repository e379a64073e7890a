# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""The core's random kicks (core/kicks.h) through the C API: the same numbers fix hardsphere/kick
gives in LAMMPS, independent of the particles' order, momentum kept, the variance of eq 7."""
import os

import numpy as np
import pytest

from granfric import core, lmp

# atoms at rest, far apart, one kick (f_dr = 1 per time unit, the step is 0.5: kick 0 at t = 0
# in the first step, none in the second); their velocities after the run are the kick
SCRIPT = """
units lj
dimension 3
atom_style sphere
boundary p p p
region box block 0 40 0 40 0 40
create_box 2 box
create_atoms 1 random 50 4321 NULL overlap 2.0 maxtry 1000
set type 1 diameter 1.0
set group all mass ${m}
group half id <= 20
set group half type 2
set group half mass ${m2}
velocity all set 0 0 0
pair_style hardsphere/rough
pair_coeff * * 1.0 -1.0
comm_modify vel yes
neighbor 0.0 bin
fix ed all hardsphere/ed
fix kick all hardsphere/kick 1.0 0.05 ${seed} momentum yes spin 0.5
timestep 0.5
run 2
write_dump all custom ${out} id mass radius vx vy vz omegax omegay omegaz modify format float %.17g sort id
"""


def test_core_kicks_equal_fix_hardsphere_kick(tmp_path):
    script = tmp_path / "in.kick"
    script.write_text(SCRIPT)
    out = tmp_path / "kicked.dump"
    lmp.run(str(script), {"m": 1.5, "m2": 0.7, "seed": 77, "out": out}, cwd=tmp_path)
    d = np.loadtxt(out, skiprows=9)
    tags, m, radius = d[:, 0].astype(np.int64), d[:, 1], d[:, 2]
    # the same kick through the C API, the particles in reverse order
    rev = slice(None, None, -1)
    v, w = np.zeros((len(tags), 3)), np.zeros((len(tags), 3))
    core.kick(0, tags[rev], m[rev], radius[rev], v, w, fdr=1.0, vdr=0.05, seed=77, spin=0.5)
    assert np.array_equal(v[rev], d[:, 3:6])
    assert np.array_equal(w[rev], d[:, 6:9])


def test_kicks_keep_momentum_and_have_the_variance_of_eq_7():
    n = 20000
    tags = np.arange(1, n + 1)
    m, a = np.full(n, 2.0), np.full(n, 0.5)
    v, w = np.zeros((n, 3)), np.zeros((n, 3))
    core.kick(3, tags, m, a, v, w, vdr=0.2, seed=5, dim=2)
    # (zero up to the rounding of the sum and the shift: 1e-14 of the summed momenta)
    assert np.abs((m[:, None] * v).sum(axis=0)).max() < 1e-14 * (m[:, None] * np.abs(v)).sum()
    assert np.all(v[:, 2] == 0.0) and np.all(w == 0.0)    # (2d: no z, no spin without spin)
    var = v[:, :2].var(axis=0)
    assert var == pytest.approx(np.full(2, 0.04 * (1 - 1 / n)), rel=0.03)
    with pytest.raises(ValueError):
        core.kick(0, tags, m, a, v, w, seed=0)
