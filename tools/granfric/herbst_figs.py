# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Figures 2, 3 and 5-11 of Herbst, Cafiero, Zippelius, Herrmann & Luding, Phys. Fluids 17,
107102 (2005): GRANFRIC simulations of the randomly driven monolayer (examples/driven, through
granfric.herbst.simulate) against the mean-field models A-E (granfric.meanfield), with the
equation corrections of doc/conventions.rst.

    fig2_rt_vs_gamma.png      rt(gamma) of the Walton law: the C++ law (core.collide) vs eqs 5-6
    fig3_p_gamma.png          impact-angle distribution P(gamma): simulation vs eq 12
    fig5_rt_scan.png          T_tr, T_rot, R against rt_max at mu = 0.5
    fig6_ttr_vs_mu.png        T_tr / T_tr(mu = 0) against mu
    fig7_R_vs_mu.png          R against mu
    fig8_one_minus_R.png      1 - R against 1/mu (rt_max = 1)
    fig9_R_small_mu.png       R against mu at small mu, power-law fit R = b mu^delta
    fig10_relaxation_rates.png  the two linear relaxation rates and their ratio
    fig11_evolution.png       T_tr, T_rot from an elastic smooth start against t/tau

Used by `tools/reproduce herbst2005` (granfric.herbst.main), which appends `report_section` to
report.md. Temperatures per degree of freedom; T_tr(mu = 0) is the mean-field steady value of
smooth particles, (H_dr/(G A_r))^2/3 with H_dr = f_dr m v_dr^2 (1 - 1/N).
"""
import math
import os
from dataclasses import dataclass, field

import numpy as np

from . import cli, cooling, core, herbst, lammpslog
from . import meanfield as mf

Q = 0.4                       # spheres
INF = math.inf
MODELS = ("A", "B", "C", "D", "E")
STYLE = {"A": dict(color="0.55", ls=":", lw=1.3), "B": dict(color="C2", ls="-.", lw=1.1),
         "C": dict(color="C4", ls=(0, (5, 1, 1, 1, 1, 1)), lw=1.0),
         "D": dict(color="C1", ls="--", lw=1.1), "E": dict(color="k", ls="-", lw=1.4)}
PAPER = {  # numbers stated in the text of Herbst et al. 2005
    "delta": {0.99: "1.00(4)", 0.95: "0.99(4)"},
    "fig10_equal_rt": -0.84, "fig10_ratio_rt1": 14.0, "fig6_min_mu": 0.4,
}


# ------------------------------------------------------------------------------------------------
# theory
# ------------------------------------------------------------------------------------------------
def rt_walton(gamma, r, mu, rt_max, q=Q):
    """Eqs 5-6: rt(gamma) = min(-1 - (1+q)/q mu (1+r) cot gamma, rt_max), gamma in (pi/2, pi]."""
    g = np.asarray(gamma, dtype=float)
    if mu == INF:
        return np.full_like(g, rt_max)
    with np.errstate(divide="ignore"):
        rt_c = -1.0 - (1.0 + q) / q * mu * (1.0 + r) / np.tan(g)
    return np.minimum(rt_c, rt_max)


def rt_core(gamma, r, mu, rt_max, q=Q):
    """rt(gamma) through the C++ Walton law (core.collide, the code path of pair hardsphere/walton):
    two equal spheres without spin whose contact-point velocity g makes the angle gamma with the
    normal n. Returns (rt the law reports, rt measured from the outcome, -g_t'.g_t/|g_t|^2)."""
    n = np.array([1.0, 0.0, 0.0])
    rep, meas = [], []
    for gm in np.atleast_1d(gamma):
        g = np.array([math.cos(gm), math.sin(gm), 0.0])
        c = core.collide("walton", (r, mu, rt_max), core.Body(v=tuple(0.5 * g), q=q),
                         core.Body(v=tuple(-0.5 * g), q=q), n)
        gp = c.v1 - c.v2 - np.cross(0.5 * c.w1 + 0.5 * c.w2, n)
        gt, gtp = g - g.dot(n) * n, gp - gp.dot(n) * n
        rep.append(c.rt)
        meas.append(-gtp.dot(gt) / gt.dot(gt))
    return np.array(rep), np.array(meas)


def gamma0(r, mu, rt_max, q=Q):
    """Stick/slide border: cot gamma0 = -c (eq 22); sliding for gamma < gamma0."""
    return 0.5 * math.pi + math.atan(mf.walton(r, rt_max, mu, q).c)


def P_gamma(gamma, R, q=Q):
    """Eq 12: P(gamma) = -(1 + R/q) cos gamma / (1 + (R/q) cos^2 gamma)^3/2 on (pi/2, pi]."""
    c = np.cos(np.asarray(gamma, dtype=float))
    return -(1.0 + R / q) * c / (1.0 + (R / q) * c * c) ** 1.5


def P_gamma_cdf(gamma, R, q=Q):
    """Integral of eq 12 from pi/2 to gamma: 1 - sin gamma / sqrt(x^2 - (x^2 - 1) sin^2 gamma),
    x^2 = 1 + R/q."""
    s = np.sin(np.asarray(gamma, dtype=float))
    x2 = 1.0 + R / q
    return 1.0 - s / np.sqrt(x2 - (x2 - 1.0) * s * s)


def P_gamma_binned(edges, R, q=Q):
    """Bin averages of eq 12 over the given bin edges."""
    F = P_gamma_cdf(edges, R, q)
    return np.diff(F) / np.diff(edges)


def sliding_fraction(R, r, mu, rt_max, q=Q):
    """Fraction of sliding collisions under eq 12: int_{pi/2}^{gamma0} P = 1 - 1/f~,
    f~ = sqrt(1 + x^2 c^2) (eq 28)."""
    c = mf.walton(r, rt_max, mu, q).c
    if c == INF:
        return 1.0
    return 1.0 - 1.0 / math.sqrt(1.0 + (1.0 + R / q) * c * c)


def R_inf(rt_max):
    """R(mu -> inf) = 2 (1 + rt_max)/(9 - 5 rt_max) (paper, Sec. V B 3): eq 39 of model A,
    q eta0/(q - eta0), at q = 2/5."""
    return 2.0 * (1.0 + rt_max) / (9.0 - 5.0 * rt_max)


def H_dr(fdr, vdr, N, m=1.0):
    """Driving power per particle (eq 9) with the kicks' momentum removal: f_dr m v_dr^2 (1 - 1/N)."""
    return fdr * m * vdr * vdr * (1.0 - 1.0 / N)


def T_smooth(r, phi, H, a=0.5, m=1.0):
    """Mean-field steady T_tr of smooth particles, (H/(G A_r))^2/3 (eq 37 with I = A_r)."""
    return (H / (cooling.time_scale_G(phi, a, m, 2) * (1.0 - r * r) / 4.0)) ** (2.0 / 3.0)


def fit_power_law(x, y, yerr=None):
    """Weighted least squares of ln y = ln b + delta ln x (sigma of ln y = yerr/y). The errors come
    from the covariance, scaled by sqrt(chi2/dof) when that exceeds 1 (and always without yerr).
    Returns dict(delta, delta_err, b, b_err, chi2_red, n)."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    if len(x) < 2 or np.any(x <= 0) or np.any(y <= 0):
        raise ValueError("need >= 2 points with x, y > 0")
    s = np.ones_like(y) if yerr is None else np.asarray(yerr, float) / y
    A = np.vstack([np.ones_like(x), np.log(x)]).T / s[:, None]
    rhs = np.log(y) / s
    p, *_ = np.linalg.lstsq(A, rhs, rcond=None)
    cov = np.linalg.inv(A.T @ A)
    dof = len(x) - 2
    chi2 = float(np.sum((A @ p - rhs) ** 2) / dof) if dof > 0 else float("nan")
    scale = 1.0
    if dof > 0 and (yerr is None or chi2 > 1.0):
        scale = chi2
    cov = cov * scale
    b = math.exp(p[0])
    return {"delta": float(p[1]), "delta_err": float(math.sqrt(cov[1, 1])), "b": b,
            "b_err": float(b * math.sqrt(cov[0, 0])), "chi2_red": chi2, "n": len(x)}


def fit_slow_rate(t, Ttr, Trot, Ts_tr, Ts_rot, threshold=0.25):
    """Slowest relaxation rate from the tail of a run that approaches its steady state: from the
    first time both |T/T_s - 1| < threshold on, T_tr - Ts_tr and T_rot - Ts_rot are fitted with one
    common exponential exp(-lambda t) (free amplitudes; steady values fixed), residuals weighted by
    each component's fluctuation in the second half. Returns (lambda, its standard error, t0) or
    None when the tail is too short."""
    from scipy.optimize import least_squares
    t, a, b = np.asarray(t, float), np.asarray(Ttr, float), np.asarray(Trot, float)
    late = t > 0.5 * t[-1]
    na, nb = max(a[late].std(), 1e-12), max(b[late].std(), 1e-12)
    rel_b = np.abs(b / Ts_rot - 1.0) if Ts_rot > 0 else np.zeros_like(b)
    dev = np.maximum(np.abs(a / Ts_tr - 1.0), rel_b)
    inside = np.nonzero(dev < threshold)[0]
    if len(inside) == 0:
        return None
    i0 = inside[0]
    m = t >= t[i0]
    if m.sum() < 10:
        return None
    tt = t[m] - t[i0]

    def res(p):
        e = np.exp(-p[2] * tt)
        return np.concatenate([(a[m] - Ts_tr - p[0] * e) / na, (b[m] - Ts_rot - p[1] * e) / nb])

    lam0 = 3.0 / max(tt[-1], 1e-12)
    f = least_squares(res, [a[i0] - Ts_tr, b[i0] - Ts_rot, lam0], bounds=([-np.inf, -np.inf, 0.0],
                                                                          [np.inf, np.inf, np.inf]))
    dof = max(len(f.fun) - 3, 1)
    try:
        cov = np.linalg.inv(f.jac.T @ f.jac) * max(np.sum(f.fun ** 2) / dof, 1.0)
    except np.linalg.LinAlgError:
        return None
    return float(f.x[2]), float(math.sqrt(abs(cov[2, 2]))), float(t[i0])


def ensemble_slow_rate(run, G, threshold=0.25):
    """Slow relaxation rate, in units of G (T_tr^stat)^1/2, of the seed-averaged approach of a
    Run's ensemble to its steady state (fit_slow_rate on the mean trajectory); the error is the
    scatter of the single-seed fits / sqrt(n). None when the fit fails."""
    ser = run.ensemble
    n = min(len(x["Time"]) for x in ser)
    t = ser[0]["Time"][:n]
    a = np.mean([x["Ttr"][:n] for x in ser], axis=0)
    b = np.mean([x["Trot"][:n] for x in ser], axis=0)
    late = t > 0.5 * t[-1]
    Sa, Sb = a[late].mean(), b[late].mean()
    unit = G * math.sqrt(Sa)
    f = fit_slow_rate(t, a, b, Sa, Sb, threshold)
    if f is None:
        return None
    single = []
    for x in ser:
        la = t > 0.5 * t[-1]
        g = fit_slow_rate(t, x["Ttr"][:n], x["Trot"][:n], x["Ttr"][:n][la].mean(),
                          x["Trot"][:n][la].mean(), threshold)
        if g is not None:
            single.append(g[0] / unit)
    err = float(np.std(single, ddof=1) / math.sqrt(len(single))) if len(single) > 1 else f[1] / unit
    return {"lam": f[0] / unit, "err": err, "n": len(ser), "t0": f[2]}


def model_curves(r, rt, mus, models=MODELS):
    """Steady (R, T_tr/T_tr(mu=0)) of each model on a mu grid: dict model -> (R array, T array)."""
    out = {}
    for m in models:
        v = np.array([mf.steady_state(m, r, rt, mu, Q) for mu in mus])
        out[m] = (v[:, 0], v[:, 1])
    return out


def rates(model, r, rt, mu):
    """Positive relaxation rates (slow, fast) in units of G (T_tr^stat)^1/2 (eq 43, correction 4)."""
    ev = np.abs(np.real(mf.relaxation_rates(model, r, rt, mu, Q)))
    return tuple(sorted(ev))


# ------------------------------------------------------------------------------------------------
# what to simulate
# ------------------------------------------------------------------------------------------------
@dataclass
class Plan:
    name: str
    phi: float                   # area fraction of Figs 3, 5-10
    nside: int                   # N = nside^2
    scans: list                  # (r, rt_max, [mu ...]): Figs 6-10 (and 3b)
    rt_scan: tuple               # (r, mu, [rt_max ...]): Fig 5 (and 3a)
    fig3a: list                  # rt_max values of Fig 3a (from rt_scan)
    fig3b: tuple                 # (r, rt_max, [mu ...]) of Fig 3b (from scans)
    fig11: tuple                 # (phi, r, rt_max, [mu ...])
    tmin: float                  # run length: clip(ntau / slowest model-E rate, tmin, tmax)
    tmax: float
    ntau: float
    fit_mu_max: float = 0.02     # Fig 9: R = b mu^delta fitted for mu <= fit_mu_max
    rate_cases: list = field(default_factory=list)   # (r, rt_max, mu): Fig 10 simulated slow rate
    rate_seeds: int = 4          # independent runs averaged for each rate case
    fdr: float = 2.0
    vdr: float = 0.1
    dt: float = 0.5
    series_every: int = 2        # steps between T_tr, T_rot samples (1 time unit)
    seed: int = 4321
    extra: dict = field(default_factory=dict)

    @property
    def N(self):
        return self.nside * self.nside


QUICK = Plan(
    "quick", phi=0.0866, nside=40,
    scans=[(0.95, 0.4, [0.005, 0.01, 0.02, 0.05, 0.1, 0.3, 0.5, 1.0, INF]),
           (0.95, 1.0, [0.005, 0.01, 0.02, 0.05, 0.1, 0.3, 0.5, 1.0, 3.0, INF]),
           (0.99, 1.0, [0.005, 0.01, 0.02, 0.05, 0.1, 0.3, 1.0, 3.0, INF])],
    rt_scan=(0.95, 0.5, [-1.0, -0.6, -0.2, 0.2, 0.4, 0.6, 1.0]),
    fig3a=[-1.0, -0.2, 0.4, 1.0], fig3b=(0.95, 0.4, [0.01, 0.1, 0.5, INF]),
    fig11=(0.0866, 0.95, 1.0, [INF, 0.5]),
    tmin=500.0, tmax=1800.0, ntau=12.0,
    rate_cases=[(0.95, 0.4, 0.5), (0.95, 0.4, INF), (0.95, 1.0, 0.5), (0.95, 1.0, INF)],
    rate_seeds=4)

_MU_FULL = [0.003, 0.005, 0.01, 0.02, 0.03, 0.05, 0.1, 0.2, 0.3, 0.5, 1.0, 2.0, 3.0, 10.0, INF]
FULL = Plan(
    "full", phi=0.34, nside=105,
    scans=[(r, rt, _MU_FULL) for r in (0.95, 0.99) for rt in (0.4, 1.0)],
    rt_scan=(0.95, 0.5, [-1.0, -0.8, -0.6, -0.4, -0.2, 0.0, 0.2, 0.4, 0.6, 0.8, 1.0]),
    fig3a=[-1.0, -0.4, 0.4, 1.0], fig3b=(0.95, 0.4, [0.01, 0.1, 0.5, INF]),
    fig11=(0.0866, 0.95, 1.0, [INF, 0.5]),
    tmin=500.0, tmax=5000.0, ntau=20.0, fit_mu_max=0.03,
    rate_cases=[(0.95, 0.4, 0.5), (0.95, 0.4, INF), (0.95, 1.0, 0.5), (0.95, 1.0, INF),
                (0.99, 1.0, 0.5), (0.99, 1.0, INF)],
    rate_seeds=3)


@dataclass
class Run:
    r: float
    rt: float
    mu: float
    phi: float
    N: int
    tend: float
    d: dict                      # thermo table (+ "series", "gamma")
    st: dict                     # steady averages from the series (second half)
    T0: float                    # T_tr(mu = 0) of the mean field (scale of Figs 5, 6)
    sliding: float               # simulated fraction of sliding collisions (second half)
    ensemble: list = field(default_factory=list)   # series of all seeds (rate cases only)


def steady_series(s, tfrac=0.5, nblocks=5):
    """Averages of T_tr, T_rot, R over t > tfrac t_end with block standard errors."""
    t = s["Time"]
    sel = t > tfrac * t[-1]
    out = {}
    for k in ("Ttr", "Trot", "R"):
        out[k], out[k + "_err"] = lammpslog.block_mean(s[k][sel], nblocks)
    return out


def run_length(plan, r, rt, mu, phi):
    """ntau slowest model-E relaxation times (1/time units at this fraction), within the plan's
    bounds, rounded up to 10 time units."""
    H = H_dr(plan.fdr, plan.vdr, plan.N)
    ev = np.abs(np.real(mf.relaxation_rates("E", r, rt, mu, Q, nu=phi, H_dr=H)))
    ev = ev[ev > 1e-9 * ev.max()]
    t = plan.ntau / ev.min()
    return float(10.0 * math.ceil(min(max(t, plan.tmin), plan.tmax) / 10.0))


def run_keys(plan):
    keys = []
    for r, rt, mus in plan.scans:
        keys += [(plan.phi, r, rt, mu) for mu in mus]
    r, mu, rts = plan.rt_scan
    keys += [(plan.phi, r, rt, mu) for rt in rts]
    phi, r, rt, mus = plan.fig11
    keys += [(phi, r, rt, mu) for mu in mus]
    keys += [(plan.phi, r, rt, mu) for r, rt, mu in plan.rate_cases]
    return list(dict.fromkeys(keys))          # unique, in order


def simulate_all(plan, out):
    """Every run the figures need (each parameter set once). Returns dict key -> Run."""
    runs = {}
    H = H_dr(plan.fdr, plan.vdr, plan.N)
    for key in cli.progress(run_keys(plan), f"herbst2005 figure runs ({plan.name})"):
        phi, r, rt, mu = key
        tend = run_length(plan, r, rt, mu, phi)
        log = os.path.join(out, f"log.fig_r{r}_mu{mu}_rt{rt}_phi{phi}")
        d = herbst.simulate(r, "inf" if mu == INF else mu, rt, phi, tend, log, nside=plan.nside,
                            fdr=plan.fdr, vdr=plan.vdr, seed=plan.seed, dt=plan.dt,
                            series_every=plan.series_every)
        t = d["Time"]
        late = t > 0.5 * t[-1]
        w = np.diff(t, prepend=0.0) * d["c_C[1]"]
        sl = float(np.sum((w * d["c_C[3]"])[late]) / np.sum(w[late])) if np.sum(w[late]) > 0 else 0.0
        runs[key] = Run(r, rt, mu, phi, plan.N, tend, d, steady_series(d["series"]),
                        T_smooth(r, phi, H), sl)
    extra = [(plan.phi, r, rt, mu, plan.seed + k) for r, rt, mu in plan.rate_cases
             for k in range(1, plan.rate_seeds)]
    for r, rt, mu in plan.rate_cases:
        runs[(plan.phi, r, rt, mu)].ensemble = [runs[(plan.phi, r, rt, mu)].d["series"]]
    for phi, r, rt, mu, seed in cli.progress(extra, "herbst2005 relaxation-rate seeds"):
        run = runs[(phi, r, rt, mu)]
        log = os.path.join(out, f"log.rate_r{r}_mu{mu}_rt{rt}_phi{phi}_seed{seed}")
        d = herbst.simulate(r, "inf" if mu == INF else mu, rt, phi, run.tend, log,
                            nside=plan.nside, fdr=plan.fdr, vdr=plan.vdr, seed=seed, dt=plan.dt,
                            series_every=plan.series_every)
        run.ensemble.append(d["series"])
    return runs


# ------------------------------------------------------------------------------------------------
# figures
# ------------------------------------------------------------------------------------------------
def _save(plt, fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _inf_pos(mus):
    fin = [m for m in mus if m != INF]
    return 10.0 ** (math.floor(math.log10(max(fin))) + 1.5)


def _xs(mus, xinf):
    return np.array([xinf if m == INF else m for m in mus])


def _inf_ticks(ax, xinf):
    lo = ax.get_xlim()[0]
    ticks = [t for t in ax.get_xticks() if lo <= t < xinf / 3]
    ax.set_xticks(ticks + [xinf])
    ax.set_xticklabels([f"{t:g}" for t in ticks] + ["∞"])


def fig2(path):
    """rt(gamma) for several mu (r = 0.95, rt_max = 0.4 and 1.0): C++ law (symbols) vs eqs 5-6."""
    plt = _plt()
    r, mus = 0.95, [0.02, 0.1, 0.2, 0.5, 1.0, INF]
    gam = np.linspace(0.5 * math.pi + 1e-3, math.pi, 400)
    gs = np.linspace(0.5 * math.pi + 0.01, math.pi - 0.005, 30)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    worst = 0.0
    for ax, rt_max in zip(axes, (0.4, 1.0)):
        for k, mu in enumerate(mus):
            col = f"C{k}"
            ax.plot(np.degrees(gam), rt_walton(gam, r, mu, rt_max), color=col, lw=1.2,
                    label=f"μ = {mu:g}" if mu != INF else "μ = ∞")
            rep, meas = rt_core(gs, r, mu, rt_max)
            worst = max(worst, float(np.max(np.abs(meas - rt_walton(gs, r, mu, rt_max)))),
                        float(np.max(np.abs(rep - rt_walton(gs, r, mu, rt_max)))))
            ax.plot(np.degrees(gs), meas, "o", ms=3.5, mfc="none", color=col)
            if mu != INF:
                g0 = math.degrees(gamma0(r, mu, rt_max))
                ax.axvline(g0, color=col, lw=0.5, ls=":")
        ax.set_xlabel("impact angle γ [deg]")
        ax.set_title(f"r = {r}, rt_max = {rt_max}", fontsize=10)
        ax.set_xlim(90, 180)
    axes[0].set_ylabel("tangential restitution rt(γ)")
    axes[0].legend(fontsize=8, loc="upper left")
    fig.suptitle("Fig. 2: Walton law, C++ core (symbols: -g_t'/g_t after the collision) vs "
                 "eqs 5-6 (lines); dotted: γ0 (eq 22)", fontsize=10)
    _save(plt, fig, path)
    return {"max_dev": worst}


def fig3(runs, plan, path):
    """P(gamma) from the simulations (second half of each run) vs eq 12 with the simulated R."""
    plt = _plt()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.4), sharey=True)
    rows = []
    r_a, mu_a, _ = plan.rt_scan
    r_b, rt_b, mus_b = plan.fig3b
    panels = [(axes[0], [(plan.phi, r_a, rt, mu_a) for rt in plan.fig3a], "rt_max",
               f"(a) r = {r_a}, μ = {mu_a}"),
              (axes[1], [(plan.phi, r_b, rt_b, mu) for mu in mus_b], "μ",
               f"(b) r = {r_b}, rt_max = {rt_b}")]
    for ax, keys, var, title in panels:
        for k, key in enumerate(keys):
            run = runs[key]
            g, P = run.d["gamma"]
            w = g[1] - g[0]
            edges = np.append(g - 0.5 * w, g[-1] + 0.5 * w)
            R = run.st["R"]
            th = P_gamma_binned(edges, R)
            th12 = P_gamma_binned(edges, 0.0)
            col = f"C{k}"
            val = run.rt if var == "rt_max" else run.mu
            lab = f"{var} = {'∞' if val == INF else f'{val:g}'} (R = {R:.3f})"
            ax.plot(np.degrees(g), P, "o", ms=3.5, color=col, label=lab)
            gg = np.linspace(0.5 * math.pi, math.pi, 300)
            ax.plot(np.degrees(gg), P_gamma(gg, R), "-", color=col, lw=1.1)
            if run.mu != INF and run.rt > -1.0:
                g0 = math.degrees(gamma0(run.r, run.mu, run.rt))
                ax.annotate("", xy=(g0, 0.02), xytext=(g0, 0.18),
                            arrowprops=dict(arrowstyle="->", color=col))
            rows.append({"panel": title[:3], "r": run.r, "mu": run.mu, "rt": run.rt, "R": R,
                         "dev12": float(np.max(np.abs(P - th))), "dev_R0": float(np.max(np.abs(P - th12))),
                         "norm": float(np.sum(P) * w), "slide_sim": run.sliding,
                         "slide_th": sliding_fraction(R, run.r, run.mu, run.rt)})
        ax.plot(np.degrees(gg), P_gamma(gg, 0.0), color="0.6", lw=0.8, ls="--",
                label="R = 0: -cos γ (P12)")
        ax.set_xlabel("impact angle γ [deg]")
        ax.set_title(title, fontsize=10)
        ax.set_xlim(90, 180)
        ax.legend(fontsize=7, loc="upper left")
    axes[0].set_ylabel("P(γ)")
    fig.suptitle(f"Fig. 3: impact angles, simulation (symbols; N = {plan.N}, fraction {plan.phi}) "
                 "vs eq 12 with the simulated R (lines); arrows: γ0", fontsize=10)
    _save(plt, fig, path)
    return rows


def _err(ax, x, y, e, **kw):
    ax.errorbar(x, y, yerr=e, fmt=kw.pop("fmt", "o"), ms=kw.pop("ms", 5), capsize=2, **kw)


def fig5(runs, plan, path):
    """T_tr, T_rot (scaled by T_tr(mu=0)) and R against rt_max at fixed r, mu."""
    plt = _plt()
    r, mu, rts = plan.rt_scan
    fig, ax = plt.subplots(1, 3, figsize=(14, 4.2))
    grid = np.linspace(-1.0, 1.0, 81)
    for m in MODELS:
        v = np.array([mf.steady_state(m, r, rt, mu, Q) for rt in grid])
        ax[0].plot(grid, v[:, 1], label=f"model {m}", **STYLE[m])
        ax[1].plot(grid, v[:, 0] * v[:, 1], **STYLE[m])
        ax[2].plot(grid, v[:, 0], **STYLE[m])
    rows = []
    for rt in rts:
        run = runs[(plan.phi, r, rt, mu)]
        s, T0 = run.st, run.T0
        _err(ax[0], rt, s["Ttr"] / T0, s["Ttr_err"] / T0, color="C3")
        _err(ax[1], rt, s["Trot"] / T0, s["Trot_err"] / T0, color="C3")
        _err(ax[2], rt, s["R"], s["R_err"], color="C3")
        RE, TE = mf.steady_state("E", r, rt, mu, Q)
        RA, TA = mf.steady_state("A", r, rt, mu, Q)
        rows.append({"rt": rt, "T": s["Ttr"] / T0, "T_err": s["Ttr_err"] / T0, "TE": TE, "TA": TA,
                     "R": s["R"], "R_err": s["R_err"], "RE": RE, "RA": RA})
    for a, lab in zip(ax, ("T_tr / T_tr(μ=0)", "T_rot / T_tr(μ=0)", "R = T_rot / T_tr")):
        a.set_xlabel("rt_max")
        a.set_ylabel(lab)
    ax[0].legend(fontsize=8)
    fig.suptitle(f"Fig. 5: r = {r}, μ = {mu}, fraction {plan.phi}, N = {plan.N}: simulation "
                 "(symbols) vs mean-field models A-E (lines)", fontsize=10)
    _save(plt, fig, path)
    return rows


def _mu_panels(runs, plan, path, quantity, title, ylabel):
    """Figs 6 and 7: one panel per rt_max, r = 0.99 filled / 0.95 open symbols."""
    plt = _plt()
    rts = sorted({rt for _, rt, _ in plan.scans})
    fig, axes = plt.subplots(1, len(rts), figsize=(6 * len(rts), 4.4), squeeze=False)
    allmu = [m for _, _, mus in plan.scans for m in mus]
    xinf = _inf_pos(allmu)
    fin = [m for m in allmu if m != INF]
    grid = np.logspace(math.log10(min(fin)) - 0.3, math.log10(max(fin)) + 0.3, 90)
    curves = {}
    for ax, rt in zip(axes[0], rts):
        first = True
        for r, rt_s, mus in plan.scans:
            if rt_s != rt:
                continue
            thick = r >= 0.99
            mc = model_curves(r, rt, grid)
            curves[(r, rt)] = mc
            for m in MODELS:
                y = mc[m][1] if quantity == "T" else mc[m][0]
                st = dict(STYLE[m])
                st["lw"] = st["lw"] * (1.6 if thick else 0.8)
                ax.semilogx(grid, y, label=f"model {m}" if first else None, **st)
                Ri, Ti = mf.steady_state(m, r, rt, INF, Q)
                ax.plot([xinf], [Ti if quantity == "T" else Ri], marker="_", ms=14,
                        color=st["color"])
            xs, ys, es = [], [], []
            for mu in mus:
                run = runs[(plan.phi, r, rt, mu)]
                if quantity == "T":
                    ys.append(run.st["Ttr"] / run.T0)
                    es.append(run.st["Ttr_err"] / run.T0)
                else:
                    ys.append(run.st["R"])
                    es.append(run.st["R_err"])
                xs.append(xinf if mu == INF else mu)
            _err(ax, xs, ys, es, color="C3", mfc="C3" if thick else "white",
                 label=f"simulation, r = {r}")
            first = False
        ax.set_xlabel("μ")
        ax.set_ylabel(ylabel)
        ax.set_title(f"rt_max = {rt}", fontsize=10)
        _inf_ticks(ax, xinf)
        ax.legend(fontsize=6, ncol=2)
    fig.suptitle(f"{title}: fraction {plan.phi}, N = {plan.N}; thick lines / filled symbols "
                 "r = 0.99, thin / open r = 0.95", fontsize=10)
    _save(plt, fig, path)
    return curves


def fig6(runs, plan, path):
    _mu_panels(runs, plan, path, "T", "Fig. 6: T_tr^stat / T_tr^stat(μ=0) against μ",
               "T_tr / T_tr(μ=0)")
    rows = []
    for r, rt, mus in plan.scans:
        fin = [m for m in mus if m != INF]
        sim = [(runs[(plan.phi, r, rt, m)].st["Ttr"] / runs[(plan.phi, r, rt, m)].T0, m) for m in fin]
        grid = np.logspace(-3, 2, 501)
        TE = np.array([mf.steady_state("E", r, rt, m, Q)[1] for m in grid])
        k = int(np.argmin(TE))
        rows.append({"r": r, "rt": rt, "mu_min_sim": min(sim)[1], "T_min_sim": min(sim)[0],
                     "mu_min_E": float(grid[k]) if 0 < k < len(grid) - 1 else None,
                     "T_min_E": float(TE[k])})
    return rows


def fig7(runs, plan, path):
    _mu_panels(runs, plan, path, "R", "Fig. 7: R = T_rot/T_tr against μ", "R")
    rows = []
    for r, rt, mus in plan.scans:
        if INF in mus:
            run = runs[(plan.phi, r, rt, INF)]
            rows.append({"r": r, "rt": rt, "R_sim": run.st["R"], "R_err": run.st["R_err"],
                         "R_formula": R_inf(rt), "R_A": mf.R_model_A(r, rt, Q),
                         "R_E_1e6": mf.steady_state("E", r, rt, 1e6, Q)[0]})
    return rows


def fig8(runs, plan, path):
    """1 - R against 1/mu (log-log) for the rt_max = 1 scans."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.5, 4.6))
    rows = []
    inv = np.logspace(-2.2, 2.3, 120)
    for k, (r, rt, mus) in enumerate([s for s in plan.scans if s[1] == 1.0]):
        thick = r >= 0.99
        first = k == 0
        for m in MODELS:
            R = np.array([mf.steady_state(m, r, rt, 1.0 / x, Q)[0] for x in inv])
            st = dict(STYLE[m])
            st["lw"] = st["lw"] * (1.6 if thick else 0.8)
            ax.loglog(inv, 1.0 - R, label=f"model {m}" if first else None, **st)
        fin = [mu for mu in mus if mu != INF]
        x = np.array([1.0 / mu for mu in fin])
        y = np.array([1.0 - runs[(plan.phi, r, rt, mu)].st["R"] for mu in fin])
        e = np.array([runs[(plan.phi, r, rt, mu)].st["R_err"] for mu in fin])
        ok = y > 0
        _err(ax, x[ok], y[ok], e[ok], color="C3", mfc="C3" if thick else "white",
             label=f"simulation, r = {r}")
        # large-mu slope: 1 - R ~ (1/mu)^s, from the points with mu >= 0.5 and 1 - R > 2 sigma
        big = np.array([mu >= 0.5 for mu in fin]) & (y > 2 * e)
        row = {"r": r, "rt": rt, "mus": [mu for mu, b in zip(fin, big) if b]}
        if big.sum() >= 2:
            f = fit_power_law(x[big], y[big], e[big])
            RE = np.array([mf.steady_state("E", r, rt, mu, Q)[0] for mu in row["mus"]])
            fE = fit_power_law(x[big], 1.0 - RE)
            row.update(slope=f["delta"], slope_err=f["delta_err"], slope_E=fE["delta"])
        RE_far = [1.0 - mf.steady_state("E", r, rt, mu, Q)[0] for mu in (100.0, 1000.0)]
        row["slope_E_asym"] = math.log(RE_far[0] / RE_far[1]) / math.log(10.0)
        rows.append(row)
    ax.set_xlabel("1/μ")
    ax.set_ylabel("1 - R")
    ax.set_ylim(1e-3, 2)
    ax.set_xlim(3e-2, 3e2)
    ax.legend(fontsize=6, ncol=2)
    ax.set_title(f"Fig. 8: deviation from equipartition, rt_max = 1 (fraction {plan.phi}, "
                 f"N = {plan.N})\nthick lines / filled symbols r = 0.99, thin / open r = 0.95; "
                 "model A: 1 - R = 0", fontsize=9)
    _save(plt, fig, path)
    return rows


def fig9(runs, plan, path):
    """R against mu (log-log) at small mu with the power-law fit R = b mu^delta."""
    plt = _plt()
    fig, axes = plt.subplots(1, len(plan.scans), figsize=(5.2 * len(plan.scans), 4.4),
                             squeeze=False)
    rows = []
    grid = np.logspace(-3, 0, 80)
    for ax, (r, rt, mus) in zip(axes[0], plan.scans):
        for m in MODELS:
            R = np.array([mf.steady_state(m, r, rt, mu, Q)[0] for mu in grid])
            ax.loglog(grid, R, label=f"model {m}", **STYLE[m])
        ax.loglog(grid, (1 + r) * grid, color="C0", lw=0.8, ls=(0, (1, 2)),
                  label="(1+r) μ (eq 42)")
        fin = [mu for mu in mus if mu != INF and mu <= 1.0]
        x = np.array(fin)
        y = np.array([runs[(plan.phi, r, rt, mu)].st["R"] for mu in fin])
        e = np.array([runs[(plan.phi, r, rt, mu)].st["R_err"] for mu in fin])
        _err(ax, x, y, e, color="C3", label="simulation")
        sel = x <= plan.fit_mu_max * (1 + 1e-9)
        row = {"r": r, "rt": rt, "mus": list(x[sel])}
        if sel.sum() >= 2:
            f = fit_power_law(x[sel], y[sel], e[sel])
            RE = np.array([mf.steady_state("E", r, rt, mu, Q)[0] for mu in x[sel]])
            RC = np.array([mf.steady_state("C", r, rt, mu, Q)[0] for mu in x[sel]])
            row.update(f)
            row["delta_E"] = fit_power_law(x[sel], RE)["delta"]
            row["delta_C"] = fit_power_law(x[sel], RC)["delta"]
            gx = np.logspace(math.log10(x[sel].min()) - 0.3, math.log10(x[sel].max()) + 0.3, 20)
            ax.loglog(gx, f["b"] * gx ** f["delta"], color="C3", lw=2, alpha=0.5,
                      label=f"fit δ = {f['delta']:.3f} ± {f['delta_err']:.3f}")
        rows.append(row)
        ax.set_xlabel("μ")
        ax.set_ylabel("R")
        ax.set_title(f"r = {r}, rt_max = {rt}", fontsize=10)
        ax.legend(fontsize=6)
    fig.suptitle(f"Fig. 9: R at small μ, fit R = b μ^δ for μ ≤ {plan.fit_mu_max} (fraction "
                 f"{plan.phi}, N = {plan.N})", fontsize=10)
    _save(plt, fig, path)
    return rows


def fig10(runs, plan, path):
    """(a) Model A rates against rt_max at r = 0.95 (the paper's Fig. 10) and their ratio;
    (b) model E (and D) rates against mu with simulated estimates of the slow rate; (c) ratio."""
    plt = _plt()
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.4))
    rtg = np.linspace(-1.0, 1.0, 401)
    lam = np.array([rates("A", 0.95, rt, INF) for rt in rtg])
    ax[0].plot(rtg, lam[:, 0], "k-", label="λ1 (slow), model A")
    ax[0].plot(rtg, lam[:, 1], "k--", label="λ2 (fast), model A")
    ax0b = ax[0].twinx()
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio_A = lam[:, 1] / lam[:, 0]
    ax0b.semilogy(rtg[1:], ratio_A[1:], color="C0", lw=1)
    ax0b.set_ylabel("λ2 / λ1", color="C0")
    k = 1 + int(np.argmin(ratio_A[1:]))
    out = {"rt_closest": float(rtg[k]), "ratio_min": float(ratio_A[k]),
           "ratio_rt1": float(ratio_A[-1]), "sim": []}
    ax[0].axvline(out["rt_closest"], color="0.6", lw=0.6, ls=":")
    ax[0].set_xlabel("rt_max")
    ax[0].set_ylabel("rate / (G T_tr^stat 1/2)")
    ax[0].set_title("(a) paper's Fig. 10: model A, r = 0.95", fontsize=10)
    ax[0].legend(fontsize=8, loc="upper left")
    grid = np.logspace(-3, 2.5, 120)
    xinf = 1e3
    G = cooling.time_scale_G(plan.phi, 0.5, 1.0, 2)
    lines = list(dict.fromkeys([(r, rt) for r, rt, _ in plan.scans] +
                               [(r, rt) for r, rt, _ in plan.rate_cases]))
    for k2, (r, rt) in enumerate(lines):
        col = f"C{k2}"
        lE = np.array([rates("E", r, rt, mu) for mu in grid])
        lD = np.array([rates("D", r, rt, mu) for mu in grid])
        ax[1].loglog(grid, lE[:, 0], "-", color=col, label=f"E, r = {r}, rt_max = {rt}")
        ax[1].loglog(grid, lE[:, 1], "-", color=col, lw=0.8)
        ax[1].loglog(grid, lD[:, 0], "--", color=col, lw=0.8)
        ax[1].loglog(grid, lD[:, 1], "--", color=col, lw=0.6)
        ax[2].semilogx(grid, lE[:, 1] / lE[:, 0], "-", color=col, label=f"E, r = {r}, rt_max = {rt}")
        ax[2].semilogx(grid, lD[:, 1] / lD[:, 0], "--", color=col, lw=0.8)
        ax[1].plot([xinf], [rates("E", r, rt, INF)[0]], marker="_", ms=12, color=col)
        ax[1].plot([xinf], [rates("E", r, rt, INF)[1]], marker="_", ms=12, color=col)
        for rr, rtt, mu in plan.rate_cases:
            if (rr, rtt) != (r, rt):
                continue
            est = ensemble_slow_rate(runs[(plan.phi, r, rt, mu)], G)
            if est is None:
                continue
            th = rates("E", r, rt, mu)
            ax[1].errorbar([xinf if mu == INF else mu], [est["lam"]], yerr=[est["err"]], fmt="o",
                           color=col, ms=5, capsize=2)
            out["sim"].append(dict(est, r=r, rt=rt, mu=mu, E=th[0], ratio_E=th[1] / th[0]))
    ax[1].set_xlabel("μ  (μ = ∞ at 10³)")
    ax[1].set_ylabel("rate / (G T_tr^stat 1/2)")
    ax[1].set_title(f"(b) model E (solid), D (dashed): slow and fast rate; symbols: slow rate\n"
                    f"of the simulated approach, {plan.rate_seeds} runs averaged", fontsize=9)
    ax[1].legend(fontsize=7)
    ax[2].set_xlabel("μ")
    ax[2].set_ylabel("λ2 / λ1")
    ax[2].set_title("(c) ratio of the two rates, model E (solid), D (dashed)", fontsize=9)
    ax[2].legend(fontsize=7)
    fig.suptitle("Fig. 10: linear relaxation rates about the driven steady state (eq 43 with "
                 "correction 4; models C, E: Jacobian of eq 13)", fontsize=10)
    _save(plt, fig, path)
    return out


