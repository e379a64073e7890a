# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Simple shear (examples/shear): the event-driven runs of examples/shear/in.shear2d (discs) and
in.shear3d (spheres) in steady uniform shear flow against the kinetic theory (granfric.usf, DSMC
of the Enskog-Boltzmann equation; granfric.usf_grad, Grad's moment theory), and how the steady
state departs from the homogeneous one as the box grows.

    PYTHONPATH=tools /usr/bin/python3 -m granfric shear [--quick|--full] [--out DIR]

For each case (dimension, fraction phi, N = nside^dim particles of the rough law r = 0.9,
beta = 0, shear rate a = 0.05) the example runs to its steady state and averages over it; the reduced quantities
are a* = a / nu(T_tr) (nu: the Enskog collision frequency of cooling.py), P*_ij = P_ij / (n T_tr),
R = T_rot / T_tr and the measured collisions per particle and unit time over nu. Writes
report.md (the table, the DSMC values and the relative deviations) and shear.png (the approach
to the steady state, and the steady state against the box size).
"""
import os

import numpy as np

from . import cli, cooling, lammpslog, lmp, usf, usf_grad

EXAMPLES = {2: os.path.join(lmp.ROOT, "examples", "shear", "in.shear2d"),
            3: os.path.join(lmp.ROOT, "examples", "shear", "in.shear3d")}
LAW, COEFFS, RATE = "rough", (0.9, 0.0), 0.05


def steady(log):
    """The example's closing line: T_tr, T_rot, Pxx, Pyy, Pxy, collisions, n, rate, phi"""
    return lammpslog.steady_line(log)


def reduced(s, dim):
    """a*, P*_xx, P*_yy, P*_xy, R and collisions / nu of a steady state (the example's, or the
    DSMC's in the same form)"""
    T, n = s["T_tr"], s["n"]
    nu = cooling.collision_frequency(T, s["phi"], 0.5, 1.0, dim)
    return {"T_tr": T, "a*": s["rate"] / nu, "P*xx": s["Pxx"] / (n * T), "P*yy": s["Pyy"] / (n * T),
            "P*xy": s["Pxy"] / (n * T), "R": s["T_rot"] / T, "coll/nu": s["coll"] / nu}


def theory(dim, phi, N, runs):
    m, se = usf.steady(LAW, COEFFS, dim, phi, RATE, runs=runs, N=N, t_relax=400.0, t_avg=600.0,
                       T0=(RATE / 0.5 / cooling.collision_frequency(1.0, phi, 0.5, 1.0, dim)) ** 2)
    s = {"T_tr": m["Ttr"], "T_rot": m["Trot"], "Pxx": m["P"][0, 0], "Pyy": m["P"][1, 1],
         "Pxy": m["P"][0, 1], "coll": m["coll_rate"], "n": m["n"], "rate": RATE, "phi": phi}
    return reduced(s, dim), m, se


def grad(dim, phi):
    """Grad's theory (granfric.usf_grad: Boltzmann limit, the kinetic stress only) in the form of
    reduced(): its a* gives T_tr through nu(T_tr) = a / a*; collisions at the rate nu"""
    g = usf_grad.grad(LAW, COEFFS, dim)
    T = (RATE / (g["a_star"] * cooling.collision_frequency(1.0, phi, 0.5, 1.0, dim))) ** 2
    P = g["P_star"]
    return {"T_tr": T, "a*": g["a_star"], "P*xx": P[0, 0], "P*yy": P[1, 1], "P*xy": P[0, 1], "R": g["R"],
            "coll/nu": 1.0}


def run_example(work, dim, phi, nside, tavg, seed=4321):
    log = os.path.join(work, f"log.{dim}d.phi{phi}.n{nside}.s{seed}")
    lmp.run(EXAMPLES[dim], {"phi": phi, "nside": nside, "tavg": tavg, "seed": seed}, cwd=work, log=log)
    return log


KEYS = ("T_tr", "a*", "P*xx", "P*yy", "P*xy", "R", "coll/nu")
GRAD_PHI = 0.01    # (Grad's theory is the Boltzmann limit: compared in the dilute gas only)


def main(argv=None):
    a = cli.scene_args(argv, __doc__, "out/shear",
                       "2D phi 0.01 and 0.05 at N = 1024, 3D phi 0.05 at N = 1728, 2D sizes N = 64 "
                       "to 4096; DSMC N = 20000 x 2",
                       "sizes up to N = 16384, three seeds per case; DSMC N = 40000 x 4")
    os.makedirs(a.out, exist_ok=True)
    work = cli.logs_dir(a.out)
    sizes = [8, 16, 32, 64, 128] if a.full else [8, 16, 32, 64]
    seeds = [4321, 777, 99] if a.full else [4321]
    dN, runs = (40000, 4) if a.full else (20000, 2)
    cases = [(2, 0.01, 32), (2, 0.05, 32), (3, 0.05, 12)]
    lines = ["# Simple shear: event-driven runs against the kinetic theory", "",
             f"Rough discs r = {COEFFS[0]}, beta = {COEFFS[1]}, shear rate a = {RATE}; DSMC of the "
             f"Enskog-Boltzmann equation with N = {dN} x {runs} runs. a* = a/nu(T_tr), P* = P/(n T_tr).",
             "", "## The dilute gas (2D: N = 1024 discs; 3D: N = 1728 spheres)", "",
             "| dim | phi | source | " + " | ".join(KEYS) + " |", "|---|---|---|" + "---|" * len(KEYS)]
    theories = {}
    for dim, phi, nside in cli.progress(cases, "cases"):
        th = theories[(dim, phi)] = theory(dim, phi, dN, runs)[0]
        eds = [reduced(steady(run_example(work, dim, phi, nside, 10000.0, seed)), dim) for seed in seeds]
        ed = {k: float(np.mean([e[k] for e in eds])) for k in KEYS}
        lines.append(f"| {dim} | {phi} | DSMC | " + " | ".join(f"{th[k]:.4g}" for k in KEYS) + " |")
        lines.append(f"| {dim} | {phi} | ED | " + " | ".join(f"{ed[k]:.4g}" for k in KEYS) + " |")
        lines.append(f"| {dim} | {phi} | ED/DSMC - 1 | " + " | ".join(f"{100 * (ed[k] / th[k] - 1):+.1f} %" for k in KEYS) + " |")
        if phi <= GRAD_PHI:
            gr = grad(dim, phi)
            lines.append(f"| {dim} | {phi} | Grad | " + " | ".join(f"{gr[k]:.4g}" for k in KEYS) + " |")
            lines.append(f"| {dim} | {phi} | ED/Grad - 1 | " +
                         " | ".join(f"{100 * (ed[k] / gr[k] - 1):+.1f} %" for k in KEYS) + " |")
    th = theories[(2, 0.05)]
    lines += ["", "## The box size (2D, phi = 0.05)", "", "| N | L / mean free path | " + " | ".join(
        f"{k}/DSMC" for k in KEYS) + " |", "|---|---|" + "---|" * len(KEYS)]
    mfp = 1.0 / (2.0 * np.sqrt(2.0) * (0.05 / (np.pi * 0.25)) * cooling.pair_correlation(0.05, 2))
    rows = []
    for nside in cli.progress(sizes, "box sizes"):
        s = reduced(steady(run_example(work, 2, 0.05, nside, max(1000.0, 320000.0 / nside), 4321)), 2)
        L = nside * np.sqrt(np.pi * 0.25 / 0.05)
        rows.append((nside * nside, L / mfp, s))
        lines.append(f"| {nside * nside} | {L / mfp:.1f} | " + " | ".join(f"{s[k] / th[k]:.3f}" for k in KEYS) + " |")
    with open(os.path.join(a.out, "report.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    plot(os.path.join(work, "log.2d.phi0.05.n32.s4321"), th, rows, os.path.join(a.out, "shear.png"))
    print("\n".join(lines))


def plot(log, th, rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.5))
    d = lammpslog.read_thermo(log, block=0)
    ax[0].plot(d["Time"], d["c_T[1]"], "o-", ms=3, label="T_tr (ED, N = 1024)")
    ax[0].plot(d["Time"], d["c_T[2]"], "s-", ms=3, label="T_rot (ED)")
    ax[0].axhline(th["T_tr"], color="k", ls="--", label="T_tr steady (DSMC)")
    ax[0].axhline(th["T_tr"] * th["R"], color="gray", ls=":", label="T_rot steady (DSMC)")
    ax[0].set_yscale("log")
    ax[0].set_xlabel("time")
    ax[0].set_ylabel("temperature")
    ax[0].set_title("approach to steady shear flow (phi = 0.05)")
    ax[0].legend()
    N = [r[0] for r in rows]
    for k, mk in (("T_tr", "o"), ("a*", "s"), ("P*xy", "^"), ("P*xx", "v"), ("coll/nu", "d")):
        ax[1].semilogx(N, [r[2][k] / th[k] for r in rows], mk + "-", label=k)
    ax[1].axhline(1.0, color="k", lw=0.8)
    ax[1].set_xlabel("N (box side = sqrt(N) x 3.96 diameters)")
    ax[1].set_ylabel("event-driven / homogeneous kinetic theory")
    ax[1].set_title("steady state against box size")
    ax[1].legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
