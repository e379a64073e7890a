# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Collision-law demonstration: single collisions of two particles under the three papers'
collision laws, computed by the C++ core (the laws the pair styles hand to fix hardsphere/ed),
with no simulation: a table of post-collision states and energy changes at three impact angles,
and a figure of the tangential restitution and the energy change against the impact angle.
The papers' scenes simulated: tools/reproduce PAPER, and examples/.

    /usr/bin/python3 tools/granfric collisions [--out DIR]
"""
import argparse
import math
import os

import numpy as np

from . import core

# the papers' laws (equal particles of unit mass and diameter)
CASES = [
    ("Luding 1998, rough discs (2D, q=1/2)", "rough", (0.9, 0.0), 0.5),
    ("Herbst 2005, Walton spheres in 2D (q=2/5)", "walton", (0.95, 0.5, 0.4), 0.4),
    ("Herbst 2005, Walton, mu=0.01", "walton", (0.95, 0.01, 0.4), 0.4),
    ("Risso 2005, Jenkins-Zhang discs (q=1/2)", "jz", (0.05, 0.05, 0.3, 0.3), 0.5),
]


def oblique(law, coeffs, q, gamma_deg, spin=0.0):
    """Disc/sphere 1 hits resting 2 at impact angle gamma (deg) with |g| = 1, 2D."""
    g = math.radians(gamma_deg)
    n = (1.0, 0.0, 0.0)
    b1 = core.Body(v=(math.cos(g), math.sin(g), 0.0), w=(0.0, 0.0, spin), q=q)
    b2 = core.Body(q=q)
    return core.collide(law, coeffs, b1, b2, n), b1, b2


def table():
    lines = ["| law | coefficients | gamma (deg) | v1' | w1' | v2' | w2' | dE | rt | sliding |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for name, law, coeffs, q in CASES:
        for gam in (180.0, 135.0, 100.0):
            c, _, _ = oblique(law, coeffs, q, gam)
            f = lambda v: "(%.4f, %.4f)" % (v[0], v[1])
            lines.append(f"| {name} | {coeffs} | {gam:.0f} | {f(c.v1)} | {c.w1[2]:.4f} | "
                         f"{f(c.v2)} | {c.w2[2]:.4f} | {c.dE:.5f} | {c.rt:.4f} | {c.sliding} |")
    return "\n".join(lines)


def figure(path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    gammas = np.linspace(90.5, 180.0, 400)
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    for name, law, coeffs, q in CASES:
        rt, de = [], []
        for gam in gammas:
            c, b1, b2 = oblique(law, coeffs, q, gam)
            rt.append(c.rt)
            de.append(c.dE)
        ax[0].plot(gammas, rt, label=name)
        ax[1].plot(gammas, de, label=name)
    ax[0].set_xlabel("impact angle gamma (deg)")
    ax[0].set_ylabel("tangential restitution rt = -g_t'/g_t")
    ax[1].set_xlabel("impact angle gamma (deg)")
    ax[1].set_ylabel("energy change dE (m = 1, |g| = 1)")
    ax[0].legend(fontsize=7)
    ax[0].set_title("sticking (rt = rt_max) vs sliding (Coulomb limit)")
    ax[1].set_title("energy loss per collision")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default="out", help="output directory (default: out)")
    a = ap.parse_args(argv)
    os.makedirs(a.out, exist_ok=True)
    t = table()
    with open(os.path.join(a.out, "collision_table.md"), "w") as f:
        f.write(t + "\n")
    print(t)
    png = os.path.join(a.out, "collision_laws.png")
    figure(png)
    print(f"wrote {png} and {os.path.join(a.out, 'collision_table.md')}")


if __name__ == "__main__":
    main()
