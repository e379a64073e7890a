# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Grad's moment theory of uniform shear flow (USF) for any collision law of the C++ core: the
steady reduced shear rate, pressure tensor and T_rot/T_tr in closed form from three collision
integrals, which are evaluated by Monte Carlo with the core's collision map (core.collide_batch).

    PYTHONPATH=tools /usr/bin/python3 -m granfric.usf_grad [--quick|--full] [--out DIR]

The velocity distribution is taken as Grad's: a Maxwellian at T_tr times
(1 + pi_ij c_i c_j / (2 T_tr)), pi_ij = P_ij / p - delta_ij traceless, the spins Maxwellian at
T_rot = R T_tr and uncorrelated with c. To first order in pi the collisional change of the
second moments is, per particle (mass 1, p = n T_tr),

    d<c_i c_j>/dt |coll = -nu_eta pi_ij T_tr + lambda T_tr delta_ij,

nu_eta (the relaxation rate of the traceless stress) and lambda (the cooling of the translational
motion, -zeta) being integrals over Maxwellian pairs: with a pair drawn at the collision rate
(weight |g.n| for approaching pairs, g the relative velocity, n the normal), E the weighted
mean and nu the collision frequency per particle (cooling.collision_frequency: the Enskog
frequency of a Maxwellian gas),

    lambda / nu = E[d|c1|^2 + d|c2|^2] / (2 d T_tr),
    nu_eta / nu = -E[(c1x c1y + c2x c2y) (d(c1x c1y) + d(c2x c2y))] / (2 T_tr^2)