def fig11(runs, plan, path):
    """T_tr, T_rot against t/tau, tau^-1 = G T_tr(0)^1/2 / 2, simulation vs model E."""
    plt = _plt()
    phi, r, rt, mus = plan.fig11
    fig, axes = plt.subplots(1, len(mus), figsize=(6 * len(mus), 4.4), squeeze=False)
    G = cooling.time_scale_G(phi, 0.5, 1.0, 2)
    rows = []
    for k, (ax, mu) in enumerate(zip(axes[0], mus)):
        run = runs[(phi, r, rt, mu)]
        s = run.d["series"]
        t = s["Time"]
        T0tr = float(s["Ttr"][0])
        tau = 2.0 / (G * math.sqrt(T0tr))
        H = H_dr(plan.fdr, plan.vdr, run.N)
        _, Ttr, Trot = mf.integrate("E", r, rt, mu, Q, phi, H_dr=H, T0=(T0tr, float(s["Trot"][0])),
                                    times=t)
        # symbols: the log-spaced thermo output before the first sample of the series, then
        # the series thinned to about 150 points per decade
        th = run.d
        early = (th["Time"] > 0) & (th["Time"] < t[1])
        pick = np.nonzero(t > 0)[0]
        pick = pick[np.unique(np.logspace(0, math.log10(len(pick)), 250).astype(int) - 1)]
        ts = np.concatenate([th["Time"][early], t[pick]])
        ax.semilogx(ts / tau, np.concatenate([th["c_T[1]"][early], s["Ttr"][pick]]), "o", ms=3,
                    color="C0", mfc="none", label="T_tr simulation")
        ax.semilogx(ts / tau, np.concatenate([th["c_T[2]"][early], s["Trot"][pick]]), "s", ms=3,
                    color="C3", mfc="none", label="T_rot simulation")
        tl = np.concatenate([th["Time"][early], t[t > 0]])
        _, Ttr_l, Trot_l = mf.integrate("E", r, rt, mu, Q, phi, H_dr=H,
                                        T0=(T0tr, float(s["Trot"][0])), times=np.append(0.0, tl))
        ax.semilogx(tl / tau, Ttr_l[1:], "-", color="C0", label="T_tr model E")
        ax.semilogx(tl / tau, Trot_l[1:], "-", color="C3", label="T_rot model E")
        ax.set_xlabel("t / τ,  τ⁻¹ = G T_tr(0)^½ / 2")
        ax.set_ylabel("temperature")
        ax.set_title(f"({'ab'[k] if k < 2 else k}) μ = {'∞' if mu == INF else mu}", fontsize=10)
        ax.legend(fontsize=8)
        Ts_rot = run.st["Trot"]
        grown = Trot > 0.2 * Ts_rot if Ts_rot > 0 else np.zeros_like(t, dtype=bool)
        rms = lambda x: float(np.sqrt(np.mean(x * x))) if len(x) else 0.0
        late = t > 0.5 * t[-1]
        rows.append({"mu": mu, "tend_tau": float(t[-1] / tau),
                     "dev_tr": rms(s["Ttr"] / Ttr - 1),
                     "dev_rot": rms(s["Trot"][grown] / Trot[grown] - 1),
                     "noise_tr": float(np.std(s["Ttr"][late]) / np.mean(s["Ttr"][late])),
                     "Ttr": run.st["Ttr"], "Ttr_E": float(Ttr[-1]), "Trot": Ts_rot,
                     "Trot_E": float(Trot[-1])})
    fig.suptitle(f"Fig. 11: evolution from an elastic smooth start, N = {plan.N}, "
                 f"fraction {phi}, r = {r}, rt_max = {rt}; no fit parameters", fontsize=10)
    _save(plt, fig, path)
    return rows


