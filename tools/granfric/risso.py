"""Risso et al. 2005, Fig. 1: lines of equal mean energy loss per collision <dE> in the (kappa, q)
plane (q = q_n = q_t, kappa = kappa_s = kappa_d, discs, T0 = 1), from the closed form (model E of
the same law) with Monte Carlo points through the C++ law, and the kappa of maximum loss.
The vibrated-bed scenes (Figs 2-5) need fix hardsphere/wall, which is not available yet.

    PYTHONPATH=tools /usr/bin/python3 -m granfric.risso [--quick|--full] [--out DIR]
"""
import argparse
import os

import numpy as np

from . import energyloss


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default="out/risso2005")
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--quick", action="store_true")
    g.add_argument("--full", action="store_true")
    a = ap.parse_args(argv)
    os.makedirs(a.out, exist_ok=True)
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
    with open(os.path.join(a.out, "report.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
