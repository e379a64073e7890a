# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""The driven monolayer (in.driven, Herbst et al. 2005) with viscoelastic normal restitution in
place of a constant r: is the steady state, and the approach to it, robust to this change of the
Walton model?

For each friction coefficient mu the script
  1. runs in.driven with the constant r (several seeds) and measures the steady T_tr, T_rot;
  2. chooses vref (pair_coeff ... r mu rtmax viscoelastic vref: r is the restitution at the normal
     impact speed vref, E(b |g_n|^(1/5)) at other speeds) so that the Monte Carlo mean energy loss
     per collision (core.mean_energy_changes: Gaussian velocities and spins, flux-weighted, the
     C++ law) at that steady T_tr, T_rot equals the constant-r loss (common random numbers);
  3. runs in.driven with -var vref (the same seeds: the same initial state);
  4. compares steady T_tr, T_rot, R and the relaxation (slow rate fitted to the seed-averaged
     approach, and the integrated relaxation time of T_tr) with each other and with mean-field
     model E, for the viscoelastic case with r replaced by the flux-weighted effective restitution
     r_eff(T_tr), 1 - r_eff^2 = <(1 - E^2) g_n^2>_flux at the current T_tr.

    /usr/bin/python3 examples/driven/viscoelastic.py [--quick] [--reuse] [--out DIR] [--fig PNG]

