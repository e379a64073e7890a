# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""The vibrated bed in 3D (in.convection3d): runs the scene at a few friction coefficients from
the same start, classifies each run from its order parameters and density profile, prints a
markdown table and draws convection3d.png (order parameters against time, the mean flow in a
side view of the convecting run, the density profiles).

    /usr/bin/python3 examples/convection3d/convection3d.py [--kappas 0.005 0.03 0.3]
        [--q 0] [--periods 3000] [--seed 2005] [--np 1] [--png examples/convection3d/convection3d.png]
        [--keep DIR [--replot]]

Classification, from the second half of each run: the bed convects when the mean amplitude
|Psi| = (Psi1_x^2 + Psi2_x^2 + Psi1_y^2 + Psi2_y^2)^(1/2) of the samples exceeds 5 times the
amplitude that the thermal noise alone gives each component, (T_tr / 2N)^(1/2) (no convection:
|Psi| about 2 times that); the roll's axis is y when the x pair carries the larger part of
|Psi|^2, x otherwise. The bed is collapsed when its densest layer (2 diameters thick, mean over
the second half) is compact, packing fraction >= 0.5, above a layer of less than half that
density (as tools/granfric/kmeans.py decides it for the 2D bed).
"""
import argparse
import os
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "tools"))
from granfric import lammpslog, lmp  # noqa: E402

SCENE = os.path.join(HERE, "in.convection3d")
PSI = ["c_psi[1]", "c_psi[2]", "c_psi[3]", "c_psi[4]"]
N_ATOMS = 6000    # the input's default n


def read_chunks(path):
    """A fix ave/chunk file of 2d bins: array (samples, bins, columns) with the columns
    Chunk Coord1 Coord2 Ncount density/number v_h vz."""
    blocks, cur = [], None
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                continue
            w = line.split()
            if len(w) == 3:
                cur = []
                blocks.append(cur)
            elif w:
                cur.append([float(x) for x in w])
    return np.array(blocks)


def field(chunks):
    """Mean over the samples: horizontal and vertical bin centres, density, v_h, v_z as 2d
    arrays indexed [horizontal, vertical] (velocities weighted by the atoms counted)."""
    h, z = np.unique(chunks[0, :, 1]), np.unique(chunks[0, :, 2])
    shape = (len(h), len(z))
    count = chunks[:, :, 3]
    w = np.maximum(count.sum(0), 1e-300)
    vh = (chunks[:, :, 5] * count).sum(0) / w
    vz = (chunks[:, :, 6] * count).sum(0) / w
    n = chunks[:, :, 4].mean(0)
    return h, z, n.reshape(shape), vh.reshape(shape), vz.reshape(shape)


def run(kappa, q, periods, seed, np_, work, again=True):
    tag = f"k{kappa}".replace(".", "p")
    log = os.path.join(work, f"log.{tag}")
    if again or not os.path.exists(log):
        lmp.run(SCENE, {"kappa": kappa, "q": q, "periods": periods, "seed": seed, "flow": tag},
                cwd=work, np=np_, log=log)
    th = lammpslog.read_thermo(log)
    half = th["Step"] > th["Step"][-1] / 2
    psi = np.array([th[c] for c in PSI]).T
    amp = np.sqrt((psi ** 2).sum(1))
    noise = np.sqrt(th["c_T[1]"][half].mean() / (2 * N_ATOMS))
    xz = read_chunks(os.path.join(work, f"{tag}.xz"))
    yz = read_chunks(os.path.join(work, f"{tag}.yz"))
    nh = len(xz) // 2
    fx, fy = field(xz[nh:]), field(yz[nh:])
    z, prof = fx[1], fx[2].mean(0)
    frac = prof * np.pi / 6.0
    top = int(np.argmax(prof))
    collapsed = bool(frac[top] >= 0.5 and prof[:top].size and prof[:top].min() < 0.5 * prof[top])
    ax2 = (psi[half, :2] ** 2).sum(1).mean()
    ay2 = (psi[half, 2:] ** 2).sum(1).mean()
    convects = amp[half].mean() > 5 * noise
    state = "collapse" if collapsed else ("convection, roll axis " + ("y" if ax2 > ay2 else "x")
                                          if convects else "no convection")
    steps = np.diff(th["Step"])
    return dict(kappa=kappa, t=th["Step"], psi=psi, amp=amp, noise=noise, state=state,
                mean_psi=psi[half].mean(0), std_psi=psi[half].std(0), mean_amp=amp[half].mean(),
                zcm=th["v_zcm"][half].mean(), T=th["c_T[1]"][half].mean(),
                coll=np.diff(th["f_ed[2]"])[half[1:]].sum() / steps[half[1:]].sum(),
                z=z, prof=prof, fx=fx, fy=fy, ax2=ax2, ay2=ay2)



def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--kappas", type=float, nargs="+", default=[0.005, 0.03, 0.3])
    ap.add_argument("--q", type=float, default=0.0)
    ap.add_argument("--periods", type=int, default=3000)
    ap.add_argument("--seed", type=int, default=2005)
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--png", default=os.path.join(HERE, "convection3d.png"))
    ap.add_argument("--keep", help="keep the logs and flow files in this directory; with "
                    "--replot, read them from there instead of running again")
    ap.add_argument("--replot", action="store_true")
    a = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        work = a.keep or tmp
        os.makedirs(work, exist_ok=True)
        runs = [run(k, a.q, a.periods, a.seed, a.np, work, not a.replot) for k in a.kappas]
    print(f"N = {N_ATOMS}, q = {a.q}, {a.periods} periods from the same start (seed {a.seed}), "
          f"means over the second half")
    print("| kappa | state | Psi1_x | Psi2_x | Psi1_y | Psi2_y | mean abs Psi | noise (T/2N)^1/2 | "
          "Z_cm | T_tr | collisions / period |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in runs:
        m, s = r["mean_psi"], r["std_psi"]
        print(f"| {r['kappa']:g} | {r['state']} | " +
              " | ".join(f"{m[k]:+.3f} ± {s[k]:.3f}" for k in range(4)) +
              f" | {r['mean_amp']:.3f} | {r['noise']:.4f} | {r['zcm']:.1f} | {r['T']:.3f} | "
              f"{r['coll']:.0f} |")
    draw(runs, a.png)


def draw(runs, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axs = plt.subplots(2, 2, figsize=(12, 10), gridspec_kw={"height_ratios": [1, 1.3]})
    conv = next((r for r in runs if r["state"].startswith("convection")), runs[0])
    ax = axs[0, 0]
    names = [r"$\Psi_{1,x}$", r"$\Psi_{2,x}$", r"$\Psi_{1,y}$", r"$\Psi_{2,y}$"]
    for k in range(4):
        ax.plot(conv["t"], conv["psi"][:, k], label=names[k])
    ax.axhline(0, color="k", lw=0.5)
    ax.set_xlabel("base periods")
    ax.set_ylabel("order parameter")
    ax.set_title(f"(a) $\\kappa$ = {conv['kappa']:g}: {conv['state']}")
    ax.legend(fontsize=8, ncol=2)
    ax = axs[0, 1]
    for r in runs:
        line, = ax.semilogy(r["t"][1:], r["amp"][1:], label=f"$\\kappa$ = {r['kappa']:g}: {r['state']}")
        ax.axhline(5 * r["noise"], color=line.get_color(), ls=":", lw=1)
    ax.set_xlabel("base periods")
    ax.set_ylabel(r"$|\Psi| = (\Psi_{1,x}^2+\Psi_{2,x}^2+\Psi_{1,y}^2+\Psi_{2,y}^2)^{1/2}$")
    ax.set_title("(b) amplitude; dotted: 5 x thermal noise $(T_{tr}/2N)^{1/2}$")
    ax.legend(fontsize=8)
    ax = axs[1, 0]
    f, hname = (conv["fx"], "x") if conv["ax2"] > conv["ay2"] else (conv["fy"], "y")
    h, z, n, vh, vz = f
    keep = z < 56
    H, Z = np.meshgrid(h, z[keep], indexing="ij")
    im = ax.pcolormesh(H, Z, n[:, keep] * np.pi / 6, shading="nearest", cmap="Greys", vmin=0)
    dense = n[:, keep] > 0.01
    ax.quiver(H[dense], Z[dense], vh[:, keep][dense], vz[:, keep][dense], color="tab:red",
              scale=0.15, scale_units="xy", angles="xy", width=0.006)
    ax.set_aspect("equal")
    ax.set_xlabel(hname)
    ax.set_ylabel("z")
    ax.set_title(f"(c) $\\kappa$ = {conv['kappa']:g}: mean flow, {hname}-z plane\n"
                 f"(mean over {'y' if hname == 'x' else 'x'} and the second half; "
                 f"an arrow 2 long = speed 0.3)", fontsize=10)
    fig.colorbar(im, ax=ax, label="packing fraction")
    ax = axs[1, 1]
    for r in runs:
        ax.plot(r["prof"] * np.pi / 6, r["z"], label=f"$\\kappa$ = {r['kappa']:g}")
    ax.set_xlabel("packing fraction (layers 2 diameters thick)")
    ax.set_ylabel("z")
    ax.set_ylim(0, 100)
    ax.set_title("(d) density profiles (second half)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


if __name__ == "__main__":
    main()
