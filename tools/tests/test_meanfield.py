# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Driven 2D mean-field theory of Herbst et al. 2005, models A-E (granfric.meanfield): limits,
small-mu scaling (doc/conventions.rst, correction 7), steady states, relaxation rates, the
coefficients' defining averages by quadrature, and <dE> per collision against Monte Carlo through
the C++ Walton law."""
import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from granfric import cooling, core
from granfric import meanfield as mf

MU_SMALL = np.logspace(-4, -2, 9)


# ------------------------------------------------------------------------------------------------
# mu -> inf: every model is model A
# ------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("r,rt,q", [(0.9, 0.4, 0.4), (0.95, 1.0, 0.5), (0.7, -0.6, 0.4)])
def test_mu_inf_reduces_every_model_to_model_A(r, rt, q):
    A = mf.coefficients("A", r, rt, math.inf, q)
    # model A is the constant-rt theory of granfric.cooling (B = B')
    ref = cooling.coefficients(r, rt, q, 2)
    assert A.as_tuple() == pytest.approx((ref.A, ref.B, ref.B, ref.C), rel=1e-14)
    for model in "BCDE":
        for R in ([None] if model in "BD" else [0.0, 0.3, 2.0, 50.0]):
            c = mf.coefficients(model, r, rt, math.inf, q, R)
            assert c.as_tuple() == pytest.approx(A.as_tuple(), rel=1e-14, abs=1e-16), (model, R)
        assert mf.steady_state(model, r, rt, math.inf, q) == \
            pytest.approx(mf.steady_state("A", r, rt, math.inf, q), rel=1e-12)
    # 3D model E at mu = inf is Luding's constant-rt theory
    for R in (0.0, 0.8):
        c3 = mf.coefficients_3d("E", r, rt, math.inf, q, R)
        ref3 = cooling.coefficients(r, rt, q, 3)
        assert c3.as_tuple() == pytest.approx((ref3.A, ref3.B, ref3.B, ref3.C), rel=1e-14)


def test_model_A_ignores_mu_and_smooth_limits():
    a = mf.coefficients("A", 0.9, 0.4, 0.3, 0.4).as_tuple()
    assert a == mf.coefficients("A", 0.9, 0.4, math.inf, 0.4).as_tuple()
    # mu = 0 or rt_max = -1: smooth particles, only normal dissipation
    for model in "ABCDE":
        for mu, rt in ((0.0, 0.4), (0.5, -1.0)):
            c = mf.coefficients(model, 0.9, rt, mu, 0.4, 0.5)
            assert c.as_tuple() == (pytest.approx((1 - 0.81) / 4), 0.0, 0.0, 0.0)
            assert mf.steady_state(model, 0.9, rt, mu, 0.4) == (0.0, pytest.approx(1.0))


# ------------------------------------------------------------------------------------------------
# large and small mu
# ------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("r,rt,q", [(0.95, 0.4, 0.4), (0.99, 1.0, 0.4), (0.95, 1.0, 0.5)])
def test_model_E_approaches_model_A_at_large_mu(r, rt, q):
    RA, TA = mf.steady_state("A", r, rt, math.inf, q)
    dev = []
    for mu in (1e1, 1e2, 1e3, 1e4):
        RE, TE = mf.steady_state("E", r, rt, mu, q)
        dev.append(max(abs(RE / RA - 1), abs(TE / TA - 1)))
        cE = mf.coefficients("E", r, rt, mu, q, RE)
        cA = mf.coefficients("A", r, rt, mu, q)
        assert cE.as_tuple() == pytest.approx(cA.as_tuple(), rel=30 / mu)
    # corrections are O(c^2) = O(mu^-2): a factor ~100 per decade
    assert dev[-1] < 1e-7
    for d0, d1 in zip(dev, dev[1:]):
        assert d1 < d0 / 50


@pytest.mark.parametrize("r,rt", [(0.95, 0.4), (0.99, 1.0)])
def test_small_mu_scaling_of_R(r, rt):
    """Correction 7 of doc/conventions.rst over mu in [1e-4, 1e-2] (q = 2/5):
    E ~ (1+r) mu; B, C ~ mu|ln mu|; D ~ (1+r) mu/|ln mu|.
    Leading behaviour: fitted exponent p of |ln mu| in R/mu = const |ln mu|^p (log-log fit of R/mu
    against |ln mu|): E 0 +- 0.05, B and C +1 +- 0.2, D -1 +- 0.5 (the logarithmic corrections
    are O(1/|ln mu|) ~ 0.1-0.2 here, larger for D whose next term is (1+rt_max)/(1+q)/ln(2c)).
    Ratios to the asymptotic forms (with the constant inside the logarithm, L = ln 2c):
    E: R/((1+r) mu); B, C: R/((1+r) mu L/2); D: R (L - (1+rt_max)/(1+q))/((1+r) mu) -> 1, within
    0.5 % at mu = 1e-4 and 15 % on the whole range, approaching 1 monotonically as mu -> 0."""
    q = 0.4
    L = np.abs(np.log(MU_SMALL))
    R = {m: np.array([mf.steady_state(m, r, rt, mu, q)[0] for mu in MU_SMALL]) for m in "BCDE"}
    p = {m: np.polyfit(np.log(L), np.log(R[m] / MU_SMALL), 1)[0] for m in R}
    assert abs(p["E"]) < 0.05, p
    assert abs(p["B"] - 1) < 0.2 and abs(p["C"] - 1) < 0.2, p
    assert abs(p["D"] + 1) < 0.5, p
    # model E is linear: log-log slope 1 and R/((1+r) mu) -> 1
    assert np.polyfit(np.log(MU_SMALL), np.log(R["E"]), 1)[0] == pytest.approx(1.0, abs=0.01)
    L2 = np.array([math.log(2 * mf.walton(r, rt, mu, q).c) for mu in MU_SMALL])
    ratios = {"E": R["E"] / ((1 + r) * MU_SMALL),
              "B": R["B"] / ((1 + r) * MU_SMALL * L2 / 2),
              "C": R["C"] / ((1 + r) * MU_SMALL * L2 / 2),
              "D": R["D"] * (L2 - (1 + rt) / (1 + q)) / ((1 + r) * MU_SMALL)}
    for m, x in ratios.items():
        d = np.abs(x - 1)
        assert d[0] < 5e-3 and np.all(d < 0.15), (m, x)
        assert np.all(np.diff(d) > 0), (m, x)       # closer to 1 the smaller mu
    # and they are different laws: at mu = 1e-4, B/C exceed E by ~|ln mu|/2, D is below E
    assert R["B"][0] / R["E"][0] > 3 and R["C"][0] / R["E"][0] > 3 and R["D"][0] / R["E"][0] < 0.2


# ------------------------------------------------------------------------------------------------
# steady state
# ------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("q", [0.4, 0.5])
def test_model_A_R_closed_form(q):
    for rt in np.linspace(-0.9, 1.0, 9):
        R, T = mf.steady_state("A", 0.95, rt, math.inf, q)
        e0 = mf.eta(rt, q)
        assert R == pytest.approx(q * e0 / (q - e0), rel=1e-14)     # eq 39
        if q == 0.4:  # the paper's spheres: R = 2(1 + rt_max)/(9 - 5 rt_max)
            assert R == pytest.approx(2 * (1 + rt) / (9 - 5 * rt), rel=1e-13)
        # root of dT_rot/dt = 0, found without the closed form
        c = mf.coefficients("A", 0.95, rt, math.inf, q)
        root = brentq(lambda x: c.Bprime - c.C * x, 0.0, 100.0, xtol=1e-15)
        assert R == pytest.approx(root, rel=1e-12)
        # eq 40 (correction 2): I = A_r + eta0(1-eta0)/2 - eta0^3/(2(q-eta0)) = A - B R
        I = mf.I_model_A(0.95, rt, q)
        assert c.A - c.B * R == pytest.approx(I, rel=1e-12)
        assert T == pytest.approx(((1 - 0.95 ** 2) / 4 / I) ** (2 / 3), rel=1e-12)
        # mu -> inf of model E
        assert mf.steady_state("E", 0.95, rt, 1e7, q)[0] == pytest.approx(R, rel=1e-9)
    # with the misprinted minus sign eq 40 would not be the dissipation factor
    e0 = mf.eta(0.4, q)
    wrong = 0.0975 / 4 - e0 * (1 - e0) / 2 - e0 ** 3 / (2 * (q - e0))
    assert abs(wrong - mf.I_model_A(0.95, 0.4, q)) > 0.1
    # elastic rough limit: equipartition, and T_tr equals the smooth value (no tangential loss)
    assert mf.steady_state("A", 1.0, 1.0, math.inf, q)[0] == pytest.approx(1.0, rel=1e-14)
    assert mf.steady_state("A", 0.95, 1.0, math.inf, q) == pytest.approx((1.0, 1.0), rel=1e-12)


def test_steady_state_is_reached_by_the_ode():
    nu, H = 0.1, 1.0
    for model in "ABCDE":
        Ts, Trs = mf.steady_state_temperatures(model, 0.95, 0.4, 0.3, 0.4, nu, H_dr=H)
        G = mf.time_scale_G(nu)
        t_relax = 1.0 / (G * math.sqrt(Ts))
        _, Ttr, Trot = mf.integrate(model, 0.95, 0.4, 0.3, 0.4, nu, H_dr=H, T0=(3 * Ts, 0.0),
                                    times=[0.0, 600 * t_relax])
        assert Ttr[-1] == pytest.approx(Ts, rel=1e-7) and Trot[-1] == pytest.approx(Trs, rel=1e-7)
        rhs = mf.rhs(0.0, (Ts, Trs), model, 0.95, 0.4, 0.3, 0.4, G, H)
        assert np.all(np.abs(rhs) < 1e-12 * H)


def test_model_E_steady_state_unique_over_grid():
    n = 0
    for r in (0.95, 0.99):
        for rt in (0.4, 1.0):
            for q in (0.4, 0.5):
                RA = mf.R_model_A(r, rt, q)
                prev = 0.0
                for mu in np.logspace(-3, 3, 13):
                    R, T = mf.steady_state("E", r, rt, mu, q, check_unique=True)
                    assert 0.0 < R < RA and T > 0
                    assert R > prev          # friction feeds the spins monotonically
                    prev = R
                    # independent scan beyond the bracket: B' - C R changes sign exactly once
                    grid = np.concatenate([np.linspace(0, 10 * RA, 300), RA * np.logspace(-9, 1, 300)])
                    F = [mf.coefficients("E", r, rt, mu, q, g).F_rot(g) for g in np.sort(grid)]
                    s = np.sign(F)
                    assert np.count_nonzero(s[1:] != s[:-1]) == 1
                    c = mf.coefficients("E", r, rt, mu, q, R)
                    assert abs(c.F_rot(R)) < 1e-13
                    n += 1
    assert n == 104


def test_model_E_translational_temperature_is_nonmonotonic_for_rt_max_1():
    # Fig. 6(b): T_tr^stat/T_tr^stat(mu=0) is 1 at mu -> 0 and mu -> inf, lower in between
    # (r = 0.99: A_r = 0.005, so the small-mu deviation 1 - T ~ mu/A_r is visible down to 1e-5)
    T = [mf.steady_state("E", 0.99, 1.0, mu, 0.4)[1] for mu in np.logspace(-6, 4, 21)]
    assert T[0] == pytest.approx(1.0, abs=2e-4) and T[-1] == pytest.approx(1.0, abs=1e-6)
    assert min(T) < 0.3 and 0 < int(np.argmin(T)) < len(T) - 1


# ------------------------------------------------------------------------------------------------
# energy conservation
# ------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("q", [0.4, 0.5])
def test_elastic_perfectly_rough_conserves_energy(q):
    for model in "ABCDE":
        c = mf.coefficients(model, 1.0, 1.0, math.inf, q, 0.7)
        assert c.A == pytest.approx(c.B, rel=1e-14) and c.B == pytest.approx(c.Bprime, rel=1e-14)
        assert c.Bprime == pytest.approx(c.C, rel=1e-14)
    # E = T_tr + T_rot/2 per particle is conserved without driving, and R -> 1
    t, Ttr, Trot = mf.integrate("E", 1.0, 1.0, math.inf, q, 0.1, T0=(1.0, 0.0),
                                times=[0, 5, 50, 500])
    assert Ttr + Trot / 2 == pytest.approx(np.ones(4), rel=1e-9)
    assert Trot[-1] / Ttr[-1] == pytest.approx(1.0, rel=1e-8)
    # with finite friction sliding contacts dissipate even at r = rt_max = 1
    c = mf.coefficients("E", 1.0, 1.0, 0.3, q, 0.7)
    assert c.A - c.Bprime > 0 or c.C - c.B > 0
    assert -c.A + c.B * 0.7 + 0.5 * (c.Bprime - c.C * 0.7) * 2 < 0


# ------------------------------------------------------------------------------------------------
# relaxation
# ------------------------------------------------------------------------------------------------
def test_relaxation_rates_negative_and_model_A_equals_jacobian():
    for model in "ABCDE":
        for r, rt, mu, q in [(0.95, 0.4, 0.5, 0.4), (0.99, 1.0, 0.05, 0.5), (0.9, -0.5, 3.0, 0.4)]:
            ev = mf.relaxation_rates(model, r, rt, mu, q)
            assert np.all(np.real(ev) < 0), (model, ev)
            if model in "ABD":   # eq 43 against the Jacobian of eq 13
                assert mf.jacobian_eigenvalues(model, r, rt, mu, q) == pytest.approx(ev, rel=1e-7)
    for rt in np.linspace(-0.95, 1.0, 14):
        ev = mf.relaxation_rates("A", 0.95, rt, math.inf, 0.4)
        assert mf.jacobian_eigenvalues("A", 0.95, rt, math.inf, 0.4) == pytest.approx(ev, rel=1e-7)
    # Fig. 10 (r = 0.95, q = 2/5): smooth limit has one vanishing rate; the rates nearly cross
    # near rt_max = -0.84; perfectly rough: the fast rate is ~14 times the slow one
    assert mf.relaxation_rates("A", 0.95, -1.0, math.inf, 0.4)[0] == 0.0
    rts = np.linspace(-0.95, -0.7, 51)
    gaps = [np.ptp(mf.relaxation_rates("A", 0.95, x, math.inf, 0.4)) for x in rts]
    assert rts[int(np.argmin(gaps))] == pytest.approx(-0.84, abs=0.02)
    slow, fast = mf.relaxation_rates("A", 0.95, 1.0, math.inf, 0.4)
    assert 13 < fast / slow < 15


def test_relaxation_rate_units_from_the_ode():
    """The slow rate (units G (T_tr^stat)^1/2, eq 43 with correction 4) is the late decay rate of
    a small perturbation of the full nonlinear model-E dynamics."""
    nu, H = 0.1, 1.0
    model, args = "E", (0.95, 0.4, 0.5, 0.4)
    Ts, Trs = mf.steady_state_temperatures(model, *args, nu, H_dr=H)
    slow, fast = mf.relaxation_rates(model, *args, nu=nu, H_dr=H)
    t = np.linspace(0, 12 / abs(slow), 7)
    _, Ttr, _ = mf.integrate(model, *args, nu, H_dr=H, T0=(1.001 * Ts, 0.999 * Trs), times=t)
    dev = np.log(np.abs(Ttr - Ts))
    assert np.polyfit(t[3:], dev[3:], 1)[0] == pytest.approx(slow, rel=2e-3)
    G = mf.time_scale_G(nu)
    assert (slow, fast) == pytest.approx(tuple(mf.relaxation_rates(model, *args) * G * math.sqrt(Ts)))


# ------------------------------------------------------------------------------------------------
# the coefficients' defining averages
# ------------------------------------------------------------------------------------------------
def test_model_C_mean_rt_is_the_average_over_eq_12_and_eq_26_log_identity():
    r, rt, mu, q = 0.9, 0.6, 0.3, 0.4
    w = mf.walton(r, rt, mu, q)
    g0 = math.pi - math.atan(1 / w.c)       # cot gamma0 = -c

    def rt_of(g):
        return min(-1 - (q + 1) / q * mu * (1 + r) / math.tan(g), rt)     # eqs 5-6

    for R in (0.0, 0.5, 2.0):
        x2 = 1 + R / q
        P = lambda g: -x2 * math.cos(g) / (1 + (x2 - 1) * math.cos(g) ** 2) ** 1.5    # eq 12
        avg = sum(quad(lambda g: P(g) * rt_of(g), a, b, epsabs=1e-13)[0]
                  for a, b in ((math.pi / 2, g0), (g0, math.pi)))
        assert mf.mean_rt_C(w, R) == pytest.approx(avg, rel=1e-9)
        if R > 0:   # correction 6: the printed long logarithm is 4 ln(xc + f~)
            x = math.sqrt(x2)
            assert mf.eq26_long_log(w.c, R, q) == pytest.approx(
                4 * math.log(x * w.c + math.sqrt(1 + x2 * w.c ** 2)), rel=1e-10)
    assert mf.mean_rt_C(w, 0.0) == pytest.approx(mf.mean_rt_B(w), rel=1e-14)   # eq 23


def test_model_D_coefficients_by_quadrature():
    """Model D: eta = eta(gamma12) (angle of v12, not of g) inserted into the exact collision map.
    Flux-weighted averages over the v12 angle phi (weight |cos phi|; spins averaged exactly):
    A = A_r + <eta u_t^2>/2 - <eta^2 u_t^2>/2, B = <eta^2>/(2q), B' = <eta^2 u_t^2>/(2q),
    C = <eta>/(2q) - <eta^2>/(2q^2) (u_t in units of sqrt(2 T_tr/m)). Fails with the misprinted
    A* = eta0 c^2/2 - q B* (correction 3)."""
    r, rt, mu, q = 0.9, 0.6, 0.3, 0.4
    w = mf.walton(r, rt, mu, q)

    def e(phi):
        cot = abs(math.cos(phi) / math.sin(phi))
        return w.eta0 if cot >= w.c else w.eta0_over_c * cot

    def avg(h, rho_power):
        fac = 0.25 if rho_power == 0 else 0.75
        return fac * 4 * quad(lambda p: math.cos(p) * h(p), 0, math.pi / 2, epsabs=1e-13,
                              limit=200, points=[math.atan(1 / w.c)])[0]

    e_ut2 = avg(lambda p: e(p) * math.sin(p) ** 2, 2)
    e2_ut2 = avg(lambda p: e(p) ** 2 * math.sin(p) ** 2, 2)
    e_m, e2_m = avg(e, 0), avg(lambda p: e(p) ** 2, 0)
    assert e_m == pytest.approx(mf.eta1(w), rel=1e-9)             # <eta> = eta1 (eq 25)
    quadr = (w.A_r + e_ut2 / 2 - e2_ut2 / 2, e2_m / (2 * q), e2_ut2 / (2 * q),
             e_m / (2 * q) - e2_m / (2 * q * q))
    assert mf.coefficients("D", r, rt, mu, q).as_tuple() == pytest.approx(quadr, rel=1e-9)


def test_model_E_coefficients_match_the_appendix():
    # eqs 33-34 against A19 and A22 (2D), and the 3D coefficients against A23 (corrected), A24
    for r, rt, mu, q in [(0.9, 0.6, 0.3, 0.4), (0.99, 1.0, 0.02, 0.5), (0.7, -0.5, 5.0, 0.4)]:
        for R in (0.0, 0.3, 1.5, 20.0):
            c = mf.coefficients("E", r, rt, mu, q, R)
            P_tr, P_rot = mf.appendix_A19_A22(r, rt, mu, q, R)
            assert c.F_tr(R) == pytest.approx(-P_tr, rel=1e-12)
            assert c.F_rot(R) == pytest.approx(P_rot, rel=1e-10, abs=1e-15)
            c3 = mf.coefficients_3d("E", r, rt, mu, q, R)
            P_tr, P_rot = mf.appendix_A23_A24(r, rt, mu, q, R)
            assert c3.F_tr(R) == pytest.approx(-P_tr, rel=1e-12)
            assert c3.F_rot(R) == pytest.approx(P_rot, rel=1e-12, abs=1e-15)


def _mc_energy_changes(r, rt, mu, q, Ttr, Trot, dim, n, seed):
    """<dE_tr>, <dE_rot> per collision through the C++ Walton law (Monte Carlo in the core:
    Gaussian velocities at T_tr, Maxwellian spins at T_rot, collisions weighted by |g_n|), as
    ((mean, s.e.), (mean, s.e.))."""
    mc = core.mean_energy_changes("walton", (r, mu, rt), q, dim, Ttr, Trot, n=n, seed=seed)
    return [(mc["tr"], mc["tr_se"]), (mc["rot"], mc["rot_se"])]


@pytest.mark.parametrize("dim,r,rt,mu,q,Ttr,Trot", [
    (2, 0.95, 1.0, 0.1, 0.5, 1.0, 0.3),
    (2, 0.9, 0.6, 0.3, 0.4, 1.0, 0.8),
    (3, 0.95, 1.0, 0.1, 0.5, 1.0, 0.3),      # A23 with correction 5
])
def test_model_E_mean_energy_changes_against_monte_carlo_through_the_cpp_law(dim, r, rt, mu, q,
                                                                              Ttr, Trot):
    """Model E is exact in the Gaussian/molecular-chaos approximation: <dE_tr> = 4(-A T_tr +
    B T_rot) and <dE_rot> = 4(B' T_tr - C T_rot) agree with Monte Carlo through the C++ law within
    4 standard errors. (Models A-D are approximations; for the first case all of them are off by
    many standard errors, so the comparison has power.)"""
    mc = _mc_energy_changes(r, rt, mu, q, Ttr, Trot, dim, 20000, 11 + dim)
    th = mf.mean_energy_changes("E", r, rt, mu, q, Ttr, Trot, dim)
    for (mean, sem), t in zip(mc, th):
        assert abs(mean - t) < 4 * sem, (mean, t, sem)
    if dim == 2 and q == 0.5:
        for model in "ABCD":
            other = mf.mean_energy_changes(model, r, rt, mu, q, Ttr, Trot, dim)
            assert max(abs(o - mc_[0]) / mc_[1] for o, mc_ in zip(other, mc)) > 6, model


# ------------------------------------------------------------------------------------------------
# homogeneous cooling, 2D and 3D model E
# ------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("dim", [2, 3])
def test_cooling_asymptotic_R_model_E(dim):
    r, rt, q = 0.9, 0.4, 0.4
    assert mf.cooling_asymptotic_R("E", r, rt, math.inf, q, dim) == \
        pytest.approx(cooling.asymptotic_R(r, rt, q, dim), rel=1e-12)
    assert mf.cooling_asymptotic_R("A", r, rt, 0.3, q, dim) == \
        pytest.approx(cooling.asymptotic_R(r, rt, q, dim), rel=1e-12)
    prev = 0.0
    for mu in (0.2, 0.5, 1.0, 10.0):
        R = mf.cooling_asymptotic_R("E", r, rt, mu, q, dim)
        assert prev < R < cooling.asymptotic_R(r, rt, q, dim)
        prev = R
        assert mf.cooling_dR("E", r, rt, mu, q, R, dim) == pytest.approx(0.0, abs=1e-13)
        _, Ttr, Trot = mf.integrate("E", r, rt, mu, q, 0.05, T0=(1.0, 0.0), times=[0, 1e9], dim=dim)
        assert Trot[-1] / Ttr[-1] == pytest.approx(R, rel=1e-6)
    # weak friction: the spins decouple, rotational energy survives and R grows without bound
    assert mf.cooling_asymptotic_R("E", r, rt, 1e-2, q, dim) == math.inf
    _, Ttr, Trot = mf.integrate("E", r, rt, 1e-2, q, 0.05, T0=(1.0, 1.0), times=[0, 1e2, 1e4], dim=dim)
    assert Trot[-1] / Ttr[-1] > 10 * Trot[1] / Ttr[1]


def test_3d_model_E_a23_correction_matters():
    # the misprinted A23 (eta0/2 instead of eta0 (1 - eta0 x^2) as first term) breaks mu -> inf
    r, rt, q, R = 0.9, 0.4, 0.4, 0.5
    e0, x2 = mf.eta(rt, q), 1 + R / q
    P_tr = mf.appendix_A23_A24(r, rt, 1e9, q, R)[0]
    ref = cooling.coefficients(r, rt, q, 3)
    assert -P_tr == pytest.approx(-ref.A + ref.B * R, rel=1e-12)
    misprint = P_tr - e0 * (1 - e0 * x2) / 2      # eta0/2 (1 - eta0 x^2)/(1 + x^2 cot^2 gamma0)
    assert abs(misprint / P_tr - 1) > 0.2