Default: N = 128^2, 8 seeds, mu = 0.05, 0.5, inf, 400 time units each (about 8 minutes on one
core). --quick: N = 64^2, 4 seeds (about 1.5 minutes). --nseed K: K seeds; --mu: other mu. Logs and viscoelastic.md in --out (default
out/driven_viscoelastic), the figure in --fig (default viscoelastic.png next to this script).
"""
import argparse
import json
import math
import os
import sys
from types import SimpleNamespace

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "tools"))

from granfric import cooling, core, herbst, lammpslog, lmp  # noqa: E402
from granfric import herbst_figs as hf  # noqa: E402
from granfric import meanfield as mf  # noqa: E402

Q = 0.4                    # spheres
R0, RT = 0.95, 0.4         # r, rt_max (in.driven's defaults)
PHI, FDR, VDR, DT = 0.0866, 2.0, 0.1, 0.5
TEND = 400.0
INF = math.inf
NMC, MCSEED = 400000, 7    # Monte Carlo collisions for the matching (common random numbers)


# ------------------------------------------------------------------------------------------------
# viscoelastic restitution
# ------------------------------------------------------------------------------------------------
def b_of_vref(vref, r=R0):
    """delta = b |g_n|^(1/5) with E(b vref^(1/5)) = r (doc/conventions.rst)."""
    from scipy.optimize import brentq
    d = brentq(lambda x: core.viscoelastic_restitution(x) - r, 0.0, 64.0, xtol=1e-14)
    return d / vref ** 0.2


_U, _W = None, None


def r_eff(Ttr, b):
    """Flux-weighted effective restitution at T_tr: the normal relative speed g of colliding pairs
    (m = 1, 2D) has density ~ g exp(-g^2/(4 T_tr)), the normal loss (1/4)(1 - E^2) g^2, so
    1 - r_eff^2 = int (1 - E(b g^(1/5))^2) u e^-u du with g^2 = 4 T_tr u (generalised
    Gauss-Laguerre, 120 nodes; within 2e-7 of scipy's quad, r_eff_quad)."""
    global _U, _W
    if _U is None:
        from scipy.special import roots_genlaguerre
        _U, _W = roots_genlaguerre(120, 1.0)
    E = np.array([core.viscoelastic_restitution(b * (4.0 * Ttr * u) ** 0.1) for u in _U])
    return math.sqrt(float(np.sum(_W * E * E)))


def r_eff_quad(Ttr, b):
    from scipy.integrate import quad
    f = lambda u: core.viscoelastic_restitution(b * (4.0 * Ttr * u) ** 0.1) ** 2 * u * math.exp(-u)
    return math.sqrt(quad(f, 0.0, np.inf, limit=400, epsabs=1e-13)[0])


def mc_loss(mu, Ttr, Trot, vref=None):
    """Monte Carlo mean energy changes per collision (dict tr, rot, total) through the C++ law."""
    rest = None if vref is None else ("viscoelastic", [vref])
    return core.mean_energy_changes("walton", [R0, mu, RT], Q, 2, Ttr, Trot, n=NMC, seed=MCSEED,
                                    restitution=rest)


def match_vref(mu, Ttr, Trot):
    """vref with the same Monte Carlo mean total loss per collision at (T_tr, T_rot) as r = R0
    (same random collisions for both), and vref from r_eff(T_tr) = R0 (normal loss only)."""
    from scipy.optimize import brentq
    target = mc_loss(mu, Ttr, Trot)["total"]
    f = lambda lv: mc_loss(mu, Ttr, Trot, math.exp(lv))["total"] - target
    v_mc = math.exp(brentq(f, math.log(0.05), math.log(50.0), xtol=1e-6))
    g = lambda lv: r_eff(Ttr, b_of_vref(math.exp(lv))) - R0
    v_q = math.exp(brentq(g, math.log(0.05), math.log(50.0), xtol=1e-10))
    return v_mc, v_q, target


# ------------------------------------------------------------------------------------------------
# mean field (model E; viscoelastic: r -> r_eff(T_tr))
# ------------------------------------------------------------------------------------------------
def H_of(N):
    return hf.H_dr(FDR, VDR, N)


def mf_rhs(T, mu, G, H, b=None):
    r = R0 if b is None else r_eff(max(T[0], 1e-12), b)
    return mf.rhs(0.0, T, "E", r, RT, mu, Q, G, H)


def mf_steady_and_rates(mu, N, b=None):
    """Steady (T_tr, T_rot) and the two relaxation rates (1/time, slow first) of model E, with
    the viscoelastic r_eff(T_tr) when b is given (numerical Jacobian)."""
    from scipy.optimize import fsolve
    G, H = cooling.time_scale_G(PHI, 0.5, 1.0, 2), H_of(N)
    T0 = np.array(mf.steady_state_temperatures("E", R0, RT, mu, Q, PHI, H_dr=H))
    if b is None:
        Ts = T0
    else:
        Ts = fsolve(lambda x: mf_rhs(x * T0, mu, G, H, b) / T0, np.ones(2), xtol=1e-13) * T0
    J = np.zeros((2, 2))
    for j in range(2):
        h = 1e-6 * Ts[0]
        p, m = Ts.copy(), Ts.copy()
        p[j] += h
        m[j] -= h
        J[:, j] = (mf_rhs(p, mu, G, H, b) - mf_rhs(m, mu, G, H, b)) / (2 * h)
    ev = np.sort(np.abs(np.real(np.linalg.eigvals(J))))
    return Ts, ev


def mf_series(mu, N, T0, times, b=None):
    from scipy.integrate import solve_ivp
    G, H = cooling.time_scale_G(PHI, 0.5, 1.0, 2), H_of(N)
    s = solve_ivp(lambda t, T: mf_rhs(T, mu, G, H, b), (times[0], times[-1]), np.array(T0, float),
                  t_eval=times, method="DOP853", rtol=1e-9, atol=1e-12)
    return s.y[0], s.y[1]


# ------------------------------------------------------------------------------------------------
# simulations
# ------------------------------------------------------------------------------------------------
def simulate(mu, seed, vref, nside, logs, reuse):
    """in.driven (with the series fixes of granfric.herbst) for one seed; vref = 0: constant r.
    Returns the T_tr, T_rot, R series every time unit."""
    tag = "const" if not vref else f"ve{vref:.6g}"
    out = os.path.join(logs, f"log.mu{mu}_n{nside}_{tag}_seed{seed}")
    tfile = out + ".T"
    if not (reuse and os.path.exists(tfile) and os.path.exists(out)
            and "Total wall time" in open(out).read()):
        v = {"r": R0, "mu": "inf" if mu == INF else mu, "rtmax": RT, "phi": PHI, "tend": TEND,
             "nside": nside, "fdr": FDR, "vdr": VDR, "seed": seed, "dt": DT, "vref": vref or 0,
             "tevery": int(round(1.0 / DT)), "tfile": tfile, "gfile": out + ".gamma"}
        lmp.run(herbst._script_with_series(logs), v, log=out)
    s = lammpslog.read_ave_time(tfile)
    return {"Time": s["TimeStep"] * DT, "Ttr": s["c_T[1]"], "Trot": s["c_T[2]"], "R": s["c_T[3]"]}


def steady(runs):
    """Second-half averages per seed; mean and standard error over the seeds."""
    out = {}
    for k in ("Ttr", "Trot", "R"):
        v = np.array([x[k][x["Time"] > 0.5 * TEND].mean() for x in runs])
        out[k], out[k + "_err"] = float(v.mean()), float(v.std(ddof=1) / math.sqrt(len(v)))
    return out


def tau_int(t, Ttr, Ts, tmax=0.5 * TEND):
    """Integrated relaxation time of T_tr: int_0^tmax (T_tr - T_s)/(T_tr(0) - T_s) dt."""
    m = t <= tmax
    trapz = getattr(np, "trapezoid", None) or np.trapz
    return float(trapz((Ttr[m] - Ts) / (Ttr[0] - Ts), t[m]))


def relaxation(runs):
    """Slow rate (1/time) fitted to the seed-averaged approach (granfric.herbst_figs.fit_slow_rate,
    steady values fixed at the second-half means) and tau_int; errors from the single seeds."""
    n = min(len(x["Time"]) for x in runs)
    t = runs[0]["Time"][:n]
    late = t > 0.5 * TEND
    a = np.mean([x["Ttr"][:n] for x in runs], axis=0)
    b = np.mean([x["Trot"][:n] for x in runs], axis=0)
    f = hf.fit_slow_rate(t, a, b, a[late].mean(), b[late].mean())
    single, ti = [], []
    for x in runs:
        xa, xb = x["Ttr"][:n], x["Trot"][:n]
        g = hf.fit_slow_rate(t, xa, xb, xa[late].mean(), xb[late].mean())
        if g is not None:
            single.append(g[0])
        ti.append(tau_int(t, xa, xa[late].mean()))
    k = len(single)
    return {"lam": f[0], "lam_err": float(np.std(single, ddof=1) / math.sqrt(k)) if k > 1 else f[1],
            "tau_int": float(np.mean(ti)), "tau_int_err": float(np.std(ti, ddof=1) / math.sqrt(len(ti))),
            "t": t, "Ttr": a, "Trot": b, "R": np.mean([x["R"][:n] for x in runs], axis=0)}


# ------------------------------------------------------------------------------------------------
def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="N = 64^2, 4 seeds")
    ap.add_argument("--reuse", action="store_true", help="reuse finished logs in --out")
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "driven_viscoelastic"))
    ap.add_argument("--fig", default=os.path.join(HERE, "viscoelastic.png"))
    ap.add_argument("--mu", type=float, nargs="+", default=[0.05, 0.5, INF])
    ap.add_argument("--nseed", type=int, help="seeds per case (default 8, --quick 4)")
    a = ap.parse_args(argv)
    nside, nseed = (64, 4) if a.quick else (128, 8)
    nseed = a.nseed or nseed
    N = nside * nside
    seeds = [4321 + 1000 * k for k in range(nseed)]
    logs = os.path.join(a.out, "logs")
    os.makedirs(logs, exist_ok=True)
    res = {}
    for mu in a.mu:
        print(f"mu = {mu}: {nseed} constant-r runs, N = {N}", flush=True)
        cr = [simulate(mu, s, 0, nside, logs, a.reuse) for s in seeds]
        sc = steady(cr)
        v_mc, v_q, loss = match_vref(mu, sc["Ttr"], sc["Trot"])
        print(f"  steady T_tr {sc['Ttr']:.4f} T_rot {sc['Trot']:.4f}: vref {v_mc:.4f} "
              f"(MC total loss), {v_q:.4f} (r_eff = r)", flush=True)
        vr = [simulate(mu, s, round(v_mc, 4), nside, logs, a.reuse) for s in seeds]
        sv = steady(vr)
        vref = round(v_mc, 4)
        b = b_of_vref(vref)
        rc, rv = relaxation(cr), relaxation(vr)
        # the loss of the viscoelastic law at the viscoelastic steady state, and r_eff there
        mc_c = mc_loss(mu, sc["Ttr"], sc["Trot"])
        mc_v = mc_loss(mu, sc["Ttr"], sc["Trot"], vref)
        Tc, evc = mf_steady_and_rates(mu, N)
        Tv, evv = mf_steady_and_rates(mu, N, b)
        T0 = (rc["Ttr"][0], rc["Trot"][0])
        mfc = mf_series(mu, N, T0, rc["t"])
        mfv = mf_series(mu, N, T0, rc["t"], b)
        # paired relative difference of T_tr(t): viscoelastic / constant - 1, per seed
        n = len(rc["t"])
        dT = np.array([v["Ttr"][:n] / c["Ttr"][:n] - 1.0 for c, v in zip(cr, vr)])
        res[mu] = SimpleNamespace(
            mu=mu, vref=vref, vref_q=v_q, loss=loss, sc=sc, sv=sv, rc=rc, rv=rv,
            mc_c=mc_c, mc_v=mc_v, r_eff_c=r_eff(sc["Ttr"], b), r_eff_v=r_eff(sv["Ttr"], b),
            r_eff_1=r_eff(1.0, b), Tc=Tc, Tv=Tv, evc=evc, evv=evv, mfc=mfc, mfv=mfv,
            tau_mf_c=tau_int(rc["t"], mfc[0], Tc[0]), tau_mf_v=tau_int(rc["t"], mfv[0], Tv[0]),
            dT=dT.mean(axis=0), dT_err=dT.std(axis=0, ddof=1) / math.sqrt(len(dT)))
        print(f"  T_tr {sc['Ttr']:.4f} -> {sv['Ttr']:.4f}, R {sc['R']:.4f} -> {sv['R']:.4f}, "
              f"slow rate {rc['lam']:.4f} -> {rv['lam']:.4f}, tau_int {rc['tau_int']:.2f} -> "
              f"{rv['tau_int']:.2f}", flush=True)
    text = report(res, N, nseed)
    with open(os.path.join(a.out, "viscoelastic.md"), "w") as f:
        f.write(text)
    print(text)
    plot(res, a.fig, N, nseed)
    dump = {str(mu): {k: (v if not isinstance(v, np.ndarray) else None) for k, v in vars(x).items()
                      if k in ("vref", "vref_q", "loss", "sc", "sv", "r_eff_c", "r_eff_v",
                               "r_eff_1", "tau_mf_c", "tau_mf_v")}
            for mu, x in res.items()}
    for mu, x in res.items():
        d = dump[str(mu)]
        d.update(lam_c=x.rc["lam"], lam_c_err=x.rc["lam_err"], lam_v=x.rv["lam"],
                 lam_v_err=x.rv["lam_err"], tau_c=x.rc["tau_int"], tau_c_err=x.rc["tau_int_err"],
                 tau_v=x.rv["tau_int"], tau_v_err=x.rv["tau_int_err"], Tc=list(x.Tc), Tv=list(x.Tv),
                 evc=list(x.evc), evv=list(x.evv), mc_c=x.mc_c, mc_v=x.mc_v)
    with open(os.path.join(a.out, "viscoelastic.json"), "w") as f:
        json.dump(dump, f, indent=1)