# ------------------------------------------------------------------------------------------------
# driver and report
# ------------------------------------------------------------------------------------------------
FIGS = ("fig2_rt_vs_gamma.png", "fig3_p_gamma.png", "fig5_rt_scan.png", "fig6_ttr_vs_mu.png",
        "fig7_R_vs_mu.png", "fig8_one_minus_R.png", "fig9_R_small_mu.png",
        "fig10_relaxation_rates.png", "fig11_evolution.png")


def make_figures(runs, plan, out):
    """Every figure from the runs; returns the numbers for the report."""
    p = lambda name: os.path.join(out, name)
    res = {"plan": plan}
    res["fig2"] = fig2(p(FIGS[0]))
    res["fig3"] = fig3(runs, plan, p(FIGS[1]))
    res["fig5"] = fig5(runs, plan, p(FIGS[2]))
    res["fig6"] = fig6(runs, plan, p(FIGS[3]))
    res["fig7"] = fig7(runs, plan, p(FIGS[4]))
    res["fig8"] = fig8(runs, plan, p(FIGS[5]))
    res["fig9"] = fig9(runs, plan, p(FIGS[6]))
    res["fig10"] = fig10(runs, plan, p(FIGS[7]))
    res["fig11"] = fig11(runs, plan, p(FIGS[8]))
    return res


