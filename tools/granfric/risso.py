# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Risso et al. 2005, Fig. 1: lines of equal mean energy loss per collision <dE> in the (kappa, q)
plane (q = q_n = q_t, kappa = kappa_s = kappa_d, discs, T0 = 1), from the closed form (model E of
the same law) with Monte Carlo points through the C++ law, and the kappa of maximum loss.
Fig. 2: height of the centre of mass of 500 discs on a thermal base against kappa
(examples/compaction). Figs 3-5 and Table I: thermal convection on a vibrated base
(examples/convection, granfric.convection): kappa scans continuing from the previous
configuration, states by K-means on (Psi1, Psi2), transition lines and their mean <dE>.

    PYTHONPATH=tools /usr/bin/python3 -m granfric.risso [--quick|--full] [--out DIR]
"""
import os

import numpy as np

from . import cli, convection, energyloss, lammpslog, lmp

COMPACTION = os.path.join(lmp.ROOT, "examples", "compaction", "in.compaction")


def compaction(kappa, out, tend=20000.0, seed=4321):
    """Mean centre-of-mass height (second half of the run) of the Fig. 2 system at friction
    kappa, with its block standard error."""
    lmp.run(COMPACTION, {"kappa": kappa, "tend": tend, "seed": seed}, log=out)
    d = lammpslog.read_thermo(out)
    t, y = d["Time"], d["v_ycm"]
    return lammpslog.block_mean(y[t > 0.5 * t[-1]], 4)


def main(argv=None):
    a = cli.scene_args(argv, __doc__, "out/risso2005", "coarse map, 5 kappas for Fig. 2 (default)", "fine map, 10 kappas")
    nk, nq, nmc = (60, 41, 200000) if a.full else (30, 21, 40000)
    kappas = np.exp(np.linspace(np.log(1e-3), np.log(10.0), nk))
    qs = np.linspace(0.0, 0.2, nq)
    dE = np.array([[energyloss.closed_form_dE(k, q) for k in kappas] for q in qs])
    kmax = [(q, energyloss.kappa_of_max_loss(q)) for q in (0.0, 0.025, 0.05, 0.1)]
    mc = []
    for iq, q in enumerate((0.025, 0.1)):
        for ik, k in enumerate((0.01, 0.1, 0.3, 1.0, 10.0)):
            m, se, sl = energyloss.mean_dE(k, q, n=nmc, seed=11 + 10 * iq + ik)
            mc.append((q, k, m, se, energyloss.closed_form_dE(k, q), sl))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    cs = ax.contour(kappas, qs, -dE, levels=np.linspace(0.05, 1.0, 20), cmap="viridis")
    ax.clabel(cs, fontsize=6)
    ax.plot([k for _, k in kmax], [q for q, _ in kmax], "r^-", label="kappa of maximum loss")
    ax.set_xscale("log")
    ax.set_xlabel("kappa")
    ax.set_ylabel("q = q_n = q_t")
    ax.set_title("Risso Fig. 1: lines of equal |<dE>| / T0 (Walton = JZ law, discs)", fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "energy_loss.png"), dpi=110)

    lines = ["# Risso et al. 2005: mean energy loss per collision", "",
             "kappa of maximum loss (paper: about 0.3):", "",
             "| q | kappa of maximum loss | <dE> there |", "|---|---|---|"]
    for q, k in kmax:
        lines.append(f"| {q} | {k:.3f} | {energyloss.closed_form_dE(k, q):.4f} |")
    lines += ["", "Monte Carlo through the C++ law against the closed form:", "",
              "| q | kappa | MC <dE> | closed form | sliding fraction |", "|---|---|---|---|---|"]
    for q, k, m, se, cf, sl in mc:
        lines.append(f"| {q} | {k} | {m:.4f} ± {se:.4f} | {cf:.4f} | {sl:.3f} |")
    # Fig. 2: compaction against kappa
    ks2 = (0.01, 0.1, 0.3, 1.0, 3.0) if not a.full else (0.003, 0.01, 0.03, 0.1, 0.2, 0.3, 0.5, 1.0, 3.0, 10.0)
    tend = 40000.0 if a.full else 20000.0
    ycm = [compaction(k, os.path.join(a.logs, f"log.compaction_k{k}"), tend=tend) for k in ks2]
    fig, ax = plt.subplots(figsize=(5.5, 4))
    ax.errorbar(ks2, [y for y, _ in ycm], yerr=[e for _, e in ycm], fmt="o-")
    ax.set_xscale("log")
    ax.set_xlabel("kappa")
    ax.set_ylabel("Y_cm (diameters)")
    ax.set_title("Risso Fig. 2: 500 discs on a thermal base, q = 0.025, g = 0.002", fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "compaction.png"), dpi=110)
    lines += ["", "Fig. 2, centre-of-mass height against kappa (paper: minimum near kappa = 0.3):", "",
              "| kappa | Y_cm |", "|---|---|"]
    for k, (y, e) in zip(ks2, ycm):
        lines.append(f"| {k} | {y:.2f} ± {e:.2f} |")
    lines += convection_figures(a)
    with open(os.path.join(a.out, "report.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


# Figs 3-5: the quick run is one reentrant kappa scan at q = 0 and the larger gravity (3000
# oscillations per kappa, samples every 50); the full run is the paper's: 1e5 oscillations per
# point, samples every 100, q rows for both gravities (about 10 hours on one core per gravity)
QUICK_KAPPAS = (0.005, 0.03, 0.05, 0.07, 0.1, 0.15, 0.3, 0.7, 1.5, 5.0)
FULL_KAPPAS = (0.005, 0.01, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08, 0.1, 0.15, 0.2, 0.3, 0.5,
               0.7, 1.0, 1.5, 2.0, 3.0, 5.0, 10.0)
FULL_QS = {convection.G_HIGH: (0.0, 0.01, 0.02, 0.03, 0.05),
           convection.G_LOW: (0.0, 0.02, 0.04, 0.06, 0.08, 0.1, 0.12)}


def convection_figures(a):
    if a.full:
        periods, every, rows = 100000, 100, [(g, q) for g, qs in FULL_QS.items() for q in qs]
        kappas = FULL_KAPPAS
    else:
        periods, every, rows = 3000, 50, [(convection.G_HIGH, 0.0)]
        kappas = QUICK_KAPPAS
    lines = ["", f"Figs 3-5: convection of 1000 discs on a vibrated base, {periods} oscillations per "
             f"point (paper: 1e5), samples every {every}, the first half discarded; each kappa "
             "continues from the previous configuration. States: K-means on (Psi1, Psi2) "
             "(granfric.kmeans), collapse from the density profile.", ""]
    points, table_lines = [], []
    for g in sorted({g for g, _ in rows}, reverse=True):
        trans = []
        for gg, q in rows:
            if gg != g:
                continue
            res = convection.scan(kappas, q, g, periods, every, a.logs, desc=f"convection g={g} q={q}")
            points += res
            trans += convection.transitions(res)
            if q == 0.0:
                convection.plot_scan(res, os.path.join(a.out, f"fig3_psi_g{g}.png"),
                                     f"Risso Fig. 3: g = {g}, q = {q}, {periods} oscillations per kappa")
            lines += [f"g = {g}, q = {q}:", ""] + convection.state_rows(res) + [""]
        convection.plot_map([p for p in points if p["g"] == g], os.path.join(a.out, f"fig5_states_g{g}.png"),
                            f"Risso Fig. 5: states at g = {g}; lines: |<dE>| of the paper's transitions (Table I)", g=g)
        table_lines += convection.table_rows(convection.table_one(trans), g)[(2 if table_lines else 0):]
    lines += ["Table I: Monte Carlo <dE> through the C++ law at the transition points (geometric mean "
              "of the neighbouring kappas), mean ± standard deviation over each line, and q_eff (eq 9):",
              ""] + table_lines
    return lines


if __name__ == "__main__":
    main()