def _pm(x, e, d=4):
    return f"{x:.{d}f} ± {e:.{d}f}"


def _dev(a, ea, b, eb):
    return f"{100 * (b / a - 1):+.1f} ± {100 * math.hypot(ea / a, eb * 1.0 / a):.1f} %"


def report(res, N, nseed):
    L = [f"N = {N}, fraction {PHI}, r = {R0}, rt_max = {RT}, f_dr = {FDR}, v_dr = {VDR}, "
         f"{TEND:g} time units, {nseed} seeds (mean ± standard error over seeds; steady values "
         f"from the second half).", "",
         "| μ | model | vref | T_tr | T_rot | R | slow rate | τ_int of T_tr |",
         "|---|---|---|---|---|---|---|---|"]
    for mu, x in res.items():
        m = "∞" if mu == INF else f"{mu:g}"
        for lab, s, rr, v in (("constant r", x.sc, x.rc, "–"), ("viscoelastic", x.sv, x.rv, f"{x.vref:.4g}")):
            L.append(f"| {m} | {lab} | {v} | {_pm(s['Ttr'], s['Ttr_err'])} | "
                     f"{_pm(s['Trot'], s['Trot_err'])} | {_pm(s['R'], s['R_err'])} | "
                     f"{_pm(rr['lam'], rr['lam_err'], 3)} | {_pm(rr['tau_int'], rr['tau_int_err'], 1)} |")
        L.append(f"| {m} | change | | {_dev(x.sc['Ttr'], x.sc['Ttr_err'], x.sv['Ttr'], x.sv['Ttr_err'])} | "
                 f"{_dev(x.sc['Trot'], x.sc['Trot_err'], x.sv['Trot'], x.sv['Trot_err'])} | "
                 f"{_dev(x.sc['R'], x.sc['R_err'], x.sv['R'], x.sv['R_err'])} | "
                 f"{_dev(x.rc['lam'], x.rc['lam_err'], x.rv['lam'], x.rv['lam_err'])} | "
                 f"{_dev(x.rc['tau_int'], x.rc['tau_int_err'], x.rv['tau_int'], x.rv['tau_int_err'])} |")
    L += ["", "Mean-field model E (constant r, and with r -> r_eff(T_tr) for the viscoelastic law):", "",
          "| μ | model | T_tr | T_rot | R | slow rate | fast rate | τ_int of T_tr |",
          "|---|---|---|---|---|---|---|---|"]
    for mu, x in res.items():
        m = "∞" if mu == INF else f"{mu:g}"
        for lab, T, ev, ti in (("E, constant r", x.Tc, x.evc, x.tau_mf_c),
                               ("E, r_eff(T_tr)", x.Tv, x.evv, x.tau_mf_v)):
            L.append(f"| {m} | {lab} | {T[0]:.4f} | {T[1]:.4f} | {T[1] / T[0]:.4f} | {ev[0]:.4f} | "
                     f"{ev[1]:.4f} | {ti:.2f} |")
    L += ["", "Matching (Monte Carlo at the constant-r steady state, 4e5 collisions, common random "
          "numbers):", "",
          "| μ | vref (MC total loss) | vref (r_eff = r) | r_eff at T_tr = 1 | r_eff at steady T_tr | "
          "<ΔE_tr> const / visco | <ΔE_rot> const / visco |", "|---|---|---|---|---|---|---|"]
    for mu, x in res.items():
        m = "∞" if mu == INF else f"{mu:g}"
        L.append(f"| {m} | {x.vref:.4f} | {x.vref_q:.4f} | {x.r_eff_1:.5f} | {x.r_eff_c:.5f} | "
                 f"{x.mc_c['tr']:.5f} / {x.mc_v['tr']:.5f} | {x.mc_c['rot']:.5f} / {x.mc_v['rot']:.5f} |")
    return "\n".join(L) + "\n"


