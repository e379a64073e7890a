"""Herbst et al. 2005 scene: randomly driven 2D monolayer of rough spheres (q = 2/5) with Coulomb
friction (Walton law), simulated with GRANFRIC (examples/driven) and compared with the mean-field
model E (granfric.meanfield) in the steady state.

    PYTHONPATH=tools /usr/bin/python3 -m granfric.herbst [--quick|--full] [--out DIR]
"""
import argparse
import math
import os

import numpy as np

from . import cooling, lammpslog, lmp

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
