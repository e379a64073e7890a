# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Kinetic theory of uniform shear flow (USF): DSMC of the homogeneous Enskog-Boltzmann equation
of rough or frictional hard discs (2D) and spheres (3D) in the frame of the flow, with the
collision map of the C++ core (core.collide_batch, the law the LAMMPS styles use).

    PYTHONPATH=tools /usr/bin/python3 -m granfric.usf [--quick|--full] [--out DIR]

In USF the mean velocity is u = (a y, 0, 0) with a the shear rate, and the state is homogeneous
in the peculiar velocities c = v - u. The Enskog-Boltzmann equation of the peculiar velocity
distribution f(c, w) is

    df/dt - a c_y df/dc_x = J_E[f, f],

the shear term being the free streaming in the flow's frame (c_x of a particle that does not
collide changes at -a c_y: its own velocity stays, the flow around it changes). At finite
density the two centres of a colliding pair lie sigma n apart (n the unit normal from 2 to 1),
so the flow differs across the pair by a sigma n_y in x: the velocity of 1 relative to 2 is
g = c1 - c2 + a sigma n_y x, and they collide at the rate n g2 sigma^(d-1) |g.n| for g.n < 0
(g2 the contact value of the pair correlation, as in cooling.py). The collision law acts on
both velocities in one frame (c1 + a sigma n_y x and c2), and the collisional transfer of
momentum across sigma n gives the collisional stress.

