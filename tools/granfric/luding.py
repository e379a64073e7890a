# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Luding et al. 1998 scene: free cooling of rough discs (2D) and spheres (3D) with constant r
and beta, simulated with GRANFRIC (examples/cooling) and compared with two theories of the
homogeneous cooling state: the mean-field ODEs (granfric.cooling: Gaussian velocities and spins,
molecular chaos) and the kinetic theory without the Gaussian closure, the homogeneous
Enskog-Boltzmann equation solved by DSMC through the same C++ collision law (granfric.dsmc).

    PYTHONPATH=tools /usr/bin/python3 -m granfric.luding [--quick|--full] [--seeds K] [--out DIR]

(--seeds K: K runs per case, seed 4321 and 101, 102, ..., averaged; the report then gives the
deviations with the seed scatter as error)

Agreement is measured up to the onset of clustering, detected independently of the theory: the
fraction of translational energy carried by the coarse-grained flow field (compute
temp/profile) exceeds FLOW_ONSET.
"""
import math
import os

import numpy as np

from . import cli, cooling, dsmc, lammpslog, lmp

EXAMPLE = os.path.join(lmp.ROOT, "examples", "cooling")
FLOW_ONSET = 0.02    # 2 % of E_tr in the 8x8 (4x4x4) flow field: clustering/vortices set in


def simulate(dim, r, beta, phi, tend, out, nside=None, seed=4321, tc=0.0):
    script = os.path.join(EXAMPLE, f"in.cooling{dim}d")
    v = {"r": r, "beta": beta, "phi": phi, "tend": tend, "seed": seed, "tc": tc}
    if nside:
        v["nside"] = nside
    lmp.run(script, v, log=out)
    return lammpslog.read_thermo(out)


def kinetic(dim, r, beta, phi, t, T0, N=20000, runs=4, seed=11):
    """The kinetic theory (DSMC, no Gaussian closure) at the output times t from the scene's
    initial state (Maxwellian at T_tr = T0, no spin): dsmc.ensemble, key -> (mean, se)."""
    return dsmc.ensemble(r, beta, dim, phi, t, runs=runs, N=N, T0=T0, seed=seed)


def average(runs):
    """Mean over runs of the same case (same output times) and its standard error (seed
    scatter; None for one run): (mean dict, se dict or None)."""
    mean = {k: np.mean([x[k] for x in runs], axis=0) for k in runs[0]}
    if len(runs) < 2:
        return mean, None
    se = {k: np.std([x[k] for x in runs], axis=0, ddof=1) / math.sqrt(len(runs)) for k in runs[0]}
    return mean, se


SIM = {"Ttr": "c_T[1]", "Trot": "c_T[2]", "R": "c_T[3]"}


def compare(d, dim, r, beta, phi, ks=None, d_se=None):
    """Theory at the simulation's output times; relative deviations; clustering onset. With ks
    (kinetic(...) at the same times) also the deviations from the kinetic theory (dev_ks_*, the
    time of the largest one t_ks_*, its standard error dev_ks_*_se from DSMC and, with d_se, the
    simulation's seed scatter) and the closure error of the mean-field theory, mean field /
    DSMC - 1 (closure_*), over the same windows."""
    q = 0.5 if dim == 2 else 0.4
    t = d["Time"]
    _, Ttr, Trot = cooling.integrate(r, beta, q, dim, phi, a=0.5, m=1.0,
                                     T0=(d["c_T[1]"][0], d["c_T[2]"][0]), times=t)
    flow = d["v_flowfrac"]
    onset = np.argmax(flow > FLOW_ONSET) if np.any(flow > FLOW_ONSET) else len(t)
    dev_tr = d["c_T[1]"] / Ttr - 1
    with np.errstate(divide="ignore", invalid="ignore"):
        dev_rot = np.where(Trot > 0, d["c_T[2]"] / Trot - 1, 0)
        R_th = np.where(Ttr > 0, Trot / Ttr, 0)
        dev_R = np.where(R_th > 0, d["c_T[3]"] / R_th - 1, 0)
    # T_rot and R start from 0: compare them once T_rot carries 10 % of its asymptotic share
    Rinf = cooling.asymptotic_R(r, beta, q, dim)
    grown = R_th > 0.1 * Rinf if Rinf > 0 else np.zeros_like(t, dtype=bool)
    window = np.arange(len(t)) < onset
    def worst(x, mask):
        return float(np.max(np.abs(x[mask]))) if np.any(mask) else 0.0
    out = {
        "t": t, "Ttr_th": Ttr, "Trot_th": Trot, "R_th": R_th, "onset_index": int(onset),
        "t_onset": float(t[onset]) if onset < len(t) else math.inf,
        "dev_Ttr": worst(dev_tr, window), "dev_Trot": worst(dev_rot, window & grown),
        "dev_R": worst(dev_R, window & grown), "R_inf": Rinf,
    }
    if ks is not None:
        mf = {"Ttr": Ttr, "Trot": Trot, "R": R_th}
        for key, mask in (("Ttr", window), ("Trot", window & grown), ("R", window & grown)):
            x, e = ks[key]
            y = d[SIM[key]]
            ey = d_se[SIM[key]] if d_se is not None else np.zeros_like(y)
            with np.errstate(divide="ignore", invalid="ignore"):
                ok = (x > 0) & (y > 0)
                dev = np.where(ok, y / x - 1, 0)
                clo = np.where(ok, mf[key] / x - 1, 0)
                rel_se = np.where(ok, np.hypot(e / x, ey / y), 0)
            out[f"{key}_ks"], out[f"{key}_ks_se"] = x, e
            out[f"ks_dev_{key}"], out[f"ks_dev_{key}_se"] = dev, rel_se    # at every output time
            k = int(np.flatnonzero(mask)[np.argmax(np.abs(dev[mask]))]) if np.any(mask) else 0
            out[f"dev_ks_{key}"] = worst(dev, mask)
            out[f"dev_ks_{key}_se"] = float(rel_se[k]) if np.any(mask) else 0.0
            out[f"t_ks_{key}"] = float(t[k]) if np.any(mask) else math.nan
            out[f"closure_{key}"] = worst(clo, mask)
    return out


CASES_QUICK = [(2, 0.9, 0.0, 0.05), (2, 0.9, 0.5, 0.05), (3, 0.9, 0.0, 0.05), (2, 0.9, 0.0, 0.25)]
CASES_FULL = [(2, 0.9, b, 0.05) for b in (-1.0, -0.5, 0.0, 0.5, 1.0)] + \
             [(3, 0.9, b, 0.05) for b in (-0.5, 0.0, 0.5)] + [(2, 0.9, 0.0, 0.25), (3, 0.9, 0.0, 0.2)]


def main(argv=None):
    def seeds_option(ap):
        def count(text):
            k = int(text)
            if k < 1:
                raise ValueError(text)
            return k
        count.__name__ = "number of seeds (>= 1)"
        ap.add_argument("--seeds", type=count, default=1,
                        help="runs per case, averaged, their scatter as the error (default 1)")
    a = cli.scene_args(argv, __doc__, "out/luding1998", "4 cases, t <= 400 (default)",
                       "beta scan in 2D and 3D, t <= 2000", extra=seeds_option)
    nseeds = a.seeds
    cases, tend = (CASES_FULL, 2000.0) if a.full else (CASES_QUICK, 400.0)
    N = 100000 if a.full else 20000
    results = []
    for dim, r, beta, phi in cli.progress(cases, "cooling runs"):
        log = os.path.join(a.logs, f"log.cool{dim}d_r{r}_b{beta}_phi{phi}")
        seeds = [4321] + [101 + k for k in range(nseeds - 1)]
        runs = [simulate(dim, r, beta, phi, tend, log + (f".seed{s}" if s != 4321 else ""), seed=s)
                for s in seeds]
        d, d_se = average(runs)
        ks = kinetic(dim, r, beta, phi, d["Time"], d["c_T[1]"][0], N=N)
        results.append(((dim, r, beta, phi), d, compare(d, dim, r, beta, phi, ks, d_se), nseeds))
    plot(results, os.path.join(a.out, "cooling.png"))
    report(results, os.path.join(a.out, "report.md"))
    print(open(os.path.join(a.out, "report.md")).read())


def plot(results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.5))
    for k, ((dim, r, beta, phi), d, c, _) in enumerate(results):
        col = f"C{k}"
        lab = f"{dim}D r={r} beta={beta} phi={phi}"
        t = d["Time"]
        m = t > 0
        ax[0].loglog(t[m], d["c_T[1]"][m], "o", ms=3, color=col, label=lab)
        ax[0].loglog(t[m], c["Ttr_th"][m], "-", color=col)
        ax[1].loglog(t[m], d["c_T[2]"][m], "o", ms=3, color=col)
        ax[1].loglog(t[m], c["Trot_th"][m], "-", color=col)
        ax[2].semilogx(t[m], d["c_T[3]"][m], "o", ms=3, color=col)
        ax[2].semilogx(t[m], c["R_th"][m], "-", color=col)
        if "Ttr_ks" in c:
            for key, f in (("Ttr", ax[0].loglog), ("Trot", ax[1].loglog), ("R", ax[2].semilogx)):
                f(t[m], c[f"{key}_ks"][m], "--", color=col, lw=1.2)
        if math.isfinite(c["t_onset"]):
            for x in ax:
                x.axvline(c["t_onset"], color=col, ls=":", lw=0.8)
    ax[0].set_ylabel("T_tr")
    ax[1].set_ylabel("T_rot")
    ax[2].set_ylabel("R = T_rot / T_tr")
    for x in ax:
        x.set_xlabel("time (diameter (m/T0)^1/2)")
    ax[0].legend(fontsize=7)
    from matplotlib.lines import Line2D
    ax[2].legend(handles=[Line2D([], [], color="k", marker="o", ms=3, ls="", label="GRANFRIC (event-driven)"),
                          Line2D([], [], color="k", ls="-", label="mean-field theory (Gaussian closure)"),
                          Line2D([], [], color="k", ls="--", label="kinetic theory (DSMC, no Gaussian closure)"),
                          Line2D([], [], color="k", ls=":", lw=0.8, label="onset of clustering")],
                 fontsize=7, loc="lower right")
    fig.suptitle("Free cooling of rough particles: GRANFRIC (symbols) vs homogeneous-cooling theories: "
                 "mean field (solid), kinetic theory by DSMC (dashed); dotted: onset of clustering "
                 "(flow energy > 2%)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def report(results, path):
    lines = ["# Luding et al. 1998: free cooling of rough particles", "",
             "Maximum relative deviation from the mean-field homogeneous cooling state before the "
             f"onset of clustering (flow energy fraction > {FLOW_ONSET}); T_rot and R are compared "
             "once R has grown to 10 % of its asymptotic value.", "",
             "| dim | r | beta | fraction | clustering onset t | dev T_tr | dev T_rot | dev R | R sim (end of window) | R theory (asymptotic) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for (dim, r, beta, phi), d, c, _ in results:
        k = max(0, min(c["onset_index"], len(d["Time"])) - 1)
        lines.append(f"| {dim} | {r} | {beta} | {phi} | {c['t_onset']:.4g} | {100*c['dev_Ttr']:.2f} % | "
                     f"{100*c['dev_Trot']:.2f} % | {100*c['dev_R']:.2f} % | {d['c_T[3]'][k]:.4f} | {c['R_inf']:.4f} |")
    if all("Ttr_ks" in c for _, _, c, _ in results):
        lines += ["", "Kinetic theory without the Gaussian closure (homogeneous Enskog-Boltzmann "
                  "equation by DSMC through the same C++ collision law, granfric.dsmc), same windows: "
                  "largest relative deviation of the simulation from it, with the standard error "
                  "there (DSMC and, with several seeds, the seeds' scatter; one run of N = 4096 "
                  "alone scatters by ~1/sqrt(N) in T_tr and several % in T_rot at early times) and "
                  "the time where it occurs; and the closure error of the mean-field theory, "
                  "max |mean field / DSMC - 1|.", "",
                  "| dim | r | beta | fraction | seeds | sim vs DSMC: T_tr | T_rot | R | mean field vs DSMC: T_tr | T_rot | R |",
                  "|---|---|---|---|---|---|---|---|---|---|---|"]
        for (dim, r, beta, phi), d, c, nseeds in results:
            ks = " | ".join(f"{100*c[f'dev_ks_{k}']:.2f} ± {100*c[f'dev_ks_{k}_se']:.2f} % (t = {c[f't_ks_{k}']:.3g})"
                            for k in ("Ttr", "Trot", "R"))
            cl = " | ".join(f"{100*c[f'closure_{k}']:.2f} %" for k in ("Ttr", "Trot", "R"))
            lines.append(f"| {dim} | {r} | {beta} | {phi} | {nseeds} | {ks} | {cl} |")
        marks = [5, 10, 20, 50, 100, 200, 400, 1000, 2000]
        t = results[0][1]["Time"]
        marks = [m for m in marks if m <= t[-1] * 1.001]
        lines += ["", "Simulation / DSMC - 1 at the output times nearest to these (± standard error; "
                  "* after the onset of clustering):", "",
                  "| dim | beta | fraction | | " + " | ".join(f"t = {m}" for m in marks) + " |",
                  "|---|---|---|---|" + "---|" * len(marks)]
        for (dim, r, beta, phi), d, c, _ in results:
            tt = d["Time"]
            for key in ("Ttr", "Trot", "R"):
                cells = []
                for m in marks:
                    k = int(np.argmin(np.abs(tt - m)))
                    star = "*" if tt[k] >= c["t_onset"] else ""
                    cells.append(f"{100 * c[f'ks_dev_{key}'][k]:+.1f} ± {100 * c[f'ks_dev_{key}_se'][k]:.1f}{star}")
                lines.append(f"| {dim} | {beta} | {phi} | {key} | " + " | ".join(cells) + " |")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
