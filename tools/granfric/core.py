# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""ctypes access to the GRANFRIC C++ physics core (libgranfric_capi.so): the very collision law
the LAMMPS styles use, so Monte Carlo averages and tables come from one code path."""
import ctypes
import math
import os
from dataclasses import dataclass

import numpy as np

_lib = None
_laws = None
_models = None


def build_dir():
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    return os.environ.get("GRANFRIC_BUILD", os.path.join(root, "build"))


def lib():
    """Load libgranfric_capi.so from $GRANFRIC_BUILD (default <repo>/build)."""
    global _lib
    if _lib is None:
        path = os.path.join(build_dir(), "libgranfric_capi.so")
        if not os.path.exists(path):
            raise FileNotFoundError(f"{path} not found: build GRANFRIC first (bash tools/test.sh "
                                    "or cmake --build build), or set GRANFRIC_BUILD")
        _lib = ctypes.CDLL(path)
        d = ctypes.POINTER(ctypes.c_double)
        _lib.granfric_collide.argtypes = [ctypes.c_int, d, d, d, d, d]
        _lib.granfric_collide.restype = ctypes.c_int
        for name in ("granfric_law_name", "granfric_law_joint"):
            getattr(_lib, name).restype = ctypes.c_char_p
        _lib.granfric_law_coeff.restype = ctypes.c_char_p
        _lib.granfric_law_coeff.argtypes = [ctypes.c_int, ctypes.c_int,
                                            ctypes.POINTER(ctypes.c_char_p)]
        _lib.granfric_law_check.argtypes = [ctypes.c_int, d]
        _lib.granfric_collide_model.argtypes = [ctypes.c_int, d, ctypes.c_int, d, d, d, d, d]
        _lib.granfric_collide_model.restype = ctypes.c_int
        _lib.granfric_law_elastic_normal.restype = ctypes.c_double
        _lib.granfric_restitution_name.restype = ctypes.c_char_p
        _lib.granfric_restitution_coeff.restype = ctypes.c_char_p
        _lib.granfric_restitution_coeff.argtypes = [ctypes.c_int, ctypes.c_int,
                                                    ctypes.POINTER(ctypes.c_char_p)]
        _lib.granfric_restitution_check.argtypes = [ctypes.c_int, d]
        _lib.granfric_viscoelastic_restitution.argtypes = [ctypes.c_double]
        _lib.granfric_viscoelastic_restitution.restype = ctypes.c_double
    return _lib


def laws():
    """The core's table of collision laws: {name: (index, [(coefficient, range in words), ...])}."""
    global _laws
    if _laws is None:
        L, _laws = lib(), {}
        for k in range(L.granfric_law_count()):
            coeffs = []
            for m in range(L.granfric_law_ncoeff(k)):
                rng = ctypes.c_char_p()
                name = L.granfric_law_coeff(k, m, ctypes.byref(rng))
                coeffs.append((name.decode(), rng.value.decode()))
            _laws[L.granfric_law_name(k).decode()] = (k, coeffs)
    return _laws


def restitution_models():
    """The core's table of normal restitution models: {name: (index, [(coefficient, range), ...],
    whether the law's normal coefficient is NULL with it)}."""
    global _models
    if _models is None:
        L, _models = lib(), {}
        for k in range(L.granfric_restitution_count()):
            coeffs = []
            for m in range(L.granfric_restitution_ncoeff(k)):
                rng = ctypes.c_char_p()
                name = L.granfric_restitution_coeff(k, m, ctypes.byref(rng))
                coeffs.append((name.decode(), rng.value.decode()))
            _models[L.granfric_restitution_name(k).decode()] = (k, coeffs,
                                                              bool(L.granfric_restitution_normal_null(k)))
    return _models


def viscoelastic_restitution(delta):
    """E(delta): the normal restitution of viscoelastic spheres (core/viscoelastic.h), with
    delta = A alpha^(2/5) v^(1/5) (E = 1 - 1.15344 delta + ... for small delta)."""
    return lib().granfric_viscoelastic_restitution(float(delta))


