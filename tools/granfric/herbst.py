"""Herbst et al. 2005 scene: randomly driven 2D monolayer of rough spheres (q = 2/5) with Coulomb
friction (Walton law), simulated with GRANFRIC (examples/driven) and compared with the mean-field
model E (granfric.meanfield) in the steady state.

    PYTHONPATH=tools /usr/bin/python3 -m granfric.herbst [--quick|--full] [--out DIR]
"""
import math
import os

import numpy as np

from . import cli, cooling, lammpslog, lmp

EXAMPLE = os.path.join(lmp.ROOT, "examples", "driven")
Q = 0.4


def simulate(r, mu, rtmax, phi, tend, out, nside=64, fdr=2.0, vdr=0.1, seed=4321, dt=0.5):
    v = {"r": r, "mu": mu, "rtmax": rtmax, "phi": phi, "tend": tend, "out": out, "nside": nside,
         "fdr": fdr, "vdr": vdr, "seed": seed, "dt": dt}
    lmp.run(os.path.join(EXAMPLE, "in.driven"), v)
    return lammpslog.read_thermo(out)


def steady(d, tfrac=0.5):
    """Time averages over the last (1 - tfrac) of the run, with block standard errors."""
    t = d["Time"]
    sel = t > tfrac * t[-1]
    out = {}
    for key, name in (("c_T[1]", "Ttr"), ("c_T[2]", "Trot"), ("c_T[3]", "R")):
        x = d[key][sel]
        blocks = np.array_split(x, 4)
        means = np.array([b.mean() for b in blocks if len(b)])
        out[name] = float(x.mean())
        out[name + "_err"] = float(means.std(ddof=1) / math.sqrt(len(means))) if len(means) > 1 else float("nan")
    return out


def theory(r, mu, rtmax, phi, N, fdr, vdr, model="E", a=0.5, m=1.0):
    """Steady R and T_tr of a mean-field model for driving power H = f_dr m v_dr^2 (1 - 1/N)."""
    from . import meanfield
    R = meanfield.steady_state(model, r, rtmax, mu, Q)[0]
    A, B, _, _ = meanfield.coefficients(model, r, rtmax, mu, Q, R)
    G = cooling.time_scale_G(phi, a, m, 2)
    H = fdr * m * vdr * vdr * (1.0 - 1.0 / N)
    return R, (H / (G * (A - B * R))) ** (2.0 / 3.0)


CASES_QUICK = [  # (r, mu, rt_max, fraction): dilute cases for the comparison with model E
    (0.95, 0.5, 0.4, 0.05), (0.95, 0.05, 0.4, 0.05), (0.95, math.inf, 0.4, 0.05),
    (0.99, 0.5, 1.0, 0.05)]
CASES_FULL = [(r, mu, rt, phi) for phi in (0.0866, 0.34) for r in (0.95, 0.99) for rt in (0.4, 1.0)
              for mu in (0.01, 0.03, 0.1, 0.3, 1.0, 3.0, math.inf)]


def main(argv=None):
    a = cli.scene_args(argv, __doc__, "out/herbst2005", "4 dilute cases, N = 4096 (default)", "mu scans at the paper's fractions")
    cases = CASES_FULL if a.full else CASES_QUICK
    rows = []
    nside, fdr, vdr, tend = 64, 2.0, 0.1, 600.0
    for r, mu, rt, phi in cli.progress(cases, "driven runs"):
        log = os.path.join(a.out, f"log.driven_r{r}_mu{mu}_rt{rt}_phi{phi}")
        d = simulate(r, "inf" if mu == math.inf else mu, rt, phi, tend, log, nside=nside, fdr=fdr, vdr=vdr)
        s = steady(d)
        R_E, T_E = theory(r, mu, rt, phi, nside * nside, fdr, vdr)
        from . import meanfield
        H = fdr * vdr * vdr * (1.0 - 1.0 / (nside * nside))
        _, Ttr, Trot = meanfield.integrate("E", r, rt, mu, Q, phi, H_dr=H,
                                           T0=(d["c_T[1]"][0], d["c_T[2]"][0]), times=d["Time"])
        d["Ttr_E"], d["R_E"] = Ttr, np.where(Ttr > 0, Trot / Ttr, 0.0)
        rows.append((r, mu, rt, phi, d, s, R_E, T_E))
    report(rows, os.path.join(a.out, "report.md"))
    plot(rows, os.path.join(a.out, "driven.png"))
    print(open(os.path.join(a.out, "report.md")).read())


def report(rows, path):
    lines = ["# Herbst et al. 2005: randomly driven rough spheres with Coulomb friction", "",
             "Steady state (time average over the second half of the run, block standard error) "
             "against the mean-field model E.", "",
             "| r | mu | rt_max | fraction | R sim | R model E | dev R | T_tr sim | T_tr model E | dev T_tr |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r, mu, rt, phi, d, s, R_E, T_E in rows:
        lines.append(f"| {r} | {mu} | {rt} | {phi} | {s['R']:.4f} ± {s['R_err']:.4f} | {R_E:.4f} | "
                     f"{100 * (s['R'] / R_E - 1):+.1f} % | {s['Ttr']:.4f} ± {s['Ttr_err']:.4f} | "
                     f"{T_E:.4f} | {100 * (s['Ttr'] / T_E - 1):+.1f} % |")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    for k, (r, mu, rt, phi, d, s, R_E, T_E) in enumerate(rows):
        col = f"C{k}"
        t = d["Time"]
        m = t > 0
        lab = f"r={r} mu={mu} rt_max={rt} phi={phi}"
        ax[0].semilogx(t[m], d["c_T[1]"][m], "o", ms=3, color=col, label=lab)
        ax[0].semilogx(t[m], d["Ttr_E"][m], "-", color=col, lw=1)
        ax[1].semilogx(t[m], d["c_T[3]"][m], "o", ms=3, color=col)
        ax[1].semilogx(t[m], d["R_E"][m], "-", color=col, lw=1)
    ax[0].set_ylabel("T_tr")
    ax[1].set_ylabel("R = T_rot / T_tr")
    for x in ax:
        x.set_xlabel("time")
    ax[0].legend(fontsize=7)
    fig.suptitle("Driven granular gas from an elastic smooth start: GRANFRIC (symbols), "
                 "mean-field model E (lines)",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