Scheme: that of dsmc.py (Babovsky's disjoint pairs with a majorant), with uniform normals and
acceptance |g.n| / G_max, G_max = 2 max|c| + |a| sigma, since g depends on n; a step is a
fraction EPS of the mean free time, and in each step every velocity first streams
(c_x -= a c_y dt, exact for the linear term). The pressure tensor is
P_ij = n m <c_i c_j> + (sum over collisions of sigma n_i dp_j) / (V t), dp the momentum change
of particle 1 and V = N / n, averaged over the steady state. Reported in reduced form:
a* = a / nu with nu = G T^1/2 / 2 (cooling.collision_frequency, the Enskog collision
frequency of a Maxwellian gas at the translational temperature T), P*_ij = P_ij / (n T),
T_rot / T_tr, and the measured collisions per particle and unit time over nu.
"""
import math

import numpy as np

from . import cli, cooling, core, dsmc

EPS = 0.005    # time step / mean free time (as dsmc.EPS)


def unit_normals(k, dim, rng):
    if dim == 2:
        t = rng.uniform(0.0, 2.0 * math.pi, k)
        return np.stack([np.cos(t), np.sin(t), np.zeros(k)], axis=1)
    x = rng.normal(size=(k, 3))
    return x / np.linalg.norm(x, axis=1)[:, None]


def run(law, coeffs, dim, phi, shear, t_relax, t_avg, N=20000, q=None, a=0.5, m=1.0, seed=1,
        eps=None, T0=1.0):
    """Steady USF at shear rate `shear` from a Maxwellian at T0 (no spin): relaxation for
    t_relax, then averages over t_avg. Returns a dict: Ttr, Trot, R, P (3x3, pressure tensor),
    Pk (its kinetic part), dissipation (energy lost in collisions per volume and time), a_star, P_star (P / (n T_tr)), nu (collision frequency of cooling.py at
    the mean T_tr), coll_rate (measured collisions per particle and unit time), and the series
    (t, Ttr) of the whole run."""
    q = dsmc.SHAPE[dim] if q is None else q
    eps = EPS if eps is None else eps
    I = q * m * a * a
    rng = np.random.default_rng(seed)
    if N % 2:
        raise ValueError("N must be even")
    v = rng.normal(size=(N, 3)) * math.sqrt(T0 / m)
    if dim == 2:
        v[:, 2] = 0.0
    v -= v.mean(axis=0)
    w = np.zeros((N, 3))
    n_dens = dsmc.density(phi, a, dim)
    g2 = cooling.pair_correlation(phi, dim)
    sigma = 2.0 * a
    solid = 2.0 * math.pi if dim == 2 else 4.0 * math.pi
    rate_const = (N - 1) / N * n_dens * g2 * sigma ** (dim - 1) * solid    # P_c = rate_const G_max dt
    volume = N / n_dens
    t, t_end = 0.0, t_relax + t_avg
    ncoll, vir, lost = 0, np.zeros((3, 3)), 0.0
    acc_T = acc_R = acc_time = 0.0
    acc_K = np.zeros((3, 3))
    series = []
    while t < t_end:
        Ttr = m * np.einsum("ij,ij->", v, v) / (dim * N)
        nu = cooling.collision_frequency(max(Ttr, 1e-300), phi, a, m, dim)
        Gmax = 2.0 * math.sqrt(np.max(np.einsum("ij,ij->i", v, v))) + abs(shear) * sigma
        dt = min(eps / nu, 1.0 / (rate_const * Gmax))
        if t < t_relax < t + dt:
            dt = t_relax - t
        dt = min(dt, t_end - t)
        averaging = t >= t_relax
        if averaging:
            K = m * np.einsum("ni,nj->ij", v, v) / N
            acc_K += K * dt
            acc_T += Ttr * dt
            acc_R += (I * np.einsum("ij,ij->", w, w) / (1 if dim == 2 else 3) / N) * dt
            acc_time += dt
        v[:, 0] -= shear * v[:, 1] * dt    # (streaming in the flow's frame)
        t += dt
        series.append((t, Ttr))
        M = rng.binomial(N // 2, min(1.0, rate_const * Gmax * dt))
        if M == 0:
            continue
        idx = rng.choice(N, 2 * M, replace=False)
        i, j = idx[:M], idx[M:]
        nrm = unit_normals(M, dim, rng)
        shift = shear * sigma * nrm[:, 1]    # (the flow at 1 less the flow at 2, in x)
        g = v[i] - v[j]
        g[:, 0] += shift
        gn = np.einsum("ij,ij->i", g, nrm)
        acc = (gn < 0.0) & (rng.uniform(0.0, Gmax, M) < -gn)
        if not np.any(acc):
            continue
        i, j, nrm, shift = i[acc], j[acc], nrm[acc], shift[acc]
        v1, w1, v2, w2 = v[i], w[i], v[j], w[j]
        v1[:, 0] += shift
        before = v1.copy()
        dE = core.collide_batch(law, coeffs, v1, w1, v2, w2, np.ascontiguousarray(nrm), m=m, a=a, q=q,
                                want_dE=True)
        if averaging:
            vir += np.einsum("ni,nj->ij", sigma * nrm, m * (v1 - before))
            lost -= dE.sum()
        v1[:, 0] -= shift
        v[i], w[i], v[j], w[j] = v1, w1, v2, w2
        if averaging:
            ncoll += len(i)
    Ttr = acc_T / acc_time
    Trot = acc_R / acc_time
    Pk = n_dens * acc_K / acc_time
    P = Pk + vir / (volume * acc_time)
    nu = cooling.collision_frequency(Ttr, phi, a, m, dim)
    return {"Ttr": Ttr, "Trot": Trot, "R": Trot / Ttr, "P": P, "Pk": Pk, "nu": nu,
            "dissipation": lost / (volume * acc_time),
            "a_star": shear / nu, "P_star": P / (n_dens * Ttr), "coll_rate": 2.0 * ncoll / (N * acc_time),
            "n": n_dens, "series": np.array(series)}


def steady(law, coeffs, dim, phi, shear, runs=4, seed=1, **kw):
    """run() over independent seeds: each result's mean and standard error (dicts of values, the
    tensors as 3x3 arrays)"""
    res = [run(law, coeffs, dim, phi, shear, seed=seed + 7919 * k, **kw) for k in range(runs)]
    keys = ("Ttr", "Trot", "R", "P", "Pk", "nu", "a_star", "P_star", "coll_rate", "n")
    mean = {k: np.mean([r[k] for r in res], axis=0) for k in keys}
    se = {k: np.std([r[k] for r in res], axis=0, ddof=1) / math.sqrt(runs) if runs > 1 else
          np.nan * np.asarray(mean[k]) for k in keys}
    return mean, se


CASES = [("rough", (0.9, -1.0), 2, 0.05), ("rough", (0.9, 0.0), 2, 0.05),
         ("rough", (0.9, 0.0), 3, 0.05), ("walton", (0.9, 0.3, 0.4), 2, 0.05)]


def main(argv=None):
    a = cli.scene_args(argv, __doc__, "out/usf", "4 cases, N = 20000 x 4 runs",
                       "N = 100000 x 8 runs, and the time step halved")
    N, runs = (100000, 8) if a.full else (20000, 4)
    lines = [f"# Uniform shear flow: DSMC of the Enskog-Boltzmann equation (N = {N}, {runs} runs)", "",
             "Shear rate a = 0.05 (units: diameter 1, mass 1); steady state after t = 400, averaged "
             "over t = 400. a* = a/nu, P* = P/(nT).", "",
             "| law | dim | phi | T_tr | R | a* | P*_xx | P*_yy | P*_xy | coll/(nu) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for law, coeffs, dim, phi in cli.progress(CASES, "USF runs"):
        m, s = steady(law, coeffs, dim, phi, 0.05, runs=runs, N=N, t_relax=400.0, t_avg=400.0,
                      eps=EPS / 2 if a.full else EPS)
        P = m["P_star"]
        lines.append(f"| {law} {coeffs} | {dim} | {phi} | {m['Ttr']:.4g} ± {s['Ttr']:.2g} | "
                     f"{m['R']:.4f} | {m['a_star']:.4f} ± {s['a_star']:.1g} | {P[0, 0]:.4f} | "
                     f"{P[1, 1]:.4f} | {P[0, 1]:.4f} ± {s['P_star'][0, 1]:.1g} | "
                     f"{m['coll_rate'] / m['nu']:.4f} |")
    cli.write_report(a.out, lines)


if __name__ == "__main__":
    main()