def _law_and_model(law, coeffs, restitution):
    """(law index, coefficients, model index, model coefficients) for core calls: restitution is
    None (the law's constant restitution) or (model name, [values]) as pair_coeff takes them
    after the law's coefficients; with a model whose law coefficient is NULL, coeffs[0] may be
    None."""
    if restitution is None:
        k, c = law_index(law, coeffs)
        return k, c, -1, np.zeros(1)
    name, values = restitution
    table = restitution_models()
    if name not in table:
        raise ValueError(f"unknown restitution model {name!r} (known: {', '.join(table)})")
    mk, names, null = table[name]
    coeffs = list(coeffs)
    if null:
        if coeffs and coeffs[0] is not None:
            raise ValueError(f"{name}: give the law's normal coefficient as None (the model sets it)")
        coeffs[0] = lib().granfric_law_elastic_normal(laws()[law][0]) if law in laws() else 0.0
    k, c = law_index(law, coeffs)
    mc = np.array(values, dtype=float).ravel()
    if mc.size != len(names):
        raise ValueError(f"{name} takes {len(names)} values ({' '.join(n for n, _ in names)}), not {mc.size}")
    bad = lib().granfric_restitution_check(mk, mc.ctypes.data_as(ctypes.POINTER(ctypes.c_double)))
    if bad >= 0:
        raise ValueError(f"{name}: {names[bad][0]} = {mc[bad]} is out of range ({names[bad][1]})")
    return k, c, mk, mc


def law_index(law, coeffs):
    """The table index of law `law` (a name), with coeffs as a float64 array checked against the
    law's ranges; ValueError naming what is wrong."""
    table = laws()
    if law not in table:
        raise ValueError(f"unknown collision law {law!r} (known: {', '.join(table)})")
    k, names = table[law]
    c = np.array(coeffs, dtype=float).ravel()
    if c.size != len(names):
        raise ValueError(f"law {law} takes {len(names)} coefficients "
                         f"({' '.join(n for n, _ in names)}), not {c.size}")
    bad = lib().granfric_law_check(k, c.ctypes.data_as(ctypes.POINTER(ctypes.c_double)))
    if 0 <= bad < len(names):
        raise ValueError(f"law {law}: {names[bad][0]} = {c[bad]} is out of range ({names[bad][1]})")
    if bad == len(names):
        raise ValueError(f"law {law}: {lib().granfric_law_joint(k).decode()}")
    return k, c


@dataclass
class Body:
    v: tuple = (0.0, 0.0, 0.0)
    w: tuple = (0.0, 0.0, 0.0)
    m: float = 1.0
    a: float = 0.5
    q: float = 0.4

    def array(self):
        return np.array([*self.v, *self.w, self.m, self.a, self.q], dtype=float)

    @staticmethod
    def wall(v=(0.0, 0.0, 0.0)):
        return Body(v=v, m=math.inf, a=0.0, q=1.0)


@dataclass
class Collision:
    v1: np.ndarray
    w1: np.ndarray
    v2: np.ndarray
    w2: np.ndarray
    dE: float
    gn: float
    gt: float
    cos_gamma: float
    rt: float
    sliding: bool
    energy_created: bool


def collide(law, coeffs, b1, b2, n, restitution=None):
    """Apply law ('rough' r beta | 'walton' r mu rtmax | 'jz' qn qt kappa_s kappa_d) to bodies
    b1, b2 touching along unit normal n (from 2 to 1); restitution: None, or a normal
    restitution model as pair_coeff takes it, e.g. ('viscoelastic', [vref]) or
    ('viscoelastic/material', [Y, nu, A]) (then coeffs[0] = None). Returns a Collision."""
    k, c, mk, mc = _law_and_model(law, coeffs, restitution)
    a1, a2, nn = b1.array(), b2.array(), np.array(n, dtype=float)
    out = np.zeros(19)
    p = ctypes.POINTER(ctypes.c_double)
    rc = lib().granfric_collide_model(k, c.ctypes.data_as(p), mk, mc.ctypes.data_as(p), a1.ctypes.data_as(p),
                                      a2.ctypes.data_as(p), nn.ctypes.data_as(p), out.ctypes.data_as(p))
    if rc != 0:
        raise ValueError(f"invalid {law} coefficients {coeffs}")
    return Collision(out[0:3], out[3:6], out[6:9], out[9:12], out[12], out[13], out[14],
                     out[15], out[16], bool(out[17]), bool(out[18]))


def mean_energy_changes(law, coeffs, q, dim, Ttr, Trot, n=20000, seed=1, restitution=None):
    """Monte Carlo, in the C++ core, of the mean translational and rotational energy changes per
    collision of equal particles (m = 1): Gaussian velocities at Ttr, spins with I<w^2> = Trot,
    collisions weighted by the normal relative speed; restitution as in collide. Returns a dict
    with tr, tr_se, rot, rot_se, total, total_se, sliding."""
    k, c, mk, mc = _law_and_model(law, coeffs, restitution)
    out = np.zeros(7)
    f = lib().granfric_mean_energy_changes_model
    d = ctypes.POINTER(ctypes.c_double)
    f.argtypes = [ctypes.c_int, d, ctypes.c_int, d, ctypes.c_double, ctypes.c_int, ctypes.c_double,
                  ctypes.c_double, ctypes.c_long, ctypes.c_ulong, d]
    f.restype = ctypes.c_int
    if f(k, c.ctypes.data_as(d), mk, mc.ctypes.data_as(d), q, dim, Ttr, Trot, n, seed,
         out.ctypes.data_as(d)) != 0:
        raise ValueError(f"invalid {law} coefficients {coeffs}")
    keys = ("tr", "tr_se", "rot", "rot_se", "total", "total_se", "sliding")
    return dict(zip(keys, (float(x) for x in out)))


