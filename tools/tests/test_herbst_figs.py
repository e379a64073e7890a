# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Theory behind the Herbst et al. 2005 figures (granfric.herbst_figs): rt(gamma) of the C++ Walton
law against eqs 5-6 (Fig. 2), the impact-angle distribution eq 12 against a Monte Carlo of
flux-weighted collisions (Fig. 3), R(mu -> inf) = 2(1+rt)/(9-5rt) against model A (Fig. 7), the
power-law fit of Fig. 9 and the slow-rate fit of Fig. 10 on synthetic data, and the figure and
report pipeline on synthetic runs made from model E (no LAMMPS; the simulated pipeline runs in
`tools/reproduce herbst2005 --quick`)."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from granfric import cooling
from granfric import herbst_figs as hf
from granfric import meanfield as mf

INF = math.inf


# ------------------------------------------------------------------------------------------------
# Fig. 2: the C++ Walton law is eqs 5-6
# ------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("r,rt_max", [(0.95, 0.4), (0.99, 1.0), (0.7, -0.5)])
def test_fig2_core_rt_equals_closed_form(r, rt_max):
    gam = np.linspace(0.5 * math.pi + 1e-3, math.pi - 1e-3, 41)
    for mu in (0.01, 0.1, 0.5, 3.0, INF):
        closed = hf.rt_walton(gam, r, mu, rt_max)
        reported, measured = hf.rt_core(gam, r, mu, rt_max)
        assert np.max(np.abs(measured - closed)) < 1e-12, mu
        assert np.max(np.abs(reported - closed)) < 1e-12, mu
        if mu != INF:
            # sliding (rt < rt_max) exactly below the stick/slide angle gamma0 of eq 22
            g0 = hf.gamma0(r, mu, rt_max)
            away = np.abs(gam - g0) > 1e-6
            assert np.all((closed < rt_max)[away] == (gam < g0)[away])
            assert hf.rt_walton(np.array([0.5 * math.pi]), r, mu, rt_max)[0] == pytest.approx(-1.0)


# ------------------------------------------------------------------------------------------------
# Fig. 3: eq 12
# ------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("R", [0.0, 0.1, 0.6, 3.0])
def test_eq12_is_normalised_and_its_cdf_and_sliding_fraction(R):
    assert quad(lambda g: hf.P_gamma(g, R), 0.5 * math.pi, math.pi)[0] == pytest.approx(1.0, abs=1e-10)
    for g in (1.7, 2.2, 2.9):
        assert hf.P_gamma_cdf(g, R) == pytest.approx(quad(lambda x: hf.P_gamma(x, R), 0.5 * math.pi, g)[0],
                                                     abs=1e-10)
    for r, mu, rt in ((0.95, 0.5, 0.4), (0.99, 0.05, 1.0)):
        g0 = hf.gamma0(r, mu, rt)
        assert hf.sliding_fraction(R, r, mu, rt) == pytest.approx(hf.P_gamma_cdf(g0, R), abs=1e-12)


def test_eq12_matches_monte_carlo_of_flux_weighted_collisions():
    """Gaussian velocities at T_tr = 1, spins at T_rot = R (I = q m a^2), contact normal n = x:
    collisions weighted by the approach speed -v12.n; gamma from g = v12 - a (w1 + w2) z x n."""
    rng = np.random.default_rng(7)
    n, a, R = 800000, 0.5, 0.6
    v12 = rng.normal(0.0, math.sqrt(2.0), (n, 2))
    wsum = rng.normal(0.0, math.sqrt(2.0 * R / (hf.Q * a * a)), n)
    gx, gy = v12[:, 0], v12[:, 1] - a * wsum
    ok = gx < 0
    w = -gx[ok]
    gam = np.arccos(gx[ok] / np.hypot(gx[ok], gy[ok]))
    edges = np.linspace(0.5 * math.pi, math.pi, 37)
    W, _ = np.histogram(gam, edges, weights=w)
    W2, _ = np.histogram(gam, edges, weights=w * w)
    width = edges[1] - edges[0]
    P, err = W / (w.sum() * width), np.sqrt(W2) / (w.sum() * width)
    chi2 = np.sum(((P - hf.P_gamma_binned(edges, R)) / err) ** 2) / len(P)
    assert chi2 < 2.0
    # and it is not eq 12 at R = 0 (the rotational part of g matters)
    assert np.sum(((P - hf.P_gamma_binned(edges, 0.0)) / err) ** 2) / len(P) > 50.0


