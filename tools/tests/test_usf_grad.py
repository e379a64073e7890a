# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Grad's theory of uniform shear flow (granfric.usf_grad): its collision integrals, evaluated by
Monte Carlo with the core's collision map, against closed forms that were derived without it:
the cooling and the stress relaxation rate of smooth particles, and for rough particles the
steady T_rot/T_tr and translational cooling of the mean-field model of cooling.py (the same
Maxwellian assumption); the steady state satisfies the energy balance."""
import math

from granfric import cooling, usf_grad


def test_smooth_rates_are_the_closed_forms():
    for dim in (2, 3):
        for r in (0.95, 0.6):
            g = usf_grad.grad("rough", (r, -1.0), dim, samples=1_000_000, seed=3)
            lam, nu_eta = usf_grad.smooth_rates(r, dim)
            assert g["R"] == 0.0
            # (Monte Carlo errors of 1e6 samples: 0.3 % and 0.7 %, standard deviations of 6 seeds)
            assert abs(g["lam"] / lam - 1.0) < 0.015, (dim, r, g["lam"], lam)
            assert abs(g["nu_eta"] / nu_eta - 1.0) < 0.03, (dim, r, g["nu_eta"], nu_eta)


def test_rough_spins_and_cooling_are_the_mean_field():
    for dim in (2, 3):
        for r, beta in ((0.9, 0.0), (0.7, 0.5)):
            q = 0.5 if dim == 2 else 0.4
            g = usf_grad.grad("rough", (r, beta), dim, samples=1_000_000, seed=4)
            c = cooling.coefficients(r, beta, q, dim)
            R = c.B / c.C    # (dT_rot/dt = 0)
            lam = 2.0 * c.scale * (-c.A + c.B * R)    # (dT_tr/dt / (nu T_tr), nu = G T^1/2 / 2)
            assert abs(g["R"] / R - 1.0) < 0.02, (dim, r, beta, g["R"], R)
            assert abs(g["lam"] / lam - 1.0) < 0.02, (dim, r, beta, g["lam"], lam)


def test_steady_state_balances_the_energy():
    g = usf_grad.grad("walton", (0.8, 0.4, 0.3), 3, samples=500_000, seed=5)
    P = g["P_star"]
    # the shear's work, -a P_xy, is what the collisions take from the translational motion
    assert math.isclose(-2.0 * g["a_star"] * P[0, 1], -3.0 * g["lam"], rel_tol=1e-12)
    assert math.isclose(P[0, 0] + P[1, 1] + P[2, 2], 3.0, rel_tol=1e-12)
    assert P[0, 0] > 1.0 > P[1, 1] > 0.0 > P[0, 1]
    assert 0.0 < g["R"] < 10.0
