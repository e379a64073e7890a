# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Equation of state of elastic hard spheres and discs through LAMMPS (in.eos), against
Carnahan-Starling (3D) and Henderson (2D): one run per packing fraction, a table and eos.png.

    python3 examples/eos/eos.py [--quick] [--np N]

Writes eos.png and eos.md next to this script (or in --out).
"""
import argparse
import os
import re
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))
LMP = os.path.join(HERE, "..", "..", "tools", "lmp")
FRACTIONS = {3: [0.05, 0.1, 0.2, 0.25, 0.3, 0.35, 0.4, 0.45], 2: [0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6]}


def z_theory(dim, phi):
    if dim == 3:
        return (1 + phi + phi ** 2 - phi ** 3) / (1 - phi) ** 3
    return (1 + phi ** 2 / 8) / (1 - phi) ** 2


def run(dim, phi, nrun, np_):
    cmd = [LMP] + (["-np", str(np_)] if np_ > 1 else []) + [
        "-in", os.path.join(HERE, "in.eos"), "-log", "none",
        "-var", "dim", str(dim), "-var", "phi", str(phi), "-var", "nrun", str(nrun)]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    m = re.search(r"^EOS dim \d phi \S+ N (\d+) Z (\S+) Zeos (\S+)", out, re.M)
    if not m:
        raise RuntimeError(f"no EOS line for dim {dim}, phi {phi}:\n{out[-2000:]}")
    return int(m.group(1)), float(m.group(2))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="three fractions per dimension, shorter runs")
    ap.add_argument("--np", type=int, default=1, help="MPI ranks per run (default 1)")
    ap.add_argument("--out", default=HERE, help="folder of eos.png and eos.md")
    a = ap.parse_args()
    nrun = 50 if a.quick else 200
    rows = []
    for dim in (3, 2):
        fr = FRACTIONS[dim][1::3] if a.quick else FRACTIONS[dim]
        for phi in fr:
            n, z = run(dim, phi, nrun, a.np)
            rows.append((dim, phi, n, z, z_theory(dim, phi)))
            print(f"dim {dim} phi {phi}: Z = {z:.4f}, theory {z_theory(dim, phi):.4f}", flush=True)
    lines = ["| dim | fraction | N | Z measured | Z theory | deviation |", "|---|---|---|---|---|---|"]
    lines += [f"| {d} | {p} | {n} | {z:.4f} | {zt:.4f} | {100 * (z / zt - 1):+.2f} % |"
              for d, p, n, z, zt in rows]
    with open(os.path.join(a.out, "eos.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    fig, ax = plt.subplots(figsize=(5.5, 4))
    for dim, name, mark in ((3, "spheres, Carnahan-Starling", "o"), (2, "discs, Henderson", "s")):
        pts = [(p, z) for d, p, n, z, zt in rows if d == dim]
        x = np.linspace(0.0, max(FRACTIONS[dim]), 200)
        ax.plot(x, [z_theory(dim, v) for v in x], "-", lw=1, label=f"{name}")
        ax.plot([p for p, z in pts], [z for p, z in pts], mark, label=f"GRANFRIC {dim}D (press)")
    ax.set_xlabel("packing fraction")
    ax.set_ylabel("Z = P V / (N k T)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "eos.png"), dpi=120)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