def run(plan, out, logs=None):
    """Simulate (LAMMPS logs in `logs`, default out), plot into out, and return (runs, numbers)."""
    runs = simulate_all(plan, logs or out)
    return runs, make_figures(runs, plan, out)


def _mu(m):
    return "∞" if m == INF else f"{m:g}"


def report_section(res):
    """Markdown of the figure numbers, ours next to the paper's."""
    plan = res["plan"]
    L = ["", f"## Figures ({plan.name} run: N = {plan.N}, fraction {plan.phi}, f_dr = {plan.fdr}, "
         f"v_dr = {plan.vdr})", "",
         "Steady values: time averages over the second half of each run (T_tr, T_rot sampled every "
         f"{plan.series_every * plan.dt:g} time units), block standard errors (5 blocks). Runs last "
         f"{plan.ntau:g} slowest model-E relaxation times, within [{plan.tmin:g}, {plan.tmax:g}].",
         ""]
    if plan.name == "quick":
        L += ["*Quick run:* N and the fraction are smaller than the paper's (N = 11025, fraction "
              "0.34 for Figs 3, 5-9), fewer μ values; `--full` runs the paper's parameters.", ""]
    L += [f"### Fig. 2 (`{FIGS[0]}`): rt(γ) of the Walton law",
          "", f"C++ law (core.collide, rt read off -g_t'/g_t after the collision) against eqs 5-6: "
          f"largest difference {res['fig2']['max_dev']:.1e} over 6 μ × 2 rt_max × 30 angles "
          "(the paper: Fig. 2 is the closed form).", ""]
    L += [f"### Fig. 3 (`{FIGS[1]}`): impact-angle distribution", "",
          "Histogram of the second half of each run (compute hardsphere/collisions, 36 bins) against "
          "eq 12 evaluated with the simulated R (bin averages). Paper: \"reasonably good agreement\".",
          "", "| panel | r | μ | rt_max | R sim | max abs(P_sim - P_eq12) | max abs(P_sim - P12) | "
          "sliding sim | sliding eq 12 (1 - 1/f~) |", "|---|---|---|---|---|---|---|---|---|"]
    for w in res["fig3"]:
        L.append(f"| {w['panel']} | {w['r']} | {_mu(w['mu'])} | {w['rt']} | {w['R']:.4f} | "
                 f"{w['dev12']:.3f} | {w['dev_R0']:.3f} | {w['slide_sim']:.3f} | {w['slide_th']:.3f} |")
    L += ["", "(P(γ) peaks at about 0.6-1.0; P12 = -cos γ is eq 12 at R = 0.)", ""]
    r, mu, _ = plan.rt_scan
    L += [f"### Fig. 5 (`{FIGS[2]}`): against rt_max at r = {r}, μ = {mu}", "",
          "| rt_max | T_tr/T_tr(μ=0) sim | model E | model A | R sim | model E | model A |",
          "|---|---|---|---|---|---|---|"]
    for w in res["fig5"]:
        L.append(f"| {w['rt']} | {w['T']:.4f} ± {w['T_err']:.4f} | {w['TE']:.4f} | {w['TA']:.4f} | "
                 f"{w['R']:.4f} ± {w['R_err']:.4f} | {w['RE']:.4f} | {w['RA']:.4f} |")
    L += ["", "Paper (fraction 0.34): all models agree with the simulations at rt_max ≈ -1, large "
          "discrepancies at rt_max ≈ 1, model E closest.", ""]
    L += [f"### Fig. 6 (`{FIGS[3]}`): T_tr/T_tr(μ=0) against μ", "",
          "| r | rt_max | μ of the lowest simulated T_tr | its T_tr/T_tr(μ=0) | μ of the minimum of "
          "model E | model E minimum |", "|---|---|---|---|---|---|"]
    for w in res["fig6"]:
        me = "none (monotonic)" if w["mu_min_E"] is None else f"{w['mu_min_E']:.3g}"
        L.append(f"| {w['r']} | {w['rt']} | {_mu(w['mu_min_sim'])} | {w['T_min_sim']:.4f} | {me} | "
                 f"{w['T_min_E']:.4f} |")
    L += ["", "Paper: for rt_max = 1 T_tr is non-monotonic in μ, strongest dissipation around "
          f"μ ≈ {PAPER['fig6_min_mu']}; for rt_max = 0.4 a monotonic transition over three decades.",
          ""]
    L += [f"### Fig. 7 (`{FIGS[4]}`): R against μ; R(μ → ∞)", "",
          "R(μ → ∞) = 2(1 + rt_max)/(9 - 5 rt_max) of the paper is eq 39 of model A "
          "(q eta0/(q - eta0) at q = 2/5, `meanfield.R_model_A`); every model reduces to it at μ = ∞.",
          "", "| r | rt_max | R sim (μ = ∞) | 2(1+rt)/(9-5rt) | model A (eq 39) | model E at μ = 1e6 |",
          "|---|---|---|---|---|---|"]
    for w in res["fig7"]:
        L.append(f"| {w['r']} | {w['rt']} | {w['R_sim']:.4f} ± {w['R_err']:.4f} | "
                 f"{w['R_formula']:.6f} | {w['R_A']:.6f} | {w['R_E_1e6']:.6f} |")
    L += ["", "Paper: R goes from 0 (μ = 0) to R(∞) over about three decades of μ; R(∞) = rt_max at "
          "rt_max = 0.4 and 1 is a coincidence.", ""]
    L += [f"### Fig. 8 (`{FIGS[5]}`): 1 - R against 1/μ (rt_max = 1)", "",
          "| r | μ used | slope of log(1-R) vs log(1/μ), sim | model E at the same μ | model E, μ → ∞ |",
          "|---|---|---|---|---|"]
    for w in res["fig8"]:
        if "slope" in w:
            L.append(f"| {w['r']} | {', '.join(_mu(m) for m in w['mus'])} | {w['slope']:.2f} ± "
                     f"{w['slope_err']:.2f} | {w['slope_E']:.2f} | {w['slope_E_asym']:.2f} |")
        else:
            L.append(f"| {w['r']} | too few resolved points | - | - | {w['slope_E_asym']:.2f} |")
    L += ["", "Paper: no number; the figure shows 1 - R falling with 1/μ on a double-log scale. "
          "Model E: 1 - R ∝ μ^-2 (c^2) at large μ.", ""]
    L += [f"### Fig. 9 (`{FIGS[6]}`): R = b μ^δ at small μ", "",
          f"Weighted fit of ln R against ln μ for μ ≤ {plan.fit_mu_max} (error from the covariance, "
          "scaled by sqrt(χ²/dof) when > 1). Model E and C fitted on the same μ values.", "",
          "| r | rt_max | μ fitted | δ sim | paper | δ model E (same μ) | δ model C (same μ) | χ²/dof |",
          "|---|---|---|---|---|---|---|---|"]
    for w in res["fig9"]:
        if "delta" in w:
            L.append(f"| {w['r']} | {w['rt']} | {', '.join(f'{m:g}' for m in w['mus'])} | "
                     f"{w['delta']:.3f} ± {w['delta_err']:.3f} | {PAPER['delta'].get(w['r'], '-')} | "
                     f"{w['delta_E']:.3f} | {w['delta_C']:.3f} | {w['chi2_red']:.2f} |")
    L += ["", "Model E: R → (1 + r) μ (eq 42, δ = 1); models B, C: R ∝ μ |ln μ|; D: μ/|ln μ| "
          "(doc/conventions.rst, correction 7).", ""]
    f10 = res["fig10"]
    L += [f"### Fig. 10 (`{FIGS[7]}`): relaxation rates", "",
          "The paper's Fig. 10 plots the two rates of model A against rt_max at r = 0.95 (not "
          "against μ); panel (a) reproduces it, panels (b, c) add the rates of models E and D "
          "against μ.", "",
          "| quantity | ours | paper |", "|---|---|---|",
          f"| rt_max where the rates come closest (model A, r = 0.95) | {f10['rt_closest']:.3f} "
          f"(ratio {f10['ratio_min']:.3f}: an avoided crossing, the eigenvalues of eq 43 are always "
          f"real and distinct) | \"equal\" at ≈ {PAPER['fig10_equal_rt']} |",
          f"| fast/slow ratio at rt_max = 1 (model A, r = 0.95) | {f10['ratio_rt1']:.2f} | "
          f"about {PAPER['fig10_ratio_rt1']:g} |", ""]
    if f10["sim"]:
        L += [f"Slow rate of the simulated approach to the steady state from the elastic smooth "
              f"start, {plan.rate_seeds} independent runs averaged: one exponential common to "
              "T_tr and T_rot fitted from the first time both are within 25 % of their steady "
              "values on (the fast mode has died out there when the rates are well separated); "
              "units G (T_tr^stat)^1/2 with the simulated T_tr^stat; error: scatter of the "
              "single-run fits / sqrt(n). The paper gives no simulated rates.", "",
              "| r | rt_max | μ | λ_slow sim | λ_slow model E | sim/E | model E λ_fast/λ_slow |",
              "|---|---|---|---|---|---|---|"]
        for w in f10["sim"]:
            L.append(f"| {w['r']} | {w['rt']} | {_mu(w['mu'])} | {w['lam']:.4f} ± {w['err']:.4f} | "
                     f"{w['E']:.4f} | {w['lam'] / w['E']:.2f} | {w['ratio_E']:.2f} |")
        L.append("")
    phi, r, rt, _ = plan.fig11
    L += [f"### Fig. 11 (`{FIGS[8]}`): evolution from an elastic smooth start "
          f"(fraction {phi}, r = {r}, rt_max = {rt})", "",
          "| μ | run length [τ] | rms rel. dev. T_tr(t) sim vs model E | rms rel. dev. T_rot(t) "
          "(once T_rot > 20 % of its steady value) | rel. fluctuation of T_tr in the steady state | "
          "steady T_tr: sim, model E | steady T_rot: sim, model E |",
          "|---|---|---|---|---|---|---|"]
    for w in res["fig11"]:
        L.append(f"| {_mu(w['mu'])} | {w['tend_tau']:.0f} | {100 * w['dev_tr']:.1f} % | "
                 f"{100 * w['dev_rot']:.1f} % | {100 * w['noise_tr']:.1f} % | "
                 f"{w['Ttr']:.4f}, {w['Ttr_E']:.4f} | {w['Trot']:.4f}, {w['Trot_E']:.4f} |")
    L += ["", "Paper: good agreement with model E, no fit parameters. The deviations are of "
          "instantaneous values, so they include the thermal noise of N = "
          f"{res['plan'].N} particles (previous column).", ""]
    return "\n".join(L) + "\n"