(the collision operator is isotropic: every traceless component of X = c1 c1 + c2 c2 relaxes
alike, and the code averages them all, E[X' : dX] / (4 D T_tr^2) with X' the traceless part and
D = d (d + 1) / 2 - 1 their number: the same rate with less noise),

and R solves E[d(I w1^2) + d(I w2^2)] = 0 (spins are not sheared: their energy balances in
collisions alone). The moment equations of USF, d<c_i c_j>/dt + a (delta_ix <c_y c_j> +
delta_jx <c_i c_y>) = coll, in the steady state give

    P*_yy = P*_zz = 1 + lambda / nu_eta,   P*_xy = -a* P*_yy / nu_eta*,
    a* = sqrt(-d lambda* nu_eta* / (2 P*_yy)),   P*_xx = d - (d - 1) P*_yy,

with a* = a / nu and the rates in units of nu. This is the Boltzmann limit: at finite density
the rates carry the contact value g2 (as nu does) and cancel, and the collisional transfer of
momentum is left out. For smooth particles lambda* = -(d + 2)(1 - r^2)/(4 d) nu0/nu and nu_eta* =
(1 + r)(3 - 3 r + 2 d)/(4 d) nu0/nu (nu0 = p / eta0, eta0 the elastic gas's viscosity), which the
test checks the Monte Carlo against.
"""
import math

import numpy as np
from scipy.optimize import brentq

from . import cli, core, dsmc

SAMPLES = 3_000_000


def _pairs(dim, samples, seed):
    """Maxwellian pairs at T_tr = 1 drawn at the collision rate, unit spins (scaled later) and
    normals from 2 to 1: (c1, c2, s1, s2, n, weight)"""
    rng = np.random.default_rng(seed)
    c1 = rng.normal(size=(samples, 3))
    c2 = rng.normal(size=(samples, 3))
    s1 = rng.normal(size=(samples, 3))
    s2 = rng.normal(size=(samples, 3))
    if dim == 2:
        t = rng.uniform(0.0, 2.0 * math.pi, samples)
        n = np.stack([np.cos(t), np.sin(t), np.zeros(samples)], axis=1)
        for x in (c1, c2):
            x[:, 2] = 0.0
        for s in (s1, s2):
            s[:, :2] = 0.0
    else:
        n = rng.normal(size=(samples, 3))
        n /= np.linalg.norm(n, axis=1)[:, None]
    gn = np.einsum("ij,ij->i", c1 - c2, n)
    keep = gn < 0.0
    return c1[keep], c2[keep], s1[keep], s2[keep], np.ascontiguousarray(n[keep]), -gn[keep]


def _collide(law, coeffs, pairs, R, q, restitution=None):
    """the pairs after the law, spins Maxwellian at T_rot = R (I = q m a^2, m = 1, a = 1/2)"""
    c1, c2, s1, s2, n, _ = pairs
    scale = math.sqrt(R / (q * 0.25))
    v1, v2 = c1.copy(), c2.copy()
    w1, w2 = np.ascontiguousarray(s1 * scale), np.ascontiguousarray(s2 * scale)
    core.collide_batch(law, coeffs, v1, w1, v2, w2, n, m=1.0, a=0.5, q=q, restitution=restitution)
    return v1, v2, w1, w2, scale


def _mean(weight, x):
    return float(np.sum(weight * x) / np.sum(weight))


def rotational_balance(law, coeffs, pairs, R, q, restitution=None):
    """E[change of the spins' energy] per collision at T_rot = R T_tr (T_tr = 1)"""
    c1, c2, s1, s2, n, wt = pairs
    v1, v2, w1, w2, scale = _collide(law, coeffs, pairs, R, q, restitution)
    I = q * 0.25
    before = (s1 * s1).sum(axis=1) + (s2 * s2).sum(axis=1)
    after = (w1 * w1).sum(axis=1) + (w2 * w2).sum(axis=1)
    return 0.5 * I * _mean(wt, after - before * scale * scale)


def steady_R(law, coeffs, pairs, q, restitution=None):
    """T_rot / T_tr at which collisions neither feed nor drain the spins (0 where collisions
    give no spin: smooth laws)"""
    if not rotational_balance(law, coeffs, pairs, 0.0, q, restitution) > 0.0:
        return 0.0
    hi = 1.0
    while rotational_balance(law, coeffs, pairs, hi, q, restitution) > 0.0:
        hi *= 2.0
        if hi > 1e6:
            raise ValueError("no steady T_rot/T_tr below 1e6")
    return brentq(lambda R: rotational_balance(law, coeffs, pairs, R, q, restitution), 0.0, hi,
                  xtol=1e-10, rtol=1e-10)


def grad(law, coeffs, dim, q=None, samples=SAMPLES, seed=1, restitution=None):
    """Grad's steady USF of the law (module doc): dict with R, lam (lambda*), nu_eta (nu_eta*),
    a_star, P_star (3x3), rates in units of the collision frequency"""
    q = dsmc.SHAPE[dim] if q is None else q
    pairs = _pairs(dim, samples, seed)
    R = steady_R(law, coeffs, pairs, q, restitution)
    c1, c2, _, _, _, wt = pairs
    v1, v2, _, _, _ = _collide(law, coeffs, pairs, R, q, restitution)
    dk = (v1 * v1).sum(axis=1) + (v2 * v2).sum(axis=1) - (c1 * c1).sum(axis=1) - (c2 * c2).sum(axis=1)
    lam = _mean(wt, dk) / (2.0 * dim)
    # (X = c1 c1 + c2 c2 and its change dX: X's traceless part contracted with dX, which averages
    # the response of every traceless component, D of them; for xy alone it is 2 X_xy dX_xy / D)
    dot = lambda u, w: np.einsum("ij,ij->i", u, w)
    XY = dot(c1, v1) ** 2 + dot(c1, v2) ** 2 + dot(c2, v1) ** 2 + dot(c2, v2) ** 2
    XX = dot(c1, c1) ** 2 + 2.0 * dot(c1, c2) ** 2 + dot(c2, c2) ** 2
    trX = dot(c1, c1) + dot(c2, c2)
    D = dim * (dim + 1) // 2 - 1
    nu_eta = -_mean(wt, XY - XX - trX * dk / dim) / (4.0 * D)
    Pyy = 1.0 + lam / nu_eta
    a_star = math.sqrt(max(0.0, -dim * lam * nu_eta / (2.0 * Pyy)))
    P = np.zeros((3, 3))
    P[1, 1] = Pyy
    if dim == 3:
        P[2, 2] = Pyy
    P[0, 0] = dim - (dim - 1) * Pyy
    P[0, 1] = P[1, 0] = -a_star * Pyy / nu_eta
    return {"R": R, "lam": lam, "nu_eta": nu_eta, "a_star": a_star, "P_star": P}


def smooth_rates(r, dim):
    """lambda* and nu_eta* of smooth particles in Grad's approximation, in units of the collision
    frequency (nu0 / nu = 1 in 2d, 4/5 in 3d, nu0 = p / eta0 with the elastic gas's eta0)"""
    ratio = 1.0 if dim == 2 else 0.8
    lam = -(dim + 2) * (1.0 - r * r) / (4.0 * dim) * ratio
    nu_eta = (1.0 + r) * (3.0 - 3.0 * r + 2.0 * dim) / (4.0 * dim) * ratio
    return lam, nu_eta


CASES = [("rough", (0.9, -1.0), 2), ("rough", (0.9, 0.0), 2), ("rough", (0.7, 0.0), 2),
         ("rough", (0.9, 0.0), 3), ("walton", (0.9, 0.3, 0.4), 2)]


def main(argv=None):
    a = cli.scene_args(argv, __doc__, "out/usf_grad", f"{SAMPLES} samples per case",
                       f"{4 * SAMPLES} samples per case")
    samples = 4 * SAMPLES if a.full else SAMPLES
    lines = ["# Uniform shear flow: Grad's theory (Boltzmann limit)", "",
             "| law | dim | R | a* | P*_xx | P*_yy | P*_xy |", "|---|---|---|---|---|---|---|"]
    for law, coeffs, dim in CASES:
        g = grad(law, coeffs, dim, samples=samples)
        P = g["P_star"]
        lines.append(f"| {law} {coeffs} | {dim} | {g['R']:.4f} | {g['a_star']:.4f} | {P[0, 0]:.4f} | "
                     f"{P[1, 1]:.4f} | {P[0, 1]:.4f} |")
    cli.write_report(a.out, lines)


if __name__ == "__main__":
    main()
