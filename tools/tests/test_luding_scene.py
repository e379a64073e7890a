# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""The cooling scene (examples/cooling) against the homogeneous-cooling theories of Luding et al.
1998: dilute (fraction 0.05, N = 4096), after the paper's elastic equilibration, over the first
~4 collisions per particle in 2D and ~8 in 3D (T_tr falls to ~0.4), averaged over 64 seeds.

Two theories (examples/cooling/README.md):
- the mean-field ODEs (granfric.cooling: independent Gaussian translations and spins). T_tr
  follows them within 1.5 %, but T_rot and R lie 2-4.5 % below them by t = 10-20: that is the
  closure error of the Gaussian ansatz. The kinetic theory without it (DSMC of the homogeneous
  Enskog-Boltzmann equation through the same C++ law, granfric.dsmc) puts the mean field above
  the true T_rot by +2.6/+1.1/+3.2 % at t = 11 and +3.4/+1.8/+4.0 % at t = 18 (2D beta = 0,
  2D beta = 0.5, 3D beta = 0), and R likewise. T_rot and R are therefore held to 5 % of the mean
  field here, the measured state.
- the kinetic theory itself (DSMC), which the simulation must follow within 3 % (the acceptance
  criterion) in T_tr, T_rot and R, established at 2 sigma: over blocks of the window, the
  block-averaged deviation plus twice its standard error (the seeds' scatter of the block
  averages, and DSMC's) must stay below 3 %, with standard errors below 0.75 % (measured
  0.1-0.45 %).
  With 16 seeds (standard errors 0.5-0.8 %) 2D beta = 0.5 looked like T_rot -2.2 +- 0.5 % and
  R -2.6 +- 0.8 % at t = 12-20, beyond that bound; 64 seeds and a 4x larger DSMC ensemble give
  T_rot -1.0 +- 0.3 % and R -1.5 +- 0.4 %. Measured largest |deviation| + 2 s.e. over the
  blocks: 1.6 % (2D beta = 0), 2.2 % (2D beta = 0.5), 2.1 % (3D beta = 0; T_tr +1.7 +- 0.2 %
  at t = 16-20, the slower cooling of README "Simulation against the kinetic theory").
"""
import math

import numpy as np
import pytest

from granfric import luding

SEEDS = tuple(range(101, 165))
CASES = [(2, 0.0), (2, 0.5), (3, 0.0)]
_cache = {}


def runs(dim, beta, tmp_path_factory):
    """The ED runs of a case (one set per test run, shared by the tests below)."""
    if (dim, beta) not in _cache:
        tmp = tmp_path_factory.mktemp(f"cool{dim}d_b{beta}")
        _cache[(dim, beta)] = [luding.simulate(dim, 0.9, beta, 0.05, 20.0, str(tmp / f"log.{s}"), seed=s)
                               for s in SEEDS]
    return _cache[(dim, beta)]


@pytest.mark.parametrize("dim,beta", CASES)
def test_dilute_cooling_follows_mean_field_theory(tmp_path_factory, dim, beta):
    d, _ = luding.average(runs(dim, beta, tmp_path_factory))
    c = luding.compare(d, dim, 0.9, beta, 0.05)
    grown = d["Time"] >= 4.0    # T_rot has grown from 0 to a measurable level
    assert np.max(np.abs(d["c_T[1]"] / c["Ttr_th"] - 1)) < 0.03
    assert np.max(np.abs(d["c_T[2]"][grown] / c["Trot_th"][grown] - 1)) < 0.05
    assert np.max(np.abs(d["c_T[3]"][grown] / c["R_th"][grown] - 1)) < 0.05
    assert d["c_T[1]"][-1] < 0.7    # it did cool


BLOCKS = [(0.0, 4.0), (4.0, 8.0), (8.0, 12.0), (12.0, 16.0), (16.0, 20.0)]


@pytest.mark.parametrize("dim,beta", CASES)
def test_dilute_cooling_follows_kinetic_theory_within_3_percent(tmp_path_factory, dim, beta):
    rs = runs(dim, beta, tmp_path_factory)
    t = rs[0]["Time"]
    ks = luding.kinetic(dim, 0.9, beta, 0.05, t, np.mean([x["c_T[1]"][0] for x in rs]),
                        N=25000, runs=32, seed=23)
    blocks = {}
    for key, col in luding.SIM.items():
        x, e = ks[key]
        for a, b in BLOCKS:
            if key != "Ttr" and a < 4.0:
                continue    # T_rot and R start from 0: compare once they have grown
            m = (t > a) & (t <= b)
            per_seed = np.array([np.mean(r[col][m] / x[m] - 1) for r in rs])
            se = math.hypot(per_seed.std(ddof=1) / math.sqrt(len(rs)), np.mean(e[m] / x[m]))
            blocks[(key, a, b)] = (per_seed.mean(), se)
    table = "; ".join(f"{k} {a:g}-{b:g}: {100 * d:+.2f} +- {100 * se:.2f} %"
                      for (k, a, b), (d, se) in blocks.items())
    # the check has the resolution it claims: a 3 % deviation would stand out at >= 4 sigma
    assert max(se for _, se in blocks.values()) < 0.0075, table
    outside = [k for k, (d, se) in blocks.items() if abs(d) + 2 * se >= 0.03]
    assert not outside, f"|deviation| + 2 se >= 3 % in {outside}: {table}"


def test_elastic_rough_gas_equipartitions_and_conserves_energy(tmp_path):
    d = luding.simulate(2, 1.0, 1.0, 0.05, 1000.0, str(tmp_path / "log.eq"))
    E = d["c_T[1]"] + 0.5 * d["c_T[2]"]    # 2D: E/N = T_tr + T_rot/2
    assert np.max(np.abs(E / E[0] - 1)) < 1e-10
    # the mean of R over 100 < t <= 1000 (about 200 collisions per disc) scatters by 0.005
    # between seeds (by 0.016 over 100 < t <= 200): 0.02 is four of those
    late = d["Time"] > 100
    assert abs(np.mean(d["c_T[3]"][late]) - 1.0) < 0.02
