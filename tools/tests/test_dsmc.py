# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""DSMC of the homogeneous Enskog-Boltzmann equation (granfric.dsmc) against what it must
reproduce independently of any closure: the batch collision call equals the single one,
conservation in the elastic limits, the collision frequency of a Maxwellian gas (Enskog, as
cooling.py), and the initial rates of the mean-field equations (exact for a Maxwellian state:
the closure only matters once the distribution has left the Gaussian)."""
import math

import numpy as np
import pytest

from granfric import cooling, core, dsmc


def test_batch_collision_equals_single_collisions():
    rng = np.random.default_rng(3)
    k = 50
    v1, w1, v2, w2 = (rng.normal(size=(k, 3)) for _ in range(4))
    n = rng.normal(size=(k, 3))
    n /= np.linalg.norm(n, axis=1)[:, None]
    for law, coeffs in [("rough", (0.9, 0.3)), ("walton", (0.8, 0.2, 0.5)), ("jz", (0.1, 0.3, 0.2, 0.25))]:
        ref = [core.collide(law, coeffs, core.Body(v=tuple(v1[i]), w=tuple(w1[i]), q=0.4),
                            core.Body(v=tuple(v2[i]), w=tuple(w2[i]), q=0.4), n[i]) for i in range(k)]
        b = [x.copy() for x in (v1, w1, v2, w2)]
        dE = core.collide_batch(law, coeffs, *b, n, q=0.4, want_dE=True)
        for i, c in enumerate(ref):
            for got, want in zip((b[0][i], b[1][i], b[2][i], b[3][i]), (c.v1, c.w1, c.v2, c.w2)):
                assert np.array_equal(got, want)
            assert dE[i] == c.dE
    with pytest.raises(ValueError):
        core.collide_batch("rough", (1.5, 0.0), *(x.copy() for x in (v1, w1, v2, w2)), n)


@pytest.mark.parametrize("dim", [2, 3])
def test_normals_cover_the_approaching_hemisphere_weighted_by_the_normal_speed(dim):
    rng = np.random.default_rng(5)
    g = rng.normal(size=(200000, 3))
    if dim == 2:
        g[:, 2] = 0.0
    n = dsmc.sample_normals(g, dim, rng)
    assert np.allclose(np.linalg.norm(n, axis=1), 1.0, atol=1e-12)
    if dim == 2:
        assert np.all(n[:, 2] == 0.0)
    c = -np.einsum("ij,ij->i", g, n) / np.linalg.norm(g, axis=1)    # cos of the angle to -g
    assert np.all(c >= 0.0)
    # density proportional to cos on the half circle / hemisphere:
    # 2D <cos> = pi/4, <cos^2> = 2/3; 3D <cos> = 2/3, <cos^2> = 1/2
    m1, m2 = (math.pi / 4, 2 / 3) if dim == 2 else (2 / 3, 0.5)
    se = 1 / math.sqrt(len(c))
    assert abs(c.mean() - m1) < 5 * c.std() * se
    assert abs((c * c).mean() - m2) < 5 * (c * c).std() * se


@pytest.mark.parametrize("dim", [2, 3])
def test_elastic_limits_conserve_energy(dim):
    drot = 1 if dim == 2 else 3
    # smooth and elastic: energy conserved, no spin, the Maxwellian stays a Maxwellian
    o = dsmc.run(1.0, -1.0, dim, 0.05, [0.0, 10.0], N=20000, seed=1)
    assert o["Ttr"][-1] == pytest.approx(1.0, rel=1e-12)
    assert o["Trot"][-1] == 0.0
    assert abs(o["a2_v"][-1]) < 0.04
    assert o["collisions"][-1] > 2.0
    # rough and elastic: energy conserved, equipartition
    o = dsmc.run(1.0, 1.0, dim, 0.05, [0.0, 5.0, 60.0 if dim == 2 else 20.0], N=20000, seed=2)
    E = dim * o["Ttr"] + drot * o["Trot"]
    assert E == pytest.approx(np.full(3, dim * 1.0), rel=1e-12)
    assert o["R"][-1] == pytest.approx(1.0, abs=0.03)
    v, w = o["state"]
    assert np.abs(v.sum(axis=0)).max() < 1e-9    # momentum conserved (started at 0)


@pytest.mark.parametrize("dim,phi,T", [(2, 0.05, 1.0), (2, 0.25, 0.25), (3, 0.05, 1.0), (3, 0.2, 0.25)])
def test_collision_frequency_of_a_maxwellian_is_enskogs(dim, phi, T):
    N = 40000
    nu = cooling.collision_frequency(T, phi, 0.5, 1.0, dim)
    t = 4.0 / nu    # ~4 collisions per particle
    o = dsmc.run(1.0, -1.0, dim, phi, [0.0, t], N=N, T0=T, seed=3)
    ncoll = o["collisions"][-1] * N / 2
    measured = o["collisions"][-1] / t
    assert abs(measured / nu - 1) < 4 / math.sqrt(ncoll), (measured, nu)


@pytest.mark.parametrize("dim,beta,Trot0", [(2, 0.0, 0.6), (2, 0.5, 0.0), (3, 0.0, 0.6), (3, 0.5, 0.0)])
def test_initial_rates_equal_the_mean_field_equations(dim, beta, Trot0):
    """From a Maxwellian (spins Maxwellian at Trot0) the changes over a fifth of a collision
    time equal those of cooling.py's ODE, within 4 standard errors of 6 independent runs."""
    r, phi = 0.9, 0.05
    t1 = 0.2 / cooling.collision_frequency(1.0, phi, 0.5, 1.0, dim)
    d = dsmc.ensemble(r, beta, dim, phi, [0.0, t1], runs=6, N=100000, Trot0=Trot0, seed=17)
    Ttr, Trot = dsmc.meanfield(r, beta, dim, phi, [0.0, t1], Trot0=Trot0)
    for key, mf in (("Ttr", Ttr), ("Trot", Trot)):
        change, se = d[key][0][1] - d[key][0][0], d[key][1][1]
        assert abs(change - (mf[1] - mf[0])) < 4 * se + 1e-12, (key, change, mf[1] - mf[0], se)
        assert se < 0.03 * abs(mf[1] - mf[0])    # the test resolves the rate to a few %