def collide_batch(law, coeffs, v1, w1, v2, w2, n, m=1.0, a=0.5, q=0.4, want_dE=False, restitution=None):
    """Apply law (as in collide) in place to many contacts of equal particles (mass m, radius a,
    shape factor q): v1, w1, v2, w2 and the unit normals n (from 2 to 1) are (k, 3) float64
    C-contiguous arrays; the map is applied as given (select approaching pairs first). One C++
    call for all k contacts; restitution as in collide. Returns the energy changes (k,) if
    want_dE, else None."""
    arrays = (v1, w1, v2, w2, n)
    k = len(v1)
    for x in arrays:
        if not (isinstance(x, np.ndarray) and x.dtype == np.float64 and x.shape == (k, 3)
                and x.flags.c_contiguous):
            raise ValueError("collide_batch needs (k, 3) C-contiguous float64 arrays")
    for x in arrays[:4]:
        if not x.flags.writeable:
            raise ValueError("collide_batch updates v1, w1, v2, w2 in place: they must be writeable")
    law_k, c, mk, mc = _law_and_model(law, coeffs, restitution)
    dE = np.zeros(k) if want_dE else None
    d = ctypes.POINTER(ctypes.c_double)
    f = lib().granfric_collide_batch_model
    f.argtypes = [ctypes.c_int, d, ctypes.c_int, d, ctypes.c_long, ctypes.c_double, ctypes.c_double,
                  ctypes.c_double, d, d, d, d, d, d]
    f.restype = ctypes.c_int
    ptr = lambda x: x.ctypes.data_as(d) if x is not None else None
    rc = f(law_k, ptr(c), mk, ptr(mc), k, m, a, q, *(ptr(x) for x in arrays), ptr(dE))
    if rc == -3:
        raise ValueError(f"invalid body m={m} a={a} q={q}")
    if rc != 0:
        raise ValueError(f"invalid {law} coefficients {coeffs}")
    return dE


def kick(k, tags, m, a, v, w, fdr=1.0, vdr=1.0, seed=1, momentum=True, spin=0.0, q=0.4, dim=3):
    """Kick k of the core's random driving (core/kicks.h, the kicks of fix hardsphere/kick with
    the same f_dr, v_dr, seed, momentum and spin) applied in place to velocities v and spins w
    ((n, 3) C-contiguous float64) of particles with IDs tags, masses m and radii a (n each)."""
    n = len(tags)
    t = np.ascontiguousarray(tags, dtype=np.int64)
    mm = np.ascontiguousarray(m, dtype=float)
    aa = np.ascontiguousarray(a, dtype=float)
    for x in (v, w):
        if not (isinstance(x, np.ndarray) and x.dtype == np.float64 and x.shape == (n, 3)
                and x.flags.c_contiguous and x.flags.writeable):
            raise ValueError("kick needs writeable (n, 3) C-contiguous float64 v and w")
    if mm.shape != (n,) or aa.shape != (n,):
        raise ValueError("kick needs n masses and n radii")
    d = ctypes.POINTER(ctypes.c_double)
    f = lib().granfric_kick
    f.argtypes = [ctypes.c_double, ctypes.c_double, ctypes.c_double, ctypes.c_long, ctypes.c_int,
                  ctypes.c_int, ctypes.c_long, ctypes.c_long, ctypes.POINTER(ctypes.c_long), d,
                  d, ctypes.c_double, d, d]
    f.restype = ctypes.c_int
    if f(fdr, vdr, spin, seed, int(momentum), dim, k, n,
         t.ctypes.data_as(ctypes.POINTER(ctypes.c_long)), mm.ctypes.data_as(d),
         aa.ctypes.data_as(d), q, v.ctypes.data_as(d), w.ctypes.data_as(d)) != 0:
        raise ValueError(f"invalid kick parameters fdr={fdr} vdr={vdr} spin={spin} seed={seed} "
                         f"q={q} dim={dim}")
