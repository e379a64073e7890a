# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Free cooling of a gas of smooth viscoelastic hard spheres (3D) or discs (2D): the
homogeneous-cooling theory (Schwager & Poeschel 1998; Brilliantov & Poeschel, "Kinetic Theory of
Granular Gases", 2004) against GRANFRIC's event-driven runs (examples/viscoelastic) and the
kinetic theory by DSMC with the same restitution (granfric.dsmc).

    PYTHONPATH=tools /usr/bin/python3 -m granfric.viscoelastic [--quick|--full] [--out DIR]

writes cooling_ve.png and report.md (--quick: about 7 minutes on one core; the numbers are in
examples/viscoelastic/README.md).

Restitution. A collision with normal impact speed u = |g_n| has the restitution E(delta) of
doc/conventions.rst ("Viscoelastic normal restitution"), delta = b u^(1/5). pair_coeff ... r beta
viscoelastic vref fixes b = E^-1(r) / vref^(1/5). For small delta, E = 1 - C1 delta + C2 delta^2,
so 1 - E^2 = 2 C1 delta - (C1^2 + 2 C2) delta^2 + ...; the second term is positive, the first
order overestimates the loss once delta is not small.

Cooling rate (equal smooth particles, mass m, diameter sigma, d = 2 or 3 dimensions, k_B = 1,
T = m <v^2>/d per degree of freedom). A collision takes (m/4)(1 - E^2) u^2 from the kinetic
energy (the normal effective mass is m/2). Under molecular chaos and Enskog's pair correlation
chi at contact, pairs with relative velocity g and contact normal n collide at the rate
(n^2/2) chi sigma^(d-1) |g.n| per unit volume, for each n of the approaching half of the unit
sphere. For any fixed n the normal component g.n of the relative velocity of a Maxwellian pair
is Gaussian with variance 2T/m, so the integral over g and n reduces to one over u:

    rate of collisions per unit volume  = (n^2/2) chi sigma^(d-1) S_d int_0^inf u phi(u) du
    energy loss per unit volume and time = (n^2/2) chi sigma^(d-1) S_d int_0^inf u phi(u)
                                           (m/4)(1 - E(b u^(1/5))^2) u^2 du

with phi(u) = (m / (4 pi T))^(1/2) exp(-m u^2 / (4T)) and S_d the surface of the unit sphere
(2 pi, 4 pi). The first gives the collision frequency per particle nu(T) =
n chi sigma^(d-1) S_d (T / (pi m))^(1/2), the Enskog rate of granfric.cooling (collision_frequency,
Henderson's chi in 2D, Carnahan-Starling's in 3D). With x = m u^2 / (4T) the weight u^3 phi(u) du
is proportional to x exp(-x) dx, and the energy balance d(n d T / 2)/dt = -(loss) becomes

    dT/dt = -zeta(T) T ,   zeta(T) = (nu(T) / d) F(theta(T)) ,
    F(theta) = int_0^inf x exp(-x) [1 - E(theta x^(1/10))^2] dx ,   theta(T) = b (4T/m)^(1/10) ,

F being the mean of 1 - E^2 over the collisions of a Maxwellian gas (weighted by u^3). For a
constant E = r, F = 1 - r^2 and zeta = nu (1 - r^2)/d: Haff's law (granfric.cooling with
beta = -1). The numerical average of F with the exact E (`loss_factor`) is the homogeneous
theory beyond first order in the dissipation, still with a Maxwellian distribution
(`cooling_curve`).

First order: 1 - E^2 = 2 C1 theta x^(1/10), and int_0^inf x^(11/10) exp(-x) dx = Gamma(21/10), so

    F1(theta) = 2 C1 Gamma(21/10) theta ,   zeta1(T) = zeta1(T0) (T/T0)^(3/5)

(nu ~ T^(1/2), theta ~ T^(1/10)), and dT/dt = -zeta1(T0) T0^(-3/5) T^(8/5) integrates to

    T(t) = T0 (1 + t/tau)^(-5/3) ,   1/tau = (3/5) zeta1(T0)        (`first_order`)

