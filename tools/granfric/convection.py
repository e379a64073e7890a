# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Risso et al. 2005, Figs 3-5 and Table I: thermal convection of 1000 discs on a vibrated base
(examples/convection). A kappa scan continues each run from the previous configuration; the
order parameters (Psi1, Psi2), sampled every few oscillations after a transient, are clustered
by K-means into 0 / 1 / 2-roll states; a collapsed state (a dense layer on top of a gas) is read
from the time-averaged density profile. Transition points give Table I: the Monte Carlo <dE>
through the C++ law, averaged over each transition line, and q_eff (eq 9).

    PYTHONPATH=tools /usr/bin/python3 -m granfric.convection --kappas 0.005 0.03 0.07 [--q 0]
        [--g 0.015625] [--periods 4000] [--every 50] [--out DIR]
"""
import argparse
import math
import os

import numpy as np

from . import cli, energyloss, kmeans, lammpslog, lmp

INPUT = os.path.join(lmp.ROOT, "examples", "convection", "in.convection")
G_LOW, G_HIGH = 0.002025, 0.015625
# Risso's Table I: <dE> averaged over each transition line (Monte Carlo), and q_eff
PAPER_TABLE = {
    G_LOW: {"0-1": (-0.090, 0.017), "1-2": (-0.351, 0.042), "2-collapse": (-0.614, 0.036)},
    G_HIGH: {"0-1": (-0.047, 0.009), "1-2": (-0.137, 0.022), "2-collapse": (-0.290, 0.037)},
}
COLLAPSE = 3
NAMES = {0: "0", 1: "1", 2: "2", COLLAPSE: "collapse"}


def read_profile(path, skip=0.5):
    """Time-averaged area fraction of unit discs per layer (fix ave/chunk density/number file),
    over the samples after the first `skip` fraction. Returns (layer centres, area fraction)."""
    frames, cur, centres = [], None, None
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w or w[0].startswith("#"):
                continue
            if len(w) == 3:    # timestep, number of chunks, total count
                if cur:
                    frames.append(cur)
                cur = []
            else:
                cur.append((float(w[1]), float(w[3])))
    if cur:
        frames.append(cur)
    frames = frames[int(skip * len(frames)):]
    if not frames:
        raise ValueError(f"no profile samples in {path}")
    centres = np.array([c for c, _ in frames[0]])
    dens = np.mean([[d for _, d in fr] for fr in frames], axis=0)
    return centres, dens * math.pi / 4.0


def collapsed(centres, nu, dense=0.5):
    """Risso's collapsed state: a big compact layer on top of a gas-like region. True when the
    densest layer is compact (area fraction >= `dense`) and some layer below it is a gas (less
    than half that fraction)."""
    i = int(np.argmax(nu))
    return bool(nu[i] >= dense and i > 0 and np.min(nu[:i]) < 0.5 * nu[i])


def run_point(kappa, q, g, periods, every, out, init="none", seed=2005):
    """One run of the scene; returns the path of its restart file for the next point."""
    tag = f"g{g}_q{q}_k{kappa}"
    # restart names are words (letters, digits, underscores) in the run directory: LAMMPS's if
    # command compares them as words
    save = "restart_" + tag.replace(".", "p")
    lmp.run(INPUT, {"kappa": kappa, "q": q, "g": g, "periods": periods, "every": every,
                    "profile": f"log.{tag}.profile", "init": init, "save": save, "seed": seed},
            cwd=out, log=f"log.{tag}")
    return os.path.join(out, f"log.{tag}"), save


def analyse(log, skip=0.5):
    """Samples of (Psi1, Psi2) after the transient, their K-means classification, the collapse
    test, the measured mean energy loss per pair collision and the mean height."""
    d = lammpslog.read_thermo(log)
    n = len(d["Step"])
    sel = np.arange(n) >= max(1, int(skip * n))
    X = np.c_[d["c_psi[1]"][sel], d["c_psi[2]"][sel]]
    cls = kmeans.classify(X)
    centres, nu = read_profile(log + ".profile", skip)
    state = COLLAPSE if collapsed(centres, nu) else cls["rolls"]
    return {"X": X, "class": cls, "state": state, "profile": (centres, nu),
            "ycm": float(d["v_ycm"][sel].mean()), "Ttr": float(d["c_T[1]"][sel].mean())}


def scan(kappas, q, g, periods, every, out, desc="kappa scan", init="none"):
    """A kappa scan at fixed q and g, each run starting from the previous configuration."""
    res = []
    for k in cli.progress(kappas, desc):
        log, init = run_point(k, q, g, periods, every, out, init=init)
        a = analyse(log)
        a.update(kappa=k, q=q, g=g)
        res.append(a)
    return res


def transitions(points):
    """Transition points of one scan (sorted by kappa): between neighbours in different states,
    at the geometric mean of their kappas. Returns (kind, kappa, q) with kind '0-1', '1-2' or
    '2-collapse' (whichever direction the scan crosses it: reentrant lines count too)."""
    out = []
    for a, b in zip(points, points[1:]):
        sa, sb = a["state"], b["state"]
        if sa == sb:
            continue
        lo, hi = sorted((sa, sb))
        kind = {(0, 1): "0-1", (1, 2): "1-2", (2, COLLAPSE): "2-collapse"}.get((lo, hi))
        if kind:
            out.append((kind, math.sqrt(a["kappa"] * b["kappa"]), a["q"]))
    return out


def table_one(trans, nmc=100000):
    """Table I: Monte Carlo <dE> through the C++ law at every transition point, averaged per
    line (mean, standard deviation over the points) and q_eff of the mean."""
    rows = {}
    for kind, k, q in trans:
        rows.setdefault(kind, []).append(energyloss.mean_dE(k, q, n=nmc)[0])
    table = {}
    for kind, v in rows.items():
        v = np.array(v)
        table[kind] = (float(v.mean()), float(v.std(ddof=1)) if len(v) > 1 else float("nan"),
                       len(v), energyloss.q_eff(float(v.mean())))
    return table


def plot_scan(res, path, title):
    """Fig. 3: Psi1 and Psi2 sample by sample, kappa by kappa; Fig. 4: the (Psi1, Psi2) plane."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.3), gridspec_kw={"width_ratios": [2, 1]})
    x0 = 0
    for a in res:
        n = len(a["X"])
        xs = x0 + np.arange(n)
        ax[0].plot(xs, a["X"][:, 0], ".", color="C0", ms=3)
        ax[0].plot(xs, a["X"][:, 1], ".", color="C3", ms=3)
        ax[0].axvline(x0 - 0.5, color="0.7", lw=0.5)
        ax[0].text(x0 + n / 2, 0.27, f"{a['kappa']:g}\n{NAMES[a['state']]}", ha="center", fontsize=7)
        x0 += n
    ax[0].plot([], [], ".", color="C0", label="Psi1")
    ax[0].plot([], [], ".", color="C3", label="Psi2")
    ax[0].set_ylim(-0.3, 0.32)
    ax[0].set_xlabel("sample (kappa bins, state found below each kappa)")
    ax[0].set_ylabel("order parameter")
    ax[0].legend(fontsize=7, loc="lower right")
    ax[0].set_title(title, fontsize=9)
    for j, a in enumerate(res):
        ax[1].plot(a["X"][:, 0], a["X"][:, 1], ".", ms=3, color=f"C{j % 10}", label=f"kappa {a['kappa']:g}")
        for c in a["class"]["clusters"]:
            ax[1].plot(*c["centre"], "k+", ms=10)
    ax[1].set_xlabel("Psi1")
    ax[1].set_ylabel("Psi2")
    ax[1].set_title("(Psi1, Psi2) plane, K-means centres (+)", fontsize=9)
    ax[1].legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_map(points, path, title, g=None):
    """Fig. 5: states in the ln(kappa)-q plane with the lines of equal <dE> (closed form) at the
    paper's transition values of Table I for gravity g."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    ks = np.exp(np.linspace(math.log(1e-3), math.log(10.0), 40))
    qs = np.linspace(0.0, max(0.05, max(p["q"] for p in points) * 1.2), 15)
    dE = np.array([[energyloss.closed_form_dE(k, q) for k in ks] for q in qs])
    if g in PAPER_TABLE:
        lev = sorted(-v[0] for v in PAPER_TABLE[g].values())
        cs = ax.contour(ks, qs, -dE, levels=lev, colors=["C1", "C2", "k"], linewidths=0.8)
        ax.clabel(cs, fmt={l: f"{n} ({l:.3f})" for l, n in zip(lev, ("0-1", "1-2", "2-collapse"))},
                  fontsize=6)
    else:
        cs = ax.contour(ks, qs, -dE, levels=8, colors="0.75", linewidths=0.6)
        ax.clabel(cs, fontsize=6)
    marks = {0: ("o", "C0"), 1: ("s", "C1"), 2: ("^", "C2"), COLLAPSE: ("x", "k")}
    for s, (m, c) in marks.items():
        sel = [p for p in points if p["state"] == s]
        if sel:
            ax.plot([p["kappa"] for p in sel], [p["q"] for p in sel], m, color=c, ms=7,
                    label=NAMES[s] + (" rolls" if s != COLLAPSE else ""))
    ax.set_xscale("log")
    ax.set_xlabel("kappa")
    ax.set_ylabel("q")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def state_rows(res):
    lines = ["| g | q | kappa | state | weights 0/1/2 rolls | cluster centres (Psi1, Psi2) | Y_cm | MC <dE> |",
             "|---|---|---|---|---|---|---|---|"]
    for a in res:
        w = a["class"]["weights"]
        cents = "; ".join(f"({c['centre'][0]:+.3f}, {c['centre'][1]:+.3f}) {c['weight']:.2f}"
                          for c in a["class"]["clusters"])
        dE = energyloss.mean_dE(a["kappa"], a["q"], n=40000)[0]
        lines.append(f"| {a['g']} | {a['q']} | {a['kappa']:g} | {NAMES[a['state']]} | "
                     f"{w[0]:.2f}/{w[1]:.2f}/{w[2]:.2f} | {cents} | {a['ycm']:.1f} | {dE:.3f} |")
    return lines


def table_rows(table, g):
    lines = ["| g | transition | points | <dE> (ours) | q_eff (ours) | <dE> (paper) |",
             "|---|---|---|---|---|---|"]
    for kind in ("0-1", "1-2", "2-collapse"):
        p = PAPER_TABLE[g][kind]
        if kind in table:
            m, s, n, qe = table[kind]
            qs = "undefined" if qe is None else f"{qe:.3f}"
            lines.append(f"| {g} | {kind} | {n} | {m:.3f} ± {s:.3f} | {qs} | {p[0]} ± {p[1]} |")
        else:
            lines.append(f"| {g} | {kind} | 0 | not crossed | | {p[0]} ± {p[1]} |")
    return lines


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--kappas", type=float, nargs="+", default=[0.005, 0.03, 0.07],
                    help="friction coefficients kappa of the scan (default 0.005 0.03 0.07)")
    ap.add_argument("--q", type=float, default=0.0, help="q = q_n = q_t of the law (default 0)")
    ap.add_argument("--g", type=float, default=G_HIGH,
                    help=f"gravity in the scene's units (default {G_HIGH})")
    ap.add_argument("--periods", type=int, default=4000,
                    help="vibration periods per kappa (default 4000)")
    ap.add_argument("--every", type=int, default=50,
                    help="periods between samples of Psi1, Psi2 (default 50)")
    ap.add_argument("--out", default="out/convection",
                    help="output folder: psi.png at its top, LAMMPS logs and restart files in its "
                         "logs/ (default out/convection)")
    a = ap.parse_args(argv)
    os.makedirs(a.out, exist_ok=True)
    res = scan(a.kappas, a.q, a.g, a.periods, a.every, cli.logs_dir(a.out))
    plot_scan(res, os.path.join(a.out, "psi.png"), f"g = {a.g}, q = {a.q}, {a.periods} oscillations per kappa")
    print("\n".join(state_rows(res)))


if __name__ == "__main__":
    main()