# ------------------------------------------------------------------------------------------------
# Fig. 7: R(mu -> inf)
# ------------------------------------------------------------------------------------------------
def test_R_mu_inf_formula_is_model_A_eq39_for_spheres():
    for rt in np.linspace(-1.0, 1.0, 21):
        for r in (0.95, 0.99):
            ref = hf.R_inf(rt)
            assert mf.R_model_A(r, rt, 0.4) == pytest.approx(ref, rel=1e-13, abs=1e-15)
            for model in mf.MODELS:
                assert mf.steady_state(model, r, rt, INF, 0.4)[0] == pytest.approx(ref, rel=1e-12, abs=1e-15)
            assert mf.steady_state("E", r, rt, 1e6, 0.4)[0] == pytest.approx(ref, rel=1e-6, abs=1e-12)
    # the formula is eq 39 at q = 2/5 only (discs, q = 1/2, differ)
    assert abs(mf.R_model_A(0.95, 0.4, 0.5) - hf.R_inf(0.4)) > 0.03


# ------------------------------------------------------------------------------------------------
# Fig. 9: the power-law fit
# ------------------------------------------------------------------------------------------------
def test_power_law_fit_recovers_exponent_and_honest_errors():
    mu = np.array([0.003, 0.005, 0.01, 0.02, 0.03])
    f = hf.fit_power_law(mu, 1.9 * mu ** 1.07)
    assert f["delta"] == pytest.approx(1.07, abs=1e-12) and f["b"] == pytest.approx(1.9, rel=1e-12)
    rng = np.random.default_rng(3)
    pulls = []
    for _ in range(400):
        rel = rng.uniform(0.01, 0.05, len(mu))
        y = 0.8 * mu ** 0.93 * (1.0 + rel * rng.normal(size=len(mu)))
        g = hf.fit_power_law(mu, y, rel * 0.8 * mu ** 0.93)
        pulls.append((g["delta"] - 0.93) / g["delta_err"])
    pulls = np.array(pulls)
    assert abs(pulls.mean()) < 0.2
    # errors are inflated by sqrt(chi2/dof) when > 1, so the pulls are at most of unit width
    assert 0.6 < pulls.std() < 1.1
    # model E's R at small mu is linear (eq 42) but model C's is not (mu |ln mu|)
    RE = [mf.steady_state("E", 0.95, 1.0, m, 0.4)[0] for m in mu / 10]
    RC = [mf.steady_state("C", 0.95, 1.0, m, 0.4)[0] for m in mu / 10]
    assert hf.fit_power_law(mu / 10, RE)["delta"] == pytest.approx(1.0, abs=0.01)
    assert hf.fit_power_law(mu / 10, RC)["delta"] < 0.9


# ------------------------------------------------------------------------------------------------
# Fig. 10: the slow-rate fit on the model's own relaxation
# ------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("r,rt,mu", [(0.95, 1.0, INF), (0.95, 0.4, 0.5)])
def test_slow_rate_fit_recovers_model_E_rate(r, rt, mu):
    phi, H = 0.0866, 0.02
    t = np.arange(0.0, 1500.0, 1.0)
    _, Ttr, Trot = mf.integrate("E", r, rt, mu, 0.4, phi, H_dr=H, T0=(1.0, 0.0), times=t)
    rng = np.random.default_rng(1)
    Ttr = Ttr * (1 + 0.002 * rng.normal(size=len(t)))
    Trot = Trot * (1 + 0.002 * rng.normal(size=len(t)))
    Ts, Rs = mf.steady_state_temperatures("E", r, rt, mu, 0.4, phi, H_dr=H)
    lam, err, t0 = hf.fit_slow_rate(t, Ttr, Trot, Ts, Rs)
    G = cooling.time_scale_G(phi, 0.5, 1.0, 2)
    assert lam / (G * math.sqrt(Ts)) == pytest.approx(hf.rates("E", r, rt, mu)[0], rel=0.05)