def plot(res, path, N, nseed):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.4))
    for k, (mu, x) in enumerate(res.items()):
        col = f"C{k}"
        m = "∞" if mu == INF else f"{mu:g}"
        t = x.rc["t"]
        s = t > 0
        ax[0].semilogx(t[s], x.rc["Ttr"][s], "o", ms=3, color=col, mfc="none", label=f"μ = {m}, constant r")
        ax[0].semilogx(t[s], x.rv["Ttr"][s], "x", ms=3, color=col, label=f"μ = {m}, viscoelastic (vref {x.vref:.3g})")
        ax[0].semilogx(t[s], x.mfc[0][s], "-", color=col, lw=1)
        ax[0].semilogx(t[s], x.mfv[0][s], "--", color=col, lw=1)
        Rc = np.where(x.mfc[0] > 0, x.mfc[1] / x.mfc[0], 0)
        Rv = np.where(x.mfv[0] > 0, x.mfv[1] / x.mfv[0], 0)
        ax[1].semilogx(t[s], x.rc["R"][s], "o", ms=3, color=col, mfc="none")
        ax[1].semilogx(t[s], x.rv["R"][s], "x", ms=3, color=col)
        ax[1].semilogx(t[s], Rc[s], "-", color=col, lw=1)
        ax[1].semilogx(t[s], Rv[s], "--", color=col, lw=1)
        ax[2].semilogx(t[s], 100 * x.dT[s], "-", color=col, lw=1, label=f"μ = {m}, simulated (paired seeds)")
        ax[2].fill_between(t[s], 100 * (x.dT - x.dT_err)[s], 100 * (x.dT + x.dT_err)[s], color=col, alpha=0.2)
        ax[2].semilogx(t[s], 100 * (x.mfv[0] / x.mfc[0] - 1)[s], "--", color=col, lw=1.5,
                       label=f"μ = {m}, model E with r_eff(T_tr)")
    ax[0].set_ylabel("T_tr")
    ax[1].set_ylabel("R = T_rot / T_tr")
    ax[2].set_ylabel("T_tr viscoelastic / T_tr constant r − 1  (%)")
    ax[2].axhline(0, color="k", lw=0.5)
    ax[2].set_ylim(-3, 3)
    for y in ax:
        y.set_xlabel("time")
    ax[0].legend(fontsize=7)
    ax[2].legend(fontsize=7)
    fig.suptitle(f"Driven monolayer, r = {R0} (at vref), rt_max = {RT}, N = {N}, fraction {PHI}, "
                 f"mean of {nseed} seeds: constant r (o) vs viscoelastic (x); model E "
                 "(solid: constant r, dashed: r_eff(T_tr))", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
