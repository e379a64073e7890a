# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Herbst et al. 2005 scene: randomly driven 2D monolayer of rough spheres (q = 2/5) with Coulomb
friction (Walton law), simulated with GRANFRIC (examples/driven) and compared with the mean-field
model E (granfric.meanfield) in the steady state (report.md table, driven.png), plus the paper's
Figs 2, 3 and 5-11 (granfric.herbst_figs: fig*.png and their numbers in report.md).

    PYTHONPATH=tools /usr/bin/python3 -m granfric.herbst [--quick|--full] [--out DIR]
    tools/reproduce herbst2005 [--quick|--full] [--out DIR]
"""
import math
import os

import numpy as np

from . import cli, cooling, lammpslog, lmp

EXAMPLE = os.path.join(lmp.ROOT, "examples", "driven")
Q = 0.4


def simulate(r, mu, rtmax, phi, tend, out, nside=64, fdr=2.0, vdr=0.1, seed=4321, dt=0.5,
             series_every=None):
    """Run examples/driven/in.driven; returns its thermo table (dict column -> array).

    series_every = k (steps) also records, through a copy of in.driven with two fixes added
    before its production run (examples/driven itself is unchanged):
      d["series"]: T_tr, T_rot, R every k steps (fix ave/time on compute hardsphere/temp),
      d["gamma"]:  the impact-angle histogram (gamma, P(gamma)) of the second half of the run
                   (a second compute hardsphere/collisions, so thermo's collision windows are
                   left alone)."""
    v = {"r": r, "mu": mu, "rtmax": rtmax, "phi": phi, "tend": tend, "nside": nside,
         "fdr": fdr, "vdr": vdr, "seed": seed, "dt": dt}
    script = os.path.join(EXAMPLE, "in.driven")
    if series_every:
        script = _script_with_series(os.path.dirname(os.path.abspath(out)))
        v.update({"tevery": int(series_every), "tfile": out + ".T", "gfile": out + ".gamma"})
    lmp.run(script, v, log=out)
    d = lammpslog.read_thermo(out)
    if series_every:
        s = lammpslog.read_ave_time(out + ".T")
        d["series"] = {"Time": s["TimeStep"] * float(dt), "Ttr": s["c_T[1]"], "Trot": s["c_T[2]"],
                       "R": s["c_T[3]"]}
        d["gamma"] = read_gamma(out + ".gamma")
    return d


_EXTRA = """variable        nh equal floor(${n}/2)
compute         H all hardsphere/collisions ed
fix             gam all ave/time ${nh} 1 ${nh} c_H[1] c_H[2] mode vector file ${gfile}
fix             tser all ave/time ${tevery} 1 ${tevery} c_T[1] c_T[2] c_T[3] file ${tfile}
"""


def _script_with_series(directory):
    """in.driven with the series and histogram fixes inserted before its final `run ${n}`."""
    lines = open(os.path.join(EXAMPLE, "in.driven")).read().rstrip().splitlines()
    if lines[-1].split() != ["run", "${n}"]:
        raise RuntimeError("examples/driven/in.driven no longer ends with 'run ${n}'")
    path = os.path.join(directory, "in.driven_series")
    text = "\n".join(lines[:-1]) + "\n" + _EXTRA + lines[-1] + "\n"
    if not os.path.exists(path) or open(path).read() != text:
        with open(path, "w") as f:
            f.write(text)
    return path


def read_gamma(path):
    """Last block of a fix ave/time mode-vector file of (gamma, P(gamma)): arrays (gamma, P)."""
    blocks, rows, left = [], None, 0
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            w = line.split()
            if left == 0:
                left, rows = int(w[1]), []
                blocks.append(rows)
                continue
            rows.append([float(x) for x in w[1:3]])
            left -= 1
    if not blocks or not blocks[-1]:
        raise ValueError(f"no histogram in {path}")
    a = np.array(blocks[-1])
    return a[:, 0], a[:, 1]


def steady(d, tfrac=0.5):
    """Time averages over the last (1 - tfrac) of the run, with block standard errors."""
    t = d["Time"]
    sel = t > tfrac * t[-1]
    out = {}
    for key, name in (("c_T[1]", "Ttr"), ("c_T[2]", "Trot"), ("c_T[3]", "R")):
        out[name], out[name + "_err"] = lammpslog.block_mean(d[key][sel], 4)
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


def _row(r, mu, rt, phi, d, s, nside, fdr, vdr):
    """A report/plot row: the run, its steady averages, model E's steady state and its integration
    from the run's initial temperatures at the run's output times."""
    from . import meanfield
    R_E, T_E = theory(r, mu, rt, phi, nside * nside, fdr, vdr)
    H = fdr * vdr * vdr * (1.0 - 1.0 / (nside * nside))
    _, Ttr, Trot = meanfield.integrate("E", r, rt, mu, Q, phi, H_dr=H,
                                       T0=(d["c_T[1]"][0], d["c_T[2]"][0]), times=d["Time"])
    d["Ttr_E"], d["R_E"] = Ttr, np.where(Ttr > 0, Trot / Ttr, 0.0)
    return (r, mu, rt, phi, d, s, R_E, T_E)


def main(argv=None):
    from . import herbst_figs
    a = cli.scene_args(argv, __doc__, "out/herbst2005",
                       "4 dilute cases (N = 4096) for the table + the paper's figures at N = 1600, "
                       "fraction 0.0866 (default; a few minutes)",
                       "the paper's parameters: N = 11025, fractions 0.34 (Figs 3, 5-10) and "
                       "0.0866 (Fig. 11), r = 0.95/0.99, rt_max = 0.4/1.0, mu 0.003 ... inf "
                       "(about an hour)")
    rows = []
    if not a.full:
        nside, fdr, vdr, tend = 64, 2.0, 0.1, 600.0
        for r, mu, rt, phi in cli.progress(CASES_QUICK, "driven runs"):
            log = os.path.join(a.logs, f"log.driven_r{r}_mu{mu}_rt{rt}_phi{phi}")
            d = simulate(r, "inf" if mu == math.inf else mu, rt, phi, tend, log, nside=nside,
                         fdr=fdr, vdr=vdr)
            rows.append(_row(r, mu, rt, phi, d, steady(d), nside, fdr, vdr))
    plan = herbst_figs.FULL if a.full else herbst_figs.QUICK
    runs, res = herbst_figs.run(plan, a.out, a.logs)
    if a.full:   # the table lists every run of the figures; driven.png shows Fig. 11's runs
        for (phi, r, rt, mu), run in sorted(runs.items(), key=lambda kv: kv[0]):
            rows.append(_row(r, mu, rt, phi, run.d, run.st, plan.nside, plan.fdr, plan.vdr))
        phi11, r11, rt11, mus11 = plan.fig11
        shown = [w for w in rows if (w[3], w[0], w[2]) == (phi11, r11, rt11) and w[1] in mus11]
    else:
        shown = rows
    path = os.path.join(a.out, "report.md")
    report(rows, path)
    with open(path, "a") as f:
        f.write(herbst_figs.report_section(res))
    plot(shown, os.path.join(a.out, "driven.png"))
    print(open(path).read())


def report(rows, path):
    lines = ["# Herbst et al. 2005: randomly driven rough spheres with Coulomb friction", "",
             "Steady state (time average over the second half of the run, block standard error) "
             "against the mean-field model E.", "",
             "| r | mu | rt_max | fraction | R sim | R model E | dev R | T_tr sim | T_tr model E | dev T_tr |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r, mu, rt, phi, d, s, R_E, T_E in rows:
        dev_R = f"{100 * (s['R'] / R_E - 1):+.1f} %" if R_E > 0 else "-"
        lines.append(f"| {r} | {mu} | {rt} | {phi} | {s['R']:.4f} ± {s['R_err']:.4f} | {R_E:.4f} | "
                     f"{dev_R} | {s['Ttr']:.4f} ± {s['Ttr_err']:.4f} | "
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
