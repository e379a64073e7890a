# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Risso et al. 2005, Sec. II: mean energy change per collision <dE>(kappa, q) of equal discs over
a Maxwellian at T0, by Monte Carlo through the same C++ collision law the simulations use
(core/energy_loss.cpp: collisions weighted by the normal relative speed, spins Maxwellian with
I <w^2> = T0), the effective normal inelasticity q_eff (eq 9) and the friction of maximum loss.
Closed-form cross-check: for kappa_s = kappa_d the Jenkins-Zhang law equals Walton's, whose
Gaussian average is Herbst's model E (granfric.meanfield.mean_energy_changes)."""
import ctypes
import math

import numpy as np

from . import core


def mean_dE(kappa, q, T0=1.0, n=200000, seed=12345, qt=None, dim=2, q_shape=0.5):
    """<dE> per collision with q_n = q, q_t = qt (default q), kappa_s = kappa_d = kappa, for discs
    (q_shape 1/2) in 2D. Returns (mean, standard error, sliding fraction)."""
    qt = q if qt is None else qt
    c = np.array([q, qt, kappa, kappa], dtype=float)
    out = np.zeros(3)
    lib = core.lib()
    f = lib.granfric_mean_energy_loss
    d = ctypes.POINTER(ctypes.c_double)
    f.argtypes = [ctypes.c_int, d, ctypes.c_double, ctypes.c_int, ctypes.c_double, ctypes.c_long,
                  ctypes.c_ulong, d]
    f.restype = ctypes.c_int
    rc = f(2, c.ctypes.data_as(d), q_shape, dim, T0, n, seed, out.ctypes.data_as(d))
    if rc != 0:
        raise ValueError(f"invalid Jenkins-Zhang coefficients q = {q}, qt = {qt}, kappa = {kappa}")
    return float(out[0]), float(out[1]), float(out[2])


def frictionless_dE(q, T0=1.0):
    """Risso eq 8: <dE> = -4 q_n (1 - q_n) T0 without friction."""
    return -4.0 * q * (1.0 - q) * T0


def q_eff(dE, T0=1.0):
    """Risso eq 9: q_eff = (1 - sqrt(1 + <dE>/T0)) / 2; None ("undefined") where <dE> < -T0
    (doc/conventions.rst, correction 10)."""
    x = 1.0 + dE / T0
    if x < 0.0:
        return None
    return 0.5 * (1.0 - math.sqrt(x))


def closed_form_dE(kappa, q, T0=1.0, q_shape=0.5):
    """Gaussian average of the same law in closed form: Jenkins-Zhang with kappa_s = kappa_d is
    Walton's law (r = 1 - 2 q_n, rt_max = 1 - 2 q_t, mu = kappa), whose average is model E."""
    from . import meanfield
    dEtr, dErot = meanfield.mean_energy_changes("E", 1 - 2 * q, 1 - 2 * q, kappa, q_shape, T0, T0)
    return dEtr + dErot


def kappa_of_max_loss(q, kmin=0.02, kmax=3.0, npts=40, **kw):
    """kappa where |<dE>| is largest (Risso: about 0.3), from the closed form on a log grid,
    refined by a parabola through the three best points in log kappa."""
    ks = np.exp(np.linspace(math.log(kmin), math.log(kmax), npts))
    vals = np.array([closed_form_dE(k, q, **kw) for k in ks])
    i = int(np.argmin(vals))
    i = min(max(i, 1), npts - 2)
    x, y = np.log(ks[i - 1:i + 2]), vals[i - 1:i + 2]
    a, b, _ = np.polyfit(x, y, 2)
    return float(math.exp(-b / (2 * a)))
