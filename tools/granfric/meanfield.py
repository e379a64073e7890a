# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Driven mean-field theory of rough granular gases with Coulomb friction (Walton law):
Herbst, Cafiero, Zippelius, Herrmann & Luding, Phys. Fluids 17, 107102 (2005), models A-E, plus
the 3D homogeneous-cooling form of model E (appendix A23-A24).

Conventions (doc/conventions.rst, granfric.cooling): temperatures per degree of freedom,
k_B = 1. 2D monolayer, spin about z only: T_tr = E_tr/N, T_rot = 2 E_rot/N; R = T_rot/T_tr.
q = I/(m a^2) is free (spheres 2/5, discs 1/2).

    2D (eq 13):  dT_tr/dt  = H_dr + G T_tr^1/2 (-A T_tr + B T_rot)
                 dT_rot/dt = 2 G T_tr^1/2 (B' T_tr - C T_rot)
    3D (A23-24): (3/2) dT_tr/dt  = H_dr + G3D T_tr^1/2 (-A T_tr + B T_rot)
                 (3/2) dT_rot/dt = G3D T_tr^1/2 (B' T_tr - C T_rot)

G = 8 sqrt(pi/m) a n g2(2a) (eq 14, Henderson g2), collision rate per particle G T_tr^1/2 / 2.
In terms of per-collision averages (flux-weighted, Gaussian velocities and spins):
    <dE_tr>  = 4 (-A T_tr + B T_rot),   <dE_rot> = 4 (B' T_tr - C T_rot)     (2D and 3D).

Walton law: normal restitution r, friction coefficient mu, maximum tangential restitution rt_max;
rt(gamma) = min(rt_C(gamma), rt_max), rt_C = -1 - (1+q)/q mu (1+r) cot(gamma) (eq 5-6), i.e.
eta(rt) = q(1+rt)/(2(1+q)) equals eta0 = eta(rt_max) when sticking (|cot gamma| > c) and
eta0 |cot gamma| / c when sliding, with c = -cot gamma0 = q(1+rt_max)/(mu(1+q)(1+r)) (eq 22) and
eta0/c = mu (1+r)/2. x^2 = 1 + R/q (eq 27), f = sqrt(1+c^2) (eq 24), f~ = sqrt(1+x^2 c^2) (eq 28).
mu = inf gives c = 0 and every model reduces to model A; mu = 0 (or rt_max = -1) gives smooth
particles (A = A_r, B = B' = C = 0).

Corrections of doc/conventions.rst ("Corrections to the printed equations") applied here:
  1. eq 4: Delta P_t = -(m/2) q/(1+q) (1+rt) g_t (factor m/2) -- the collision map behind all
     coefficients (checked against the C++ law by Monte Carlo in the tests).
  2. eq 40: I = A_r + eta0(1-eta0)/2 - eta0^3/(2(q-eta0)) (plus sign on the middle term).
  3. eq 31: A* = eta0 c^2/2 - q B'* (B'*, not B*).
  4. eq 43: linearisation prefactor G (T_tr^stat)^1/2.
  5. A23: first correction term eta0 (1 - eta0 x^2)/(1 + x^2 cot^2 gamma0), not eta0/2 (...).
  6. eq 26: the long logarithm equals 4 ln(x c + f~).
  7. small mu: B, C ~ mu|ln mu|, D ~ (1+r) mu/|ln mu|, E ~ (1+r) mu.

Compact equivalents (derived independently from the collision map, used in the docstrings and
tests; the functions below implement the paper's printed forms):
  model E, 2D: -A + B R  = -A_r - eta0/(2 f~) + eta0^2 x^2/(f~ (1+f~))
               B' - C R  = eta0^2 x^2/(q f~ (1+f~)) - (x^2-1) eta0/(2 f~)
  model D:     A = A_r + eta0/(2f) - eta0^2/(f(1+f)),  B = eta0^2/(q(1+f)),
               B' = eta0^2/(q f (1+f)),  C = eta1/(2q) - eta0^2/(q^2 (1+f)).
"""
import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from granfric import cooling

MODELS = ("A", "B", "C", "D", "E")


# --------------------------------------------------------------------------------------------
# Walton-law parameters
# --------------------------------------------------------------------------------------------
def eta(rt, q):
    """eta(rt) = q (1 + rt) / (2 (1 + q)), eq 19 (same as granfric.cooling.eta)."""
    return cooling.eta(rt, q)


@dataclass(frozen=True)
class Walton:
    """Derived parameters of the Walton law (eqs 20, 22): eta0 = eta(rt_max), c = -cot gamma0
    (0 for mu = inf, inf for mu = 0), eta0_over_c = mu (1+r)/2 (finite for mu = 0, unused when
    mu = inf), smooth = True when no tangential impulse is ever exchanged (mu = 0 or
    rt_max = -1)."""
    r: float
    rt_max: float
    mu: float
    q: float
    eta0: float
    c: float
    A_r: float

    @property
    def smooth(self):
        return self.eta0 == 0.0 or self.mu == 0.0

    @property
    def eta0_over_c(self):
        return self.mu * (1.0 + self.r) / 2.0


def walton(r, rt_max, mu, q):
    """Validate (r, rt_max, mu, q) and return Walton(eta0, c = q(1+rt_max)/(mu(1+q)(1+r)) (eq 22),
    A_r = (1-r^2)/4 (eq 15))."""
    if not (0.0 <= r <= 1.0):
        raise ValueError("normal restitution r must be in [0, 1]")
    if not (-1.0 <= rt_max <= 1.0):
        raise ValueError("rt_max must be in [-1, 1]")
    if not (mu >= 0.0):
        raise ValueError("friction coefficient mu must be >= 0 (math.inf allowed)")
    if not (q > 0.0):
        raise ValueError("shape factor q must be > 0")
    e0 = eta(rt_max, q)
    if mu == math.inf:
        c = 0.0
    elif mu == 0.0:
        c = math.inf
    else:
        c = q * (1.0 + rt_max) / (mu * (1.0 + q) * (1.0 + r))
    return Walton(r, rt_max, mu, q, e0, c, (1.0 - r * r) / 4.0)


def x_of_R(R, q):
    """x = sqrt(1 + R/q), eq 27."""
    return math.sqrt(1.0 + R / q)


def asinh_ratio(k):
    """asinh(k)/k = ln(k + sqrt(1+k^2))/k, stable at k -> 0 (-> 1) and k = inf (-> 0)."""
    if k == math.inf:
        return 0.0
    if abs(k) < 1e-4:
        return 1.0 - k * k / 6.0 + 3.0 * k ** 4 / 40.0
    return math.asinh(k) / k


def atan_ratio(k):
    """arctan(k)/k, stable at k -> 0 (-> 1) and k = inf (-> 0)."""
    if k == math.inf:
        return 0.0
    if abs(k) < 1e-4:
        return 1.0 - k * k / 3.0 + k ** 4 / 5.0
    return math.atan(k) / k


def eta1(w):
    """Model B: eta1 = eta(<rt>_12) = (eta0/c) ln(c + f) = eta0 asinh(c)/c, eqs 23-25
    (<rt>_12 = -1 + (q+1)/q (1+r) mu ln(c+f))."""
    return w.eta0 * asinh_ratio(w.c)


def mean_rt_C(w, R):
    """Model C: <rt>(R) averaged over the impact-angle distribution P(gamma) of eq 12, eq 26 with
    correction 6 (the long logarithm equals 4 ln(xc + f~)):
        <rt>(R) = -1 + (q+1)/q (1+r) (mu/x) ln(xc + f~) = -1 + (1 + rt_max) asinh(xc)/(xc).
    R -> 0 gives eq 23, mu -> inf gives rt_max, mu -> 0 or R -> inf gives -1."""
    k = x_of_R(R, w.q) * w.c
    return -1.0 + (1.0 + w.rt_max) * asinh_ratio(k)


def eq26_long_log(c, R, q):
    """The long logarithm of eq 26 as printed,
        ln[ (R/q) (f - c)^2 (x f~ - f + c R/q) / ((x f~ - f - c R/q)^2 (x f~ + f - c R/q)) ],
    which by correction 6 equals 4 ln(x c + f~) (singular as printed at R = 0 and c = 0; kept to
    check the identity)."""
    x = x_of_R(R, q)
    f, ft, Rq = math.sqrt(1.0 + c * c), math.sqrt(1.0 + x * x * c * c), R / q
    num = Rq * (f - c) ** 2 * (x * ft - f + c * Rq)
    den = (x * ft - f - c * Rq) ** 2 * (x * ft + f - c * Rq)
    return math.log(num / den)


def eta2(w, R):
    """Model C: eta(<rt>(R)) = eta0 asinh(xc)/(xc) (eqs 19, 26 with correction 6)."""
    return eta(mean_rt_C(w, R), w.q)


def mean_rt_B(w):
    """Model B: <rt>_12 of eq 23 (rt averaged with P12(gamma12) = -cos gamma12)."""
    return -1.0 + (1.0 + w.rt_max) * asinh_ratio(w.c)


# --------------------------------------------------------------------------------------------
# coefficients
# --------------------------------------------------------------------------------------------
@dataclass
class Coefficients:
    """A, B, B', C of eq 13 (2D) or A23-A24 (3D) for one model (and one R for models C and E)."""
    A: float
    B: float
    Bprime: float
    C: float
    model: str
    dim: int = 2

    def as_tuple(self):
        return (self.A, self.B, self.Bprime, self.C)

    def __iter__(self):
        return iter(self.as_tuple())

    def F_tr(self, R):
        """-A + B R: dT_tr/dt = H + G T_tr^3/2 (-A + B R) in 2D."""
        return -self.A + self.B * R

    def F_rot(self, R):
        """B' - C R: dT_rot/dt = 2 G T_tr^3/2 (B' - C R) in 2D."""
        return self.Bprime - self.C * R


def _coeffs_const_eta(A_r, e, q):
    """Eqs 15-18 with eta0 replaced by e (models A, B, C)."""
    B = e * e / (2.0 * q)
    return A_r + e * (1.0 - e) / 2.0, B, B, e / (2.0 * q) * (1.0 - e / q)


def coefficients(model, r, rt_max, mu, q, R=None):
    """A, B, B', C of the 2D mean-field equations (eq 13) for Herbst's models A-E.

    A: eqs 15-18 with eta0 = eta(rt_max) (constant tangential restitution; mu plays no role).
    B: eqs 15-18 with eta0 -> eta1 = (eta0/c) ln(c + f), eq 25.
    C: eqs 15-18 with eta0 -> eta(<rt>(R)), eq 26 with correction 6 (long log = 4 ln(xc + f~));
       needs R.
    D: eqs 30-31 with correction 3 (A* = eta0 c^2/2 - q B'*), B* = eta0^2 c^2/(2q(f+1)^2),
       B'* = (2f+1) B*, C* = (eta1 f - eta0 - 2 B*)/(2q); denominators f^3 (A, B') and f (B, C).
    E: eqs 33-34: A = A_r + (A_eta0 + A~*)/f~^3, B = (B_eta0 + B~*)/f~^3, B' = (B_eta0 + B~'*)/f~^3,
       C = (C_eta0 + C~*)/f~^3 with B~* = -eta0 c^2/(2q), B~'* = (2f~+1)(eta0 c x^2)^2/(2q(f~+1)^2),
       A~* = -q (B~* + B~'*), C~* = -x^2 B~*; needs R. (Equivalent to the appendix A19, A22.)
    All coefficients rest on the collision map with the corrected eq 4 (factor m/2, correction 1).

    mu = math.inf gives model A for every model (c = 0); mu = 0 or rt_max = -1 gives smooth
    particles: A = (1 - r^2)/4, B = B' = C = 0.
    """
    model = model.upper()
    if model not in MODELS:
        raise ValueError(f"unknown model {model!r}; one of {MODELS}")
    w = walton(r, rt_max, mu, q)
    if model in ("C", "E"):
        if R is None:
            raise ValueError(f"model {model} depends on R = T_rot/T_tr: pass R")
        if not (R >= 0.0):
            raise ValueError("R must be >= 0")
    if w.smooth:
        return Coefficients(w.A_r, 0.0, 0.0, 0.0, model)
    e0, c = w.eta0, w.c
    if model == "A":
        return Coefficients(*_coeffs_const_eta(w.A_r, e0, q), model)
    if model == "B":
        return Coefficients(*_coeffs_const_eta(w.A_r, eta1(w), q), model)
    if model == "C":
        return Coefficients(*_coeffs_const_eta(w.A_r, eta2(w, R), q), model)
    A0 = e0 * (1.0 - e0) / 2.0          # A_eta0, eq 16
    B0 = e0 * e0 / (2.0 * q)            # B_eta0, eq 17
    C0 = e0 / (2.0 * q) * (1.0 - e0 / q)  # C_eta0, eq 18
    if model == "D":
        f = math.sqrt(1.0 + c * c)                         # eq 24
        Bs = e0 * e0 * c * c / (2.0 * q * (f + 1.0) ** 2)  # B*, eq 31
        Bps = (2.0 * f + 1.0) * Bs                         # B'*
        As = e0 * c * c / 2.0 - q * Bps                    # A*, correction 3 (B'*, not B*)
        Cs = (eta1(w) * f - e0 - 2.0 * Bs) / (2.0 * q)     # C*
        f3 = f ** 3
        return Coefficients(w.A_r + (A0 + As) / f3, (B0 + Bs) / f, (B0 + Bps) / f3,
                            (C0 + Cs) / f, model)
    # model E
    x2 = 1.0 + R / q
    ft = math.sqrt(1.0 + x2 * c * c)                              # f~, eq 28
    Bs = -e0 * c * c / (2.0 * q)                                  # B~*, eq 34
    Bps = (2.0 * ft + 1.0) * (e0 * c * x2) ** 2 / (2.0 * q * (ft + 1.0) ** 2)  # B~'*
    As = -q * (Bs + Bps)                                          # A~*
    Cs = -x2 * Bs                                                 # C~*
    ft3 = ft ** 3
    return Coefficients(w.A_r + (A0 + As) / ft3, (B0 + Bs) / ft3, (B0 + Bps) / ft3,
                        (C0 + Cs) / ft3, model)


def coefficients_3d(model, r, rt_max, mu, q, R=None):
    """A, B, B', C of the 3D mean-field equations for model A (Luding 1998, constant
    rt = rt_max) or model E (Coulomb friction, Herbst appendix A23-A24 with correction 5):

        (3/2) dT_tr/dt  = H - G3D T_tr^3/2 [A_r + eta0 (1 - eta0 x^2)/f^2
                                             + eta0/2 (arctan(k)/k - 1/f^2)]          (A23 corr.)
        (3/2) dT_rot/dt = G3D T_tr^3/2 [eta0 (1 - (1 - eta0/q) x^2)/f^2
                                         - eta0/2 (x^2 - 1)(arctan(k)/k - 1/f^2)]     (A24)

    with k = x cot|gamma0| = x c, f^2 = 1 + k^2. Written as (3/2) dT_tr/dt = G3D T^1/2 (-A T_tr +
    B T_rot) and (3/2) dT_rot/dt = G3D T^1/2 (B' T_tr - C T_rot) using x^2 = 1 + R/q:
        A = A_r + eta0/2 (arctan(k)/k + 1/f^2) - eta0^2/f^2,   B = B' = eta0^2/(q f^2),
        C = eta0/(2q) (arctan(k)/k + 1/f^2) - eta0^2/(q^2 f^2).
    mu = inf (k = 0) gives Luding's A = A_r + eta0(1-eta0), B = eta0^2/q, C = eta0/q (1-eta0/q)
    (granfric.cooling.coefficients(dim=3)). Model E needs R."""
    model = model.upper()
    if model not in ("A", "E"):
        raise ValueError("3D: models 'A' and 'E' only")
    w = walton(r, rt_max, mu, q)
    if w.smooth:
        return Coefficients(w.A_r, 0.0, 0.0, 0.0, model, 3)
    e0 = w.eta0
    if model == "A" or w.c == 0.0:
        k = 0.0
    else:
        if R is None or not (R >= 0.0):
            raise ValueError("model E depends on R = T_rot/T_tr >= 0: pass R")
        k = x_of_R(R, q) * w.c
    f2 = 1.0 + k * k
    s = atan_ratio(k) + 1.0 / f2
    B = e0 * e0 / (q * f2)
    return Coefficients(w.A_r + e0 / 2.0 * s - e0 * e0 / f2, B, B,
                        e0 / (2.0 * q) * s - e0 * e0 / (q * q * f2), model, 3)


def appendix_A23_A24(r, rt_max, mu, q, R):
    """The right-hand brackets of the appendix equations (3D, model E) as printed with
    correction 5: returns (P_tr, P_rot) with (3/2) dT_tr/dt = H - G3D T^3/2 P_tr and
    (3/2) dT_rot/dt = G3D T^3/2 P_rot (used to check coefficients_3d)."""
    w = walton(r, rt_max, mu, q)
    e0, x2 = w.eta0, 1.0 + R / q
    k = math.sqrt(x2) * w.c
    f2 = 1.0 + k * k
    bracket = atan_ratio(k) - 1.0 / f2
    P_tr = w.A_r + e0 * (1.0 - e0 * x2) / f2 + e0 / 2.0 * bracket
    P_rot = e0 * (1.0 - (1.0 - e0 / q) * x2) / f2 - e0 / 2.0 * (x2 - 1.0) * bracket
    return P_tr, P_rot


def appendix_A19_A22(r, rt_max, mu, q, R):
    """The right-hand brackets of the 2D appendix equations (model E) as printed:
    dT_tr/dt = H - G T^3/2 P_tr (A19) and (1/2) dT_rot/dt = G T^3/2 P_rot (A22), with
    cot gamma0 = -c, tan^2 gamma0 = 1/c^2 (finite mu > 0 only)."""
    w = walton(r, rt_max, mu, q)
    if not (0.0 < w.c < math.inf):
        raise ValueError("A19/A22 as printed need 0 < mu < inf")
    e0, c, x2 = w.eta0, w.c, 1.0 + R / q
    f2 = 1.0 + x2 * c * c
    f3 = f2 ** 1.5
    tail = 1.0 - (1.0 + 1.5 * x2 * c * c) / f3
    P_tr = (w.A_r + e0 / 2.0 * (1.0 - e0 * x2) / f3 + e0 / 2.0 * x2 * c * c / f3
            - e0 * e0 / (c * c) * tail)
    P_rot = ((e0 * e0 * x2 / (2.0 * q) - (x2 - 1.0) * e0 / 2.0 * f2) / f3
             + e0 * e0 / (q * c * c) * tail)
    return P_tr, P_rot


def mean_energy_changes(model, r, rt_max, mu, q, Ttr, Trot, dim=2):
    """Mean translational and rotational energy change per collision (pair), flux-weighted over
    Gaussian velocities at T_tr and spins at T_rot: <dE_tr> = 4 (-A T_tr + B T_rot),
    <dE_rot> = 4 (B' T_tr - C T_rot) (the content of eq 13 / A17-A22 / A23-A24)."""
    R = Trot / Ttr
    c = coefficients(model, r, rt_max, mu, q, R) if dim == 2 else \
        coefficients_3d(model, r, rt_max, mu, q, R)
    return 4.0 * (-c.A * Ttr + c.B * Trot), 4.0 * (c.Bprime * Ttr - c.C * Trot)


# --------------------------------------------------------------------------------------------
# dynamics
# --------------------------------------------------------------------------------------------
def time_scale_G(nu, a=0.5, m=1.0, dim=2):
    """G of eq 14 (2D, Henderson g2) or G3D (A24, Carnahan-Starling) for fraction nu."""
    return cooling.time_scale_G(nu, a, m, dim)


def _coeffs_at(model, r, rt_max, mu, q, R, dim):
    if dim == 2:
        return coefficients(model, r, rt_max, mu, q, R if model in ("C", "E") else None)
    return coefficients_3d(model, r, rt_max, mu, q, R if model == "E" else None)


def rhs(t, T, model, r, rt_max, mu, q, G, H_dr=0.0, dim=2):
    """Right-hand side of eq 13 (2D: dT_tr/dt = H_dr + G T_tr^1/2 (-A T_tr + B T_rot),
    dT_rot/dt = 2 G T_tr^1/2 (B' T_tr - C T_rot)) or of A23-A24 (3D, divided by 3/2), with the
    coefficients of `coefficients` / `coefficients_3d` evaluated at R = T_rot/T_tr."""
    Ttr, Trot = max(float(T[0]), 0.0), max(float(T[1]), 0.0)
    R = Trot / Ttr if Ttr > 0.0 else 0.0
    c = _coeffs_at(model.upper(), r, rt_max, mu, q, R, dim)
    s = G * math.sqrt(Ttr)
    if dim == 2:
        return np.array([H_dr + s * (-c.A * Ttr + c.B * Trot), 2.0 * s * (c.Bprime * Ttr - c.C * Trot)])
    return np.array([H_dr + s * (-c.A * Ttr + c.B * Trot), s * (c.Bprime * Ttr - c.C * Trot)]) / 1.5


def integrate(model, r, rt_max, mu, q, nu, a=0.5, m=1.0, H_dr=0.0, T0=(1.0, 0.0), times=None,
              dim=2, rtol=1e-10, atol=1e-14):
    """Integrate eq 13 (2D; or A23-A24 in 3D) from T0 = (T_tr, T_rot) with constant driving H_dr
    (= f_dr T_dr, eq 9) and G from eq 14 for area fraction nu (volume fraction in 3D).
    scipy solve_ivp (DOP853). Returns (times, T_tr, T_rot)."""
    times = np.asarray(times if times is not None else np.linspace(0.0, 100.0, 101), dtype=float)
    G = time_scale_G(nu, a, m, dim)
    scale = max(abs(T0[0]), abs(T0[1]), 1e-300)
    sol = solve_ivp(rhs, (times[0], times[-1]), np.array(T0, dtype=float), method="DOP853",
                    t_eval=times, rtol=rtol, atol=atol * scale,
                    args=(model, r, rt_max, mu, q, G, H_dr, dim))
    if not sol.success:
        raise RuntimeError(sol.message)
    return sol.t, sol.y[0], sol.y[1]


# --------------------------------------------------------------------------------------------
# steady state of the randomly driven gas
# --------------------------------------------------------------------------------------------
def R_model_A(r, rt_max, q):
    """Eq 39: R_stat = q eta0/(q - eta0); q = 2/5 gives 2(1 + rt_max)/(9 - 5 rt_max)."""
    e0 = eta(rt_max, q)
    return q * e0 / (q - e0)


def I_model_A(r, rt_max, q):
    """Eq 40 with correction 2: I = A_r + eta0(1 - eta0)/2 - eta0^3/(2(q - eta0))."""
    e0 = eta(rt_max, q)
    return (1 - r * r) / 4 + e0 * (1 - e0) / 2 - e0 ** 3 / (2 * (q - e0))


def _steady_R_root(model, w, check_unique=True, ngrid=400):
    """Root in R of B'(R) - C(R) R = 0 (dT_rot/dt = 0) for models C and E.

    Bracket [0, R_A], R_A = q eta0/(q - eta0) (model A, eq 39):
      * at R = 0, B' - C R = B'(0) > 0 (mu > 0, eta0 > 0);
      * model E: B' - C R = eta0 x^2/(2 f~) [2 eta0/(q (1 + f~)) - R/(q + R)] (compact form of
        eqs 33-34). The bracket is strictly decreasing in R (f~ grows with R), so the root is
        unique; at R = R_A it is 2 eta0/(q(1+f~)) - eta0/q < 0 since f~ > 1 for c > 0.
      * model C: B' - C R has the sign of eta2(R) - q R/(q + R); eta2 = eta0 asinh(xc)/(xc) is
        strictly decreasing in R and < eta0 for c > 0, and q R_A/(q + R_A) = eta0, so the root is
        unique and < R_A.
    mu = inf (c = 0) returns R_A. When F(R_A) = O(c^2) rounds to >= 0 (mu >~ 1e7) the upper end
    is widened by a few ulp-scale steps (F < 0 for all R > R_A).
    Uniqueness is also checked numerically: at most one sign change of B' - C R (values at the
    rounding level dropped) on a grid of 2*`ngrid` points (linear and logarithmic) over the
    bracket; RuntimeError otherwise."""
    R_A = w.q * w.eta0 / (w.q - w.eta0)
    if w.c == 0.0:      # mu = inf: model A, the root is R_A itself
        return R_A

    def F(R):
        c = coefficients(model, w.r, w.rt_max, w.mu, w.q, R)
        return c.Bprime - c.C * R

    f0 = F(0.0)
    # at very large mu, F(R_A) = O(c^2) may round to >= 0: widen the bracket minimally (F < 0 for
    # all R > R_A, see above)
    R_hi = R_A
    for _ in range(40):
        f1 = F(R_hi)
        if f1 < 0.0:
            break
        R_hi *= 1.0 + 1e-12 * 4 ** _
    if not (f0 > 0.0 and f1 < 0.0):
        raise RuntimeError(f"model {model}: bracket [0, R_A] does not change sign "
                           f"(F(0) = {f0}, F(R_A) = {f1})")
    R = brentq(F, 0.0, R_hi, xtol=1e-15 * R_hi, rtol=4 * np.finfo(float).eps, maxiter=500)
    if check_unique:
        grid = np.unique(np.concatenate([np.linspace(0.0, R_hi, ngrid),
                                         R_hi * np.logspace(-12, 0, ngrid)]))
        vals = np.array([F(g) for g in grid])
        # values at the rounding level of F (relative to F(0)) carry no sign
        sgn = np.sign(vals[np.abs(vals) > 1e-12 * f0])
        changes = int(np.count_nonzero(sgn[1:] != sgn[:-1]))
        if changes > 1:
            raise RuntimeError(f"model {model}: {changes} sign changes of dT_rot/dt on [0, R_A]")
    return R


def steady_state_R_I(model, r, rt_max, mu, q, check_unique=True):
    """(R_stat, I) of the randomly driven steady state (eqs 37-38): R_stat from dT_rot/dt = 0
    and I = A - B R_stat, so T_tr^stat = (H_dr/(G I))^2/3.
    A, B, D: R_stat = B'/C (eq 38; eq 39 for A, eq 40 with correction 2 for I).
    C, E: root of B'(R) - C(R) R = 0 on [0, R_A] by brentq (see _steady_R_root).
    Smooth particles (mu = 0 or rt_max = -1) have no spin coupling (T_rot conserved); R_stat = 0
    is returned (the state reached from T_rot = 0)."""
    model = model.upper()
    w = walton(r, rt_max, mu, q)
    if w.smooth:
        return 0.0, w.A_r
    if model in ("A", "B", "D"):
        c = coefficients(model, r, rt_max, mu, q)
        R = c.Bprime / c.C
    else:
        R = _steady_R_root(model, w, check_unique)
        c = coefficients(model, r, rt_max, mu, q, R)
    return R, c.A - c.B * R


def steady_state(model, r, rt_max, mu, q, check_unique=True):
    """(R_stat, T_tr^stat / T_tr^stat(mu = 0)) of the randomly driven gas (H_dr constant,
    eqs 37-42). T_tr^stat = (H_dr/(G I))^2/3 (eq 37) and for mu = 0 I = A_r, so the ratio is
    (A_r / I)^2/3 (inf for r = 1, where smooth particles heat up without bound).
    A: eqs 39-40 (correction 2); B: eq 39-40 with eta0 -> eta1; D: R = B'_D/C_D (eqs 30-31,
    correction 3); C and E: brentq root on [0, R_A] with a uniqueness check."""
    R, I = steady_state_R_I(model, r, rt_max, mu, q, check_unique)
    A_r = (1.0 - r * r) / 4.0
    if A_r == 0.0:
        return R, math.inf if I > 0 else 1.0
    return R, (A_r / I) ** (2.0 / 3.0)


def steady_state_temperatures(model, r, rt_max, mu, q, nu, a=0.5, m=1.0, H_dr=1.0):
    """(T_tr^stat, T_rot^stat) = ((H_dr/(G I))^2/3, R_stat T_tr^stat), eq 37."""
    R, I = steady_state_R_I(model, r, rt_max, mu, q)
    T = (H_dr / (time_scale_G(nu, a, m, 2) * I)) ** (2.0 / 3.0)
    return T, R * T


# --------------------------------------------------------------------------------------------
# relaxation to the steady state
# --------------------------------------------------------------------------------------------
def _sorted_eigs(ev):
    ev = np.asarray(ev)
    ev = ev[np.argsort(np.abs(ev.real))]        # slow first
    if np.all(np.abs(ev.imag) <= 1e-12 * np.max(np.abs(ev))):
        ev = ev.real
    return ev


def linearized_matrix(model, r, rt_max, mu, q):
    """Eq 43 with correction 4, in units of G (T_tr^stat)^1/2, for d/dt (dTtr, dTrot) where
    T_tr = T_tr^stat (1 + dTtr), T_rot = T_rot^stat (1 + dTrot):
        [[-(3/2 A - B B'/(2C)),  B B'/C],
         [2 C,                   -2 C  ]]
    valid for models with R-independent coefficients (A, B, D). B B'/C is evaluated as B R_stat
    so that smooth particles (C = 0) give the rates -3A/2 and 0."""
    model = model.upper()
    if model not in ("A", "B", "D"):
        raise ValueError("eq 43 holds for R-independent coefficients (models A, B, D)")
    c = coefficients(model, r, rt_max, mu, q)
    R = c.Bprime / c.C if c.C > 0 else 0.0
    BR = c.B * R
    return np.array([[-(1.5 * c.A - 0.5 * BR), BR], [2.0 * c.C, -2.0 * c.C]])


def jacobian(model, r, rt_max, mu, q, G=1.0, H_dr=1.0, rel_step=1e-5):
    """Numerical Jacobian (central differences) of the 2D ODE (eq 13, with R-dependent
    coefficients for C and E) at the steady state for given G and H_dr. Returns (J, T_tr^stat)."""
    R, I = steady_state_R_I(model, r, rt_max, mu, q)
    Ts = (H_dr / (G * I)) ** (2.0 / 3.0)
    T = np.array([Ts, R * Ts])
    J = np.zeros((2, 2))
    for j in range(2):
        h = rel_step * Ts
        dp, dm = T.copy(), T.copy()
        dp[j] += h
        dm[j] -= h
        J[:, j] = (rhs(0.0, dp, model, r, rt_max, mu, q, G, H_dr)
                   - rhs(0.0, dm, model, r, rt_max, mu, q, G, H_dr)) / (2.0 * h)
    return J, Ts


def jacobian_eigenvalues(model, r, rt_max, mu, q, rel_step=1e-5):
    """Eigenvalues of the numerical Jacobian of eq 13 at the steady state, in units of
    G (T_tr^stat)^1/2 (slow one first)."""
    J, Ts = jacobian(model, r, rt_max, mu, q, 1.0, 1.0, rel_step)
    return _sorted_eigs(np.linalg.eigvals(J) / math.sqrt(Ts))


def relaxation_rates(model, r, rt_max, mu, q, nu=None, a=0.5, m=1.0, H_dr=None):
    """The two linear relaxation rates about the driven steady state (eigenvalues, negative when
    stable; slow one first; complex conjugate pair when the relaxation oscillates).
    A, B, D: eigenvalues of eq 43 (correction 4: prefactor G (T_tr^stat)^1/2).
    C, E: eigenvalues of the numerical Jacobian of eq 13 (coefficients depend on R).
    Units: G (T_tr^stat)^1/2, as in eq 43 (independent of H_dr and nu). If nu and H_dr are given,
    the rates are converted to 1/time with G of eq 14 and T_tr^stat of eq 37.
    Sign: the paper's (positive) relaxation rates lambda_1,2 are minus these eigenvalues. For
    eq 43 the discriminant (a - d)^2 + 4 (B R_stat)(2C) is >= 0, so the eigenvalues are always
    real; the two rates come closest (an avoided crossing, not equality) near rt_max = -0.84 for
    r = 0.95, q = 2/5 (Fig. 10)."""
    model = model.upper()
    if model in ("A", "B", "D"):
        ev = _sorted_eigs(np.linalg.eigvals(linearized_matrix(model, r, rt_max, mu, q)))
    else:
        ev = jacobian_eigenvalues(model, r, rt_max, mu, q)
    if nu is None or H_dr is None:
        return ev
    G = time_scale_G(nu, a, m, 2)
    _, I = steady_state_R_I(model, r, rt_max, mu, q)
    Ts = (H_dr / (G * I)) ** (2.0 / 3.0)
    return ev * G * math.sqrt(Ts)


# --------------------------------------------------------------------------------------------
# homogeneous cooling (H_dr = 0)
# --------------------------------------------------------------------------------------------
def cooling_dR(model, r, rt_max, mu, q, R, dim=2):
    """dR/dt up to the positive factor G T_tr^1/2 (x 2/3 in 3D) for H_dr = 0:
    2D: 2 (B' - C R) - R (-A + B R);  3D (A23-A24): (B' - C R) - R (-A + B R)."""
    c = _coeffs_at(model.upper(), r, rt_max, mu, q, R, dim)
    k = 2.0 if dim == 2 else 1.0
    return k * (c.Bprime - c.C * R) - R * (-c.A + c.B * R)


def cooling_asymptotic_R(model, r, rt_max, mu, q, dim=2, R0=0.0, R_max=1e12, ngrid=2000):
    """Asymptotic R = T_rot/T_tr of the homogeneous cooling state reached from R(0) = R0: the
    first zero of dR/dt (cooling_dR) in the direction in which R moves from R0 (A23-A24 with
    correction 5 in 3D; eq 13 in 2D). Returns math.inf when dR/dt > 0 on all of [R0, R_max]
    (at small mu the spins decouple and the rotational energy survives: R grows without
    bound). For model A this is granfric.cooling.asymptotic_R. Located by a logarithmic scan
    (ngrid points) and refined with brentq."""
    model = model.upper()
    if walton(r, rt_max, mu, q).smooth:
        return 0.0 if R0 == 0.0 else math.inf if r < 1.0 else R0
    h = lambda R: cooling_dR(model, r, rt_max, mu, q, R, dim)
    h0 = h(R0)
    if h0 == 0.0:
        return R0
    if h0 > 0.0:
        lo = max(R0, 1e-12)
        grid = np.concatenate([[R0], np.logspace(math.log10(lo), math.log10(R_max), ngrid)[1:]])
    else:
        grid = np.concatenate([[R0], R0 * (1.0 - np.logspace(-12, 0, ngrid))])
    prev, fprev = grid[0], h0
    for g in grid[1:]:
        fg = h(g)
        if fg == 0.0:
            return float(g)
        if (fg > 0.0) != (fprev > 0.0):
            a_, b_ = sorted((prev, g))
            return brentq(h, a_, b_, xtol=1e-15 * max(b_, 1e-300), rtol=4 * np.finfo(float).eps)
        prev, fprev = g, fg
    return math.inf
