"""Luding et al. 1998 scene: free cooling of rough discs (2D) and spheres (3D) with constant r
and beta, simulated with GRANFRIC (examples/cooling) and compared with the mean-field theory of
the homogeneous cooling state (granfric.cooling).

    PYTHONPATH=tools /usr/bin/python3 -m granfric.luding [--quick|--full] [--out DIR]

Agreement is measured up to the onset of clustering, detected independently of the theory: the
fraction of translational energy carried by the coarse-grained flow field (compute
temp/profile) exceeds FLOW_ONSET.
"""
import math
import os

import numpy as np

from . import cli, cooling, lammpslog, lmp

EXAMPLE = os.path.join(lmp.ROOT, "examples", "cooling")
FLOW_ONSET = 0.02    # 2 % of E_tr in the 8x8 (4x4x4) flow field: clustering/vortices set in


def simulate(dim, r, beta, phi, tend, out, nside=None, seed=4321, tc=0.0):
    script = os.path.join(EXAMPLE, f"in.cooling{dim}d")
    v = {"r": r, "beta": beta, "phi": phi, "tend": tend, "out": out, "seed": seed, "tc": tc}
    if nside:
        v["nside"] = nside
    lmp.run(script, v)
    return lammpslog.read_thermo(out)


def compare(d, dim, r, beta, phi):
    """Theory at the simulation's output times; relative deviations; clustering onset."""
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
    return {
        "t": t, "Ttr_th": Ttr, "Trot_th": Trot, "R_th": R_th, "onset_index": int(onset),
        "t_onset": float(t[onset]) if onset < len(t) else math.inf,
        "dev_Ttr": worst(dev_tr, window), "dev_Trot": worst(dev_rot, window & grown),
        "dev_R": worst(dev_R, window & grown), "R_inf": Rinf,
    }


CASES_QUICK = [(2, 0.9, 0.0, 0.05), (2, 0.9, 0.5, 0.05), (3, 0.9, 0.0, 0.05), (2, 0.9, 0.0, 0.25)]
CASES_FULL = [(2, 0.9, b, 0.05) for b in (-1.0, -0.5, 0.0, 0.5, 1.0)] + \
             [(3, 0.9, b, 0.05) for b in (-0.5, 0.0, 0.5)] + [(2, 0.9, 0.0, 0.25), (3, 0.9, 0.0, 0.2)]


def main(argv=None):
    a = cli.scene_args(argv, __doc__, "out/luding1998", "4 cases, t <= 400 (default)", "beta scan in 2D and 3D, t <= 2000")
    cases, tend = (CASES_FULL, 2000.0) if a.full else (CASES_QUICK, 400.0)
    results = []
    for dim, r, beta, phi in cli.progress(cases, "cooling runs"):
        log = os.path.join(a.out, f"log.cool{dim}d_r{r}_b{beta}_phi{phi}")
        d = simulate(dim, r, beta, phi, tend, log)
        results.append(((dim, r, beta, phi), d, compare(d, dim, r, beta, phi)))
    plot(results, os.path.join(a.out, "cooling.png"))
    report(results, os.path.join(a.out, "report.md"))
    print(open(os.path.join(a.out, "report.md")).read())


def plot(results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.5))
    for k, ((dim, r, beta, phi), d, c) in enumerate(results):
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
        if math.isfinite(c["t_onset"]):
            for x in ax:
                x.axvline(c["t_onset"], color=col, ls=":", lw=0.8)
    ax[0].set_ylabel("T_tr")
    ax[1].set_ylabel("T_rot")
    ax[2].set_ylabel("R = T_rot / T_tr")
    for x in ax:
        x.set_xlabel("time (diameter (m/T0)^1/2)")
    ax[0].legend(fontsize=7)
    fig.suptitle("Free cooling of rough particles: GRANFRIC (symbols) vs homogeneous-cooling theory "
                 "(lines); dotted: onset of clustering (flow energy > 2%)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def report(results, path):
    lines = ["# Luding et al. 1998: free cooling of rough particles", "",
             "Maximum relative deviation from the mean-field homogeneous cooling state before the "
             f"onset of clustering (flow energy fraction > {FLOW_ONSET}); T_rot and R are compared "
             "once R has grown to 10 % of its asymptotic value.", "",
             "| dim | r | beta | fraction | clustering onset t | dev T_tr | dev T_rot | dev R | R sim (end of window) | R theory (asymptotic) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for (dim, r, beta, phi), d, c in results:
        k = max(0, min(c["onset_index"], len(d["Time"])) - 1)
        lines.append(f"| {dim} | {r} | {beta} | {phi} | {c['t_onset']:.4g} | {100*c['dev_Ttr']:.2f} % | "
                     f"{100*c['dev_Trot']:.2f} % | {100*c['dev_R']:.2f} % | {d['c_T[3]'][k]:.4f} | {c['R_inf']:.4f} |")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
