# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Homogeneous cooling of rough spheres and discs with constant normal and tangential restitution
(Luding, Huthmann, McNamara & Zippelius 1998; Herbst et al. 2005 model A with no driving).

Conventions of doc/conventions.rst: temperatures per degree of freedom (k_B = 1);
2D (spin about z, one rotational dof): T_tr = E_tr/N, T_rot = 2 E_rot/N; 3D: T_tr = 2E_tr/(3N),
T_rot = 2E_rot/(3N). q = I/(m a^2) is independent of the dimension.

Mean-field equations (Gaussian velocities, molecular chaos), eta = q (1 + rt) / (2 (1 + q)):
  2D  dT_tr/dt = G T_tr^1/2 (-A T_tr + B T_rot),   dT_rot/dt = 2 G T_tr^1/2 (B T_tr - C T_rot)
      A = (1 - r^2)/4 + eta (1 - eta)/2,  B = eta^2/(2q),  C = eta/(2q) (1 - eta/q)
      G = 8 sqrt(pi/m) a n g2(2a), Henderson g2 = (1 - 7 nu/16)/(1 - nu)^2
  3D  dT_tr/dt = (2/3) G T_tr^1/2 (-A T_tr + B T_rot), dT_rot/dt = (2/3) G T_tr^1/2 (B T_tr - C T_rot)
      A = (1 - r^2)/4 + eta (1 - eta),    B = eta^2/q,      C = eta/q (1 - eta/q)
      G = 32 sqrt(pi/m) a^2 n g3(2a), Carnahan-Starling g3 = (1 - nu/2)/(1 - nu)^3
In both, the collision frequency per particle is G T_tr^1/2 / 2. The coefficients follow from the
averages of the translational and rotational energy changes of the collision map over Gaussian
velocities, weighted with the normal relative speed (the collision map and the temperatures are
those of doc/conventions.rst).
"""
import math
from dataclasses import dataclass

import numpy as np


def eta(rt, q):
    return q * (1.0 + rt) / (2.0 * (1.0 + q))


@dataclass
class Coefficients:
    A: float
    B: float
    C: float
    dim: int

    @property
    def k(self):
        """dT_rot/dt prefactor relative to dT_tr/dt: 2 in 2D (one rotational dof), 1 in 3D."""
        return 2.0 if self.dim == 2 else 1.0

    @property
    def scale(self):
        """dT_tr/dt = scale * G T^1/2 (...): 1 in 2D, 2/3 in 3D."""
        return 1.0 if self.dim == 2 else 2.0 / 3.0


def coefficients(r, rt, q, dim):
    """A, B (= B'), C for constant normal restitution r and tangential restitution rt."""
    e = eta(rt, q)
    if dim == 2:
        return Coefficients((1 - r * r) / 4 + e * (1 - e) / 2, e * e / (2 * q),
                            e / (2 * q) * (1 - e / q), 2)
    if dim == 3:
        return Coefficients((1 - r * r) / 4 + e * (1 - e), e * e / q, e / q * (1 - e / q), 3)
    raise ValueError("dim must be 2 or 3")


def pair_correlation(nu, dim):
    """Henderson (2D) or Carnahan-Starling (3D) pair correlation at contact."""
    if dim == 2:
        return (1 - 7 * nu / 16) / (1 - nu) ** 2
    return (1 - nu / 2) / (1 - nu) ** 3


def time_scale_G(nu, a, m, dim):
    """G of the mean-field equations for fraction nu (area in 2D, volume in 3D)."""
    g = pair_correlation(nu, dim)
    if dim == 2:
        n = nu / (math.pi * a * a)
        return 8.0 * math.sqrt(math.pi / m) * a * n * g
    n = nu / (4.0 / 3.0 * math.pi * a ** 3)
    return 32.0 * math.sqrt(math.pi / m) * a * a * n * g


def collision_frequency(T, nu, a, m, dim):
    return 0.5 * time_scale_G(nu, a, m, dim) * math.sqrt(T)


def asymptotic_R(r, rt, q, dim):
    """Ratio T_rot/T_tr of the homogeneous cooling state: positive root of
    B R^2 + (k C - A) R - k B = 0 (dR/dt = 0)."""
    c = coefficients(r, rt, q, dim)
    if c.B == 0.0:
        return 0.0
    b = c.k * c.C - c.A
    return (-b + math.sqrt(b * b + 4 * c.k * c.B * c.B)) / (2 * c.B)


def rhs(T, c, G):
    Ttr, Trot = max(T[0], 0.0), max(T[1], 0.0)
    s = c.scale * G * math.sqrt(Ttr)
    return np.array([s * (-c.A * Ttr + c.B * Trot), c.k * s * (c.B * Ttr - c.C * Trot)])


def integrate(r, rt, q, dim, nu, a=0.5, m=1.0, T0=(1.0, 0.0), times=None, H=0.0):
    """T_tr(t), T_rot(t) of the mean-field equations (RK4 on a fine grid), optionally with a
    constant translational heating rate H (driving). Returns (times, Ttr, Trot)."""
    c = coefficients(r, rt, q, dim)
    G = time_scale_G(nu, a, m, dim)
    times = np.asarray(times if times is not None else np.linspace(0, 100, 1001), dtype=float)
    out = np.zeros((len(times), 2))
    T = np.array(T0, dtype=float)
    t = times[0]
    out[0] = T
    f = lambda y: rhs(y, c, G) + np.array([H, 0.0])
    for k in range(1, len(times)):
        # substeps small against the collision time at the current temperature
        while t < times[k]:
            rate = 0.5 * G * math.sqrt(max(T[0], 1e-300))
            h = min(times[k] - t, 0.02 / max(rate, 1e-300))
            k1 = f(T)
            k2 = f(T + 0.5 * h * k1)
            k3 = f(T + 0.5 * h * k2)
            k4 = f(T + h * k3)
            T = T + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
            t += h
        out[k] = T
    return times, out[:, 0], out[:, 1]


def early_slopes(r, rt, q, dim, nu, a=0.5, m=1.0, T0=1.0):
    """Initial rates from T_tr = T0, T_rot = 0: dT_tr/dt = -scale G A T0^3/2 and
    dT_rot/dt = k scale G B T0^3/2 (linear change at short times)."""
    c = coefficients(r, rt, q, dim)
    G = time_scale_G(nu, a, m, dim)
    return -c.scale * G * c.A * T0 ** 1.5, c.k * c.scale * G * c.B * T0 ** 1.5


def late_decay(r, rt, q, dim, nu, a=0.5, m=1.0):
    """With R at its asymptotic value, T_tr(t) ~ (1 + t/t0)^-2 with
    1/t0 = scale G (A - B R) T0^1/2 / 2: returns the coefficient scale*G*(A - B R)/2."""
    c = coefficients(r, rt, q, dim)
    R = asymptotic_R(r, rt, q, dim)
    return 0.5 * c.scale * time_scale_G(nu, a, m, dim) * (c.A - c.B * R)