# ------------------------------------------------------------------------------------------------
# the figure and report pipeline on synthetic runs (model E + noise)
# ------------------------------------------------------------------------------------------------
def _synthetic_runs(plan, rng, noise=0.003):
    runs = {}
    H = hf.H_dr(plan.fdr, plan.vdr, plan.N)
    for key in hf.run_keys(plan):
        phi, r, rt, mu = key
        t = np.arange(0.0, 400.0 + 1e-9, 1.0)
        _, Ttr, Trot = mf.integrate("E", r, rt, mu, 0.4, phi, H_dr=H, T0=(1.0, 0.0), times=t)
        Ttr = Ttr * (1 + noise * rng.normal(size=len(t)))
        Trot = Trot * (1 + noise * rng.normal(size=len(t)))
        s = {"Time": t, "Ttr": Ttr, "Trot": Trot, "R": np.where(Ttr > 0, Trot / Ttr, 0.0)}
        edges = np.linspace(0.5 * math.pi, math.pi, 37)
        R = float(s["R"][-1])
        P = hf.P_gamma_binned(edges, R) * (1 + noise * rng.normal(size=36))
        d = {"Time": t, "c_T[1]": Ttr, "c_T[2]": Trot, "c_T[3]": s["R"], "series": s,
             "gamma": (0.5 * (edges[1:] + edges[:-1]), P)}
        run = hf.Run(r, rt, mu, phi, plan.N, t[-1], d, hf.steady_series(s), hf.T_smooth(r, phi, H),
                     hf.sliding_fraction(R, r, mu, rt) if rt > -1 else 0.0)
        run.ensemble = [s, s]
        runs[key] = run
    return runs


def test_figures_and_report_from_synthetic_runs(tmp_path):
    plan = hf.Plan("test", phi=0.0866, nside=40,
                   scans=[(0.95, 1.0, [0.005, 0.01, 0.02, 0.3, 1.0, 3.0, INF])],
                   rt_scan=(0.95, 0.5, [-1.0, 0.4, 1.0]), fig3a=[-1.0, 1.0],
                   fig3b=(0.95, 1.0, [0.01, INF]), fig11=(0.0866, 0.95, 1.0, [INF, 0.5]),
                   tmin=400, tmax=400, ntau=1, rate_cases=[(0.95, 1.0, INF)], rate_seeds=2)
    runs = _synthetic_runs(plan, np.random.default_rng(5))
    res = hf.make_figures(runs, plan, str(tmp_path))
    for name in hf.FIGS:
        assert (tmp_path / name).stat().st_size > 20000, name
    # Fig. 9: the fit returns model E's own exponent on model E's (slightly noisy) numbers
    row = res["fig9"][0]
    assert row["delta"] == pytest.approx(row["delta_E"], abs=0.02)
    # Fig. 3: eq 12 with the run's own R reproduces the synthetic histogram
    assert max(w["dev12"] for w in res["fig3"]) < 0.02
    # Fig. 11: model E against itself (noise only)
    assert max(w["dev_tr"] for w in res["fig11"]) < 0.02
    # Fig. 10: model A's rates at rt_max = 1 separate by the factor the paper quotes (~14)
    assert res["fig10"]["ratio_rt1"] == pytest.approx(14, abs=0.5)
    assert res["fig10"]["sim"][0]["lam"] == pytest.approx(res["fig10"]["sim"][0]["E"], rel=0.1)
    text = hf.report_section(res)
    for name in hf.FIGS:
        assert f"`{name}`" in text
    assert "| 0.95 | 1.0 | 0.005, 0.01, 0.02 |" in text and "| 0.99(4) |" in text
