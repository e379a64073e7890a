# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Homogeneous-cooling theory (granfric.cooling): limits that follow from conservation laws, and
the per-collision averages against Monte Carlo through the C++ collision law."""
import math

import numpy as np
import pytest

from granfric import cooling, core


@pytest.mark.parametrize("dim,q", [(2, 0.5), (2, 0.4), (3, 0.4), (3, 0.3)])
def test_elastic_rough_conserves_energy_and_equipartitions(dim, q):
    # r = 1, beta = 1: no dissipation, R -> 1
    c = cooling.coefficients(1.0, 1.0, q, dim)
    assert c.A == pytest.approx(c.B, rel=1e-14) and c.B == pytest.approx(c.C, rel=1e-14)
    assert cooling.asymptotic_R(1.0, 1.0, q, dim) == pytest.approx(1.0, rel=1e-12)
    t, Ttr, Trot = cooling.integrate(1.0, 1.0, q, dim, 0.05, T0=(1.0, 0.0), times=[0, 50, 500])
    ndof_rot = 1 if dim == 2 else 3
    E = dim * Ttr + ndof_rot * Trot
    assert E == pytest.approx(np.full(3, dim * 1.0), rel=1e-9)
    assert Trot[-1] / Ttr[-1] == pytest.approx(1.0, rel=1e-6)


@pytest.mark.parametrize("dim", [2, 3])
def test_smooth_particles_keep_no_spin_and_follow_haff(dim):
    r = 0.9
    assert cooling.asymptotic_R(r, -1.0, 0.4, dim) == 0.0
    t = np.array([0.0, 10.0, 100.0, 1000.0])
    _, Ttr, Trot = cooling.integrate(r, -1.0, 0.4, dim, 0.1, T0=(1.0, 0.0), times=t)
    assert np.all(Trot == 0.0)
    # Haff's law T = (1 + t/t0)^-2 with 1/t0 = scale G A / 2
    G = cooling.time_scale_G(0.1, 0.5, 1.0, dim)
    c = cooling.coefficients(r, -1.0, 0.4, dim)
    haff = (1 + 0.5 * c.scale * G * c.A * t) ** -2
    assert Ttr == pytest.approx(haff, rel=1e-6)


def test_collision_frequency_is_enskog():
    # 2D: nu = 2 sigma n g sqrt(pi T / m); 3D: nu = 4 sigma^2 n g sqrt(pi T / m)
    nu2 = cooling.collision_frequency(1.0, 0.05, 0.5, 1.0, 2)
    n2 = 0.05 / (math.pi * 0.25)
    assert nu2 == pytest.approx(2 * n2 * cooling.pair_correlation(0.05, 2) * math.sqrt(math.pi))
    nu3 = cooling.collision_frequency(1.0, 0.2, 0.5, 1.0, 3)
    n3 = 0.2 / (math.pi / 6)
    assert nu3 == pytest.approx(4 * n3 * cooling.pair_correlation(0.2, 3) * math.sqrt(math.pi))


def test_asymptotic_R_solves_the_stationarity_condition():
    for dim, q in [(2, 0.5), (3, 0.4)]:
        for beta in np.linspace(-0.9, 1.0, 8):
            R = cooling.asymptotic_R(0.9, beta, q, dim)
            c = cooling.coefficients(0.9, beta, q, dim)
            # dR/dt = 0: k (B - C R) - R (-A + B R) = 0
            assert c.k * (c.B - c.C * R) - R * (-c.A + c.B * R) == pytest.approx(0.0, abs=1e-12)
            _, Ttr, Trot = cooling.integrate(0.9, beta, q, dim, 0.05, T0=(1.0, R),
                                             times=[0, 200])
            assert Trot[-1] / Ttr[-1] == pytest.approx(R, rel=1e-8)


@pytest.mark.parametrize("dim,q,r,beta", [(2, 0.5, 0.9, 0.0), (3, 0.4, 0.8, 0.5), (2, 0.4, 0.95, -0.4)])
def test_mean_energy_changes_against_monte_carlo_through_the_cpp_law(dim, q, r, beta):
    """<dE_tr>, <dE_rot> per collision over Gaussian velocities and spins (weighted with the
    normal relative speed) through the C++ collision law, against the closed forms the theory
    is built from; within 4 standard errors."""
    Ttr, Trot = 1.0, 0.6
    e = cooling.eta(beta, q)
    mc = core.mean_energy_changes("rough", (r, beta), q, dim, Ttr, Trot, n=40000, seed=7 + dim)
    d = dim - 1
    th_tr = -(1 - r * r) * Ttr - 2 * d * e * (1 - e) * Ttr + 2 * d * e * e / q * Trot
    th_rot = 2 * d * (e * e / q * Ttr - e / q * (1 - e / q) * Trot)
    assert abs(mc["tr"] - th_tr) < 4 * mc["tr_se"], (mc, th_tr)
    assert abs(mc["rot"] - th_rot) < 4 * mc["rot_se"], (mc, th_rot)