so T ~ t^(-5/3) at t >> tau. The collisions per particle grow only as t^(1/6) there, and the
collision-averaged restitution approaches 1 as T^(1/10).

Early times. When theta(T0) is not small, F(theta) grows slower than theta (it tends to 1 for
E -> 0): zeta ~ T^(1/2) F(theta(T)) with a local exponent s = 1/2 + (1/10) dlnF/dln theta between
1/2 and 3/5, and the decay is Haff-like, T ~ t^(-1/s), nearer t^(-2), with the restitution of the
current temperature. `haff` is Haff's law frozen at the initial loss factor F(theta(T0)). The
local exponent d ln T / d ln t of the exact homogeneous solution starts at 0, approaches -1/s(T)
and, as theta(T) -> 0, -5/3.

What the Maxwellian theories leave out: the velocity distribution of a cooling viscoelastic gas
is not Maxwellian (its Sonine coefficient a2 is of order delta and changes in time, Brilliantov &
Poeschel 2004); the DSMC of the homogeneous Enskog-Boltzmann equation with the same E
(granfric.dsmc with restitution=("viscoelastic", [vref])) has it, the event-driven runs also
have the correlations that molecular chaos neglects.
"""
import math
import os

import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import gamma

from . import cli, cooling, core, dsmc, lammpslog, lmp

C1 = 1.15344    # E = 1 - C1 delta + C2 delta^2 - ... (doc/conventions.rst)
C2 = 0.79826
EXAMPLE = os.path.join(lmp.ROOT, "examples", "viscoelastic")


def inverse_restitution(r):
    """delta with E(delta) = r (0 < r < 1)."""
    if not 0.0 < r < 1.0:
        raise ValueError("r must be in (0, 1)")
    hi = 1.0
    while core.viscoelastic_restitution(hi) > r:
        hi *= 2.0
    return brentq(lambda d: core.viscoelastic_restitution(d) - r, 0.0, hi, xtol=1e-15, rtol=1e-14)


def b_coefficient(r, vref):
    """b of delta = b u^(1/5) for pair_coeff ... r beta viscoelastic vref."""
    return inverse_restitution(r) / vref ** 0.2


def theta(T, b, m=1.0):
    """delta of a collision at the normal speed (4T/m)^(1/2)."""
    return b * (4.0 * T / m) ** 0.1


def loss_factor(th):
    """F(theta) = int_0^inf x e^-x (1 - E(theta x^(1/10))^2) dx, by quadrature with the core's E
    (x = y^10 removes the root at x = 0). 1 - E^2 is computed from E: below theta ~ 1e-3 its
    relative precision (E's 2e-11 over 2 C1 theta) falls under 1e-8; use loss_factor_series
    there."""
    E = core.viscoelastic_restitution

    def f(y):
        x = y ** 10
        return 10.0 * y ** 9 * x * math.exp(-x) * (1.0 - E(th * y) ** 2)
    return quad(f, 0.0, 1.0, epsabs=0, epsrel=1e-10, limit=200)[0] + \
        quad(f, 1.0, 3.0, epsabs=0, epsrel=1e-10, limit=200)[0]


def loss_factor_first_order(th):
    """F1(theta) = 2 C1 Gamma(21/10) theta."""
    return 2.0 * C1 * gamma(2.1) * th


def loss_factor_series(th):
    """F to second order: 2 C1 Gamma(21/10) theta - (C1^2 + 2 C2) Gamma(22/10) theta^2."""
    return 2.0 * C1 * gamma(2.1) * th - (C1 * C1 + 2.0 * C2) * gamma(2.2) * th * th


_TABLE = None


def loss_factor_interpolated(th):
    """F(theta) from a cubic spline of ln(F/F1) in ln theta over 1e-3 <= theta <= 1e3 (361
    quadratures, made once; within 1e-8 of loss_factor), the second-order series below (within
    1e-6 at theta = 1e-3, closer below), the quadrature above."""
    global _TABLE
    if _TABLE is None:
        from scipy.interpolate import CubicSpline
        x = np.linspace(math.log(1e-3), math.log(1e3), 361)
        y = [math.log(loss_factor(math.exp(u)) / loss_factor_first_order(math.exp(u))) for u in x]
        _TABLE = CubicSpline(x, y)
    u = math.log(th)
    if u < _TABLE.x[0]:
        return loss_factor_series(th)
    if u > _TABLE.x[-1]:
        return loss_factor(th)
    return loss_factor_first_order(th) * math.exp(float(_TABLE(u)))


def cooling_rate(T, b, dim, phi, a=0.5, m=1.0, order=None):
    """zeta(T) = nu(T)/d F(theta(T)); order=1: the first-order F1."""
    F = loss_factor_first_order if order == 1 else loss_factor_interpolated
    return cooling.collision_frequency(T, phi, a, m, dim) / dim * F(theta(T, b, m))


def first_order(t, r, vref, dim, phi, T0=1.0, a=0.5, m=1.0):
    """T(t) = T0 (1 + t/tau)^(-5/3), 1/tau = (3/5) zeta1(T0)."""
    z = cooling_rate(T0, b_coefficient(r, vref), dim, phi, a, m, order=1)
    return T0 * (1.0 + 0.6 * z * np.asarray(t, dtype=float)) ** (-5.0 / 3.0)


def haff(t, r, vref, dim, phi, T0=1.0, a=0.5, m=1.0):
    """Haff's law with the loss factor frozen at T0: T0 (1 + zeta(T0) t / 2)^-2."""
    z = cooling_rate(T0, b_coefficient(r, vref), dim, phi, a, m)
    return T0 * (1.0 + 0.5 * z * np.asarray(t, dtype=float)) ** -2.0


def cooling_curve(t, r, vref, dim, phi, T0=1.0, a=0.5, m=1.0, npts=400):
    """T(t) of dT/dt = -zeta(T) T with the exact F: t(T) = int_T^T0 dT'/(zeta(T') T') on a grid
    in ln T (Simpson), inverted by interpolation. t must stay where T > 1e-12 T0."""
    b = b_coefficient(r, vref)
    t = np.asarray(t, dtype=float)
    lo = math.log(T0) - 12.0 * math.log(10.0)
    # follow ln T down until the times asked are covered
    lnT = np.linspace(math.log(T0), lo, npts * 12 + 1)
    inv = np.array([1.0 / cooling_rate(math.exp(x), b, dim, phi, a, m) for x in lnT])
    h = lnT[0] - lnT[1]
    # cumulative trapezoid refined by the midpoints (Simpson on pairs of intervals)
    mid = np.array([1.0 / cooling_rate(math.exp(0.5 * (x + y)), b, dim, phi, a, m)
                    for x, y in zip(lnT[:-1], lnT[1:])])
    seg = h / 6.0 * (inv[:-1] + 4.0 * mid + inv[1:])
    tt = np.concatenate([[0.0], np.cumsum(seg)])
    if np.max(t) > tt[-1]:
        raise ValueError("times beyond T = 1e-12 T0")
    return np.exp(np.interp(t, tt, lnT))


def local_exponent(t, T):
    """d ln T / d ln t at the geometric midpoints of successive samples (t > 0)."""
    t, T = np.asarray(t, dtype=float), np.asarray(T, dtype=float)
    return np.sqrt(t[1:] * t[:-1]), np.diff(np.log(T)) / np.diff(np.log(t))


def local_slope(t, T, at, width=math.log(1.6)):
    """d ln T / d ln t at the times `at`: least-squares slope of ln T against ln t over the samples
    within a factor exp(width) of each (nan with fewer than 3)."""
    lt, lT = np.log(t), np.log(T)
    out = np.full(len(at), np.nan)
    for k, x in enumerate(np.log(at)):
        m = np.abs(lt - x) <= width
        if np.count_nonzero(m) >= 3:
            out[k] = np.polyfit(lt[m], lT[m], 1)[0]
    return out


# ------------------------------------------------------------------ the scene (examples/viscoelastic)

FLOW_ONSET = 0.02    # flow-field share of E_tr above which the gas is no longer homogeneous
SEEDS = (4321, 101, 102, 103)
# (dim, r at vref = 1, fraction): strongly dissipative start in 3D (the crossover), a nearly
# elastic start in 3D and 2D, and the 2D strongly dissipative start, which clusters
CASES = [(3, 0.5, 0.02), (3, 0.9, 0.02), (2, 0.9, 0.02), (2, 0.5, 0.02)]
VREF = 1.0


def read_run(path):
    """The cooling runs of a log (every thermo block after the equilibration) as one series:
    dict column -> array (the repeated first row of each later block dropped)."""
    blocks = lammpslog.read_thermo_blocks(path)[1:]
    cols = blocks[0][0]
    d = np.concatenate([blocks[0][1]] + [x[1:] for _, x in blocks[1:]])
    return {c: d[:, k] for k, c in enumerate(cols)}


def simulate(dim, r, phi, out, seed=4321, **extra):
    v = dict({"dim": dim, "r": r, "vref": VREF, "phi": phi, "seed": seed}, **extra)
    lmp.run(os.path.join(EXAMPLE, "in.cooling_ve"), v, log=out)
    return read_run(out)


def measure(dim, r, phi, logs, seeds=SEEDS, dsmc_N=20000, dsmc_runs=2, **extra):
    """Event-driven runs (seeds) and DSMC at their output times, the theories there, the
    local exponents, the onset of inhomogeneity: one dict."""
    runs = [simulate(dim, r, phi, os.path.join(logs, f"log.ve{dim}d_r{r}_phi{phi}.{s}"), seed=s,
                     **extra) for s in seeds]
    t = runs[0]["Time"]
    T = np.array([x["c_T[1]"] for x in runs])
    flow = np.max([x["v_flowfrac"] for x in runs], axis=0)
    N = {2: 64 ** 2, 3: 16 ** 3}[dim] if "nside" not in extra else extra["nside"] ** dim
    coll = np.mean([(x["f_ed[2]"] - x["f_ed[2]"][0]) * 2.0 / N for x in runs], axis=0)
    T0 = float(T[:, 0].mean())
    ks = dsmc.ensemble(r, -1.0, dim, phi, t, runs=dsmc_runs, N=dsmc_N, T0=T0, seed=11,
                       restitution=("viscoelastic", [VREF]))
    onset = int(np.argmax(flow > FLOW_ONSET)) if np.any(flow > FLOW_ONSET) else len(t)
    b = b_coefficient(r, VREF)
    tg = np.geomspace(2.0, t[-1] / 1.6, int(5 * math.log10(t[-1] / 3.2)) + 1)
    tf = np.geomspace(t[1] / 2, t[-1], 600)
    Tf = cooling_curve(tf, r, VREF, dim, phi, T0=T0)
    slope_seed = np.array([local_slope(t[1:], x[1:], tg) for x in T])
    return {
        "case": (dim, r, phi), "t": t, "T": T.mean(axis=0),
        "T_se": T.std(axis=0, ddof=1) / math.sqrt(len(T)), "flow": flow, "onset": onset,
        "t_onset": float(t[onset]) if onset < len(t) else math.inf, "collisions": coll,
        "theory": cooling_curve(t, r, VREF, dim, phi, T0=T0),
        "first": first_order(t, r, VREF, dim, phi, T0=T0), "haff": haff(t, r, VREF, dim, phi, T0=T0),
        "ks": ks["Ttr"][0], "ks_se": ks["Ttr"][1], "ks_a2": ks["a2_v"][0],
        "tg": tg, "slope": slope_seed.mean(axis=0),
        "slope_se": slope_seed.std(axis=0, ddof=1) / math.sqrt(len(T)),
        "slope_ks": local_slope(t[1:], ks["Ttr"][0][1:], tg),
        "tf": tf, "Tf": Tf, "slope_theory": np.gradient(np.log(Tf), np.log(tf)),
        "slope_first": -5.0 / 3.0 * (0.6 * cooling_rate(T0, b, dim, phi, order=1) * tf)
        / (1.0 + 0.6 * cooling_rate(T0, b, dim, phi, order=1) * tf),
        "theta0": theta(T0, b), "theta_end": theta(float(T.mean(axis=0)[-1]), b),
        "seeds": len(seeds),
    }


MARKS = (10.0, 100.0, 1e3, 1e4, 1e5, 1e6, 8.7e6)


def report(results, path):
    lines = ["# Free cooling of smooth viscoelastic particles", "",
             f"Event-driven runs (examples/viscoelastic/in.cooling_ve, N = 4096, {results[0]['seeds']} "
             "seeds, mean and standard error), the homogeneous theory with the exact E averaged over a "
             "Maxwellian (`cooling_curve`), its first order (`first_order`, T ~ t^-5/3), Haff's law "
             "frozen at the initial loss (`haff`) and the kinetic theory by DSMC with the same E. "
             f"vref = {VREF}; * marks times after the onset of inhomogeneity (flow energy > "
             f"{100 * FLOW_ONSET:.0f} % of E_tr in some seed).", ""]
    for c in results:
        dim, r, phi = c["case"]
        t = c["t"]
        lines += [f"## {dim}D, r = {r} at vref, fraction {phi}", "",
                  f"theta(T0) = {c['theta0']:.4f} (F/F1 = {loss_factor(c['theta0']) / loss_factor_first_order(c['theta0']):.3f}), "
                  f"theta(T_end) = {c['theta_end']:.4f} (F/F1 = {loss_factor(c['theta_end']) / loss_factor_first_order(c['theta_end']):.3f}); "
                  f"onset of inhomogeneity t = {c['t_onset']:.4g}; largest flow share {c['flow'].max():.3f}", "",
                  "| t | collisions/particle | T_tr (ED) | ED/theory - 1 | ED/DSMC - 1 | DSMC/theory - 1 | first order/theory - 1 | Haff(T0)/theory - 1 | DSMC a2 |",
                  "|---|---|---|---|---|---|---|---|---|"]
        for m in MARKS:
            if m > t[-1] * 1.01:
                continue
            k = int(np.argmin(np.abs(np.log(t[1:] / m)))) + 1
            star = "*" if k >= c["onset"] else ""
            se = c["T_se"][k] / c["T"][k]
            kse = math.hypot(se, c["ks_se"][k] / c["ks"][k])
            lines.append(f"| {t[k]:.4g}{star} | {c['collisions'][k]:.1f} | {c['T'][k]:.4g} | "
                         f"{100 * (c['T'][k] / c['theory'][k] - 1):+.1f} ± {100 * se:.1f} % | "
                         f"{100 * (c['T'][k] / c['ks'][k] - 1):+.1f} ± {100 * kse:.1f} % | "
                         f"{100 * (c['ks'][k] / c['theory'][k] - 1):+.1f} % | "
                         f"{100 * (c['first'][k] / c['theory'][k] - 1):+.0f} % | "
                         f"{100 * (c['haff'][k] / c['theory'][k] - 1):+.0f} % | {c['ks_a2'][k]:+.3f} |")
        ok = np.arange(len(t)) < c["onset"]
        dev = np.abs(c["T"] / c["theory"] - 1)[ok]
        devk = np.abs(c["T"] / c["ks"] - 1)[ok]
        lines += ["", f"Largest |ED/theory - 1| before the onset: {100 * dev.max():.1f} %; "
                  f"|ED/DSMC - 1|: {100 * devk.max():.1f} %.", "",
                  "Local exponent d ln T / d ln t (ED: mean over seeds ± s.e.; theory: exact Maxwellian "
                  "average; first order: -5/3 t/(t + tau)):", "",
                  "| t | ED | DSMC | theory | first order |", "|---|---|---|---|---|"]
        for k in range(0, len(c["tg"]), 2):
            x = c["tg"][k]
            star = "*" if x >= c["t_onset"] else ""
            th = np.interp(math.log(x), np.log(c["tf"]), c["slope_theory"])
            fo = np.interp(math.log(x), np.log(c["tf"]), c["slope_first"])
            lines.append(f"| {x:.3g}{star} | {c['slope'][k]:.3f} ± {c['slope_se'][k]:.3f} | "
                         f"{c['slope_ks'][k]:.3f} | {th:.3f} | {fo:.3f} |")
        lines.append("")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def plot(results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    fig, ax = plt.subplots(1, 3, figsize=(16, 5))
    for k, c in enumerate(results):
        dim, r, phi = c["case"]
        col = f"C{k}"
        t, m = c["t"], c["t"] > 0
        lab = f"{dim}D, r = {r} at vref = {VREF}"
        ax[0].loglog(t[m], c["T"][m], "o", ms=3, color=col, label=lab)
        ax[0].loglog(t[m], c["theory"][m], "-", color=col, lw=1)
        ax[0].loglog(t[m], c["first"][m], ":", color=col, lw=1)
        ax[0].loglog(t[m], c["haff"][m], "-.", color=col, lw=0.8)
        ax[1].semilogx(t[m], 100 * (c["T"][m] / c["theory"][m] - 1), "o-", ms=3, lw=0.8, color=col)
        ax[1].semilogx(t[m], 100 * (c["ks"][m] / c["theory"][m] - 1), "--", lw=1, color=col)
        ax[2].errorbar(c["tg"], c["slope"], yerr=c["slope_se"], fmt="o", ms=3, color=col)
        ax[2].semilogx(c["tf"], c["slope_theory"], "-", lw=1, color=col)
        ax[2].semilogx(c["tf"], c["slope_first"], ":", lw=1, color=col)
        if math.isfinite(c["t_onset"]):
            for x in ax:
                x.axvline(c["t_onset"], color=col, ls=":", lw=0.8)
    ax[2].set_xscale("log")
    for y in (-2.0, -5.0 / 3.0):
        ax[2].axhline(y, color="k", lw=0.5)
    ax[0].set_ylabel("T_tr")
    ax[1].set_ylabel("T / theory - 1 (%)")
    ax[1].set_ylim(-10, 25)
    ax[1].axhline(0, color="k", lw=0.5)
    ax[2].set_ylabel("local exponent d ln T / d ln t")
    ax[2].set_ylim(-2.05, 0.0)
    for x in ax:
        x.set_xlabel("time (diameter (m/T0)^1/2)")
    ax[0].legend(fontsize=8, loc="lower left")
    ax[1].legend(handles=[Line2D([], [], color="k", marker="o", ms=3, lw=0.8, label="event-driven (GRANFRIC)"),
                          Line2D([], [], color="k", ls="--", label="kinetic theory (DSMC)"),
                          Line2D([], [], color="k", ls=":", lw=0.8, label="onset of inhomogeneity")],
                 fontsize=8, loc="upper left")
    ax[2].legend(handles=[Line2D([], [], color="k", marker="o", ms=3, ls="", label="event-driven"),
                          Line2D([], [], color="k", ls="-", label="homogeneous theory, exact E"),
                          Line2D([], [], color="k", ls=":", label="first order: -5/3 t/(t + tau)")],
                 fontsize=8, loc="upper right")
    fig.suptitle("Free cooling of smooth viscoelastic particles: event-driven (symbols), homogeneous "
                 "theory with the exact E (solid), first order (dotted), Haff at T0 (dash-dot), "
                 "DSMC (dashed)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main(argv=None):
    a = cli.scene_args(argv, __doc__, "out/viscoelastic",
                       f"{len(CASES)} cases, {len(SEEDS)} seeds, DSMC N = 20000 x 2 (~4 min)",
                       "the same with DSMC N = 50000 x 4")
    N, runs = (50000, 4) if a.full else (20000, 2)
    results = [measure(dim, r, phi, a.logs, dsmc_N=N, dsmc_runs=runs)
               for dim, r, phi in cli.progress(CASES, "cases")]
    plot(results, os.path.join(a.out, "cooling_ve.png"))
    report(results, os.path.join(a.out, "report.md"))
    print(open(os.path.join(a.out, "report.md")).read())


if __name__ == "__main__":
    main()
