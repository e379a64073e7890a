# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Plane Couette flow (examples/couette): the event-driven runs of examples/couette/in.couette2d
(discs) and in.couette3d (spheres) between two thermal walls sliding at -U and +U, their momentum
books, and their steady profiles against Navier-Stokes hydrodynamics with velocity slip and
temperature jump at the walls.

    PYTHONPATH=tools /usr/bin/python3 -m granfric.couette [--quick|--full] [--out DIR] [--reuse]
        [--figure PATH]

Runs both examples (logs and side files in DIR/logs; --reuse takes the ones already there),
writes DIR/report.md and the figure (default examples/couette/couette.png).

The momentum books: the x force on each wall (block averages of fix hardsphere/wall's element 3)
against P_xy (compute pressure). The collision virial gives a wall collision's impulse the arm
from the contact point to the centre, which is normal to the wall, so LAMMPS's symmetric
xy = sum r_x dP_y leaves the walls out; the virial theorem for sum m y v_x then gives
P_xy L_y = (F_hi / A) (L_y - sigma): the kinetic and pair-collision stress averaged over the box
is the wall's force per area times the fraction of the height the centres can reach.

The theory: steady Navier-Stokes equations across the channel of the centres, |y| <= h =
(L_y - sigma)/2, with the shear stress S = eta du/dy constant and
d/dy(kappa dT/dy) + S du/dy = 0, the pressure uniform, the number of particles per wall area
given, and at each wall the slip u_wall - u = zeta_u lambda du/dn and the jump
T - T_wall = zeta_T lambda dT/dn (n the normal into the gas, lambda the local mean free path).
Transport coefficients: Chapman-Enskog for hard spheres with the higher-Sonine factors 1.016034
(viscosity) and 1.025218 (conductivity), Chapman & Cowling (1970) ch. 16; for hard discs the
first Sonine values with the factors 1.022 and 1.029 of Gass (1971). "boltzmann": the dilute
gas; "enskog": the standard Enskog theory at the local density (Carnahan-Starling or Henderson
pair correlation at contact), as in Chapman & Cowling ch. 16 and, for any dimension, Garzo &
Dufty, Phys. Rev. E 59, 5895 (1999) in the elastic limit. Slip and jump coefficients for diffuse
(thermal) walls: hard spheres, from the linearized Boltzmann equation, zeta_u = 1.2540 sqrt(pi)/2
= 1.1113 and zeta_T = 2.4001 sqrt(pi)/2 = 2.1269 in units of lambda = 1/(sqrt(2) pi n sigma^2)
(Ohwada, Sone & Aoki 1989; Sone, Ohwada & Aoki 1989; Sone, Molecular Gas Dynamics, 2007). For
hard discs no such solution is used here: Maxwell's slip length (eta/p) sqrt(pi T/(2m)) and
Smoluchowski's jump length kappa/((d+1) n sqrt(T/(2 pi m))) (both derived for any dimension)
are multiplied by the ratios of the exact hard-sphere values to the same estimates in 3D
(1.114 and 1.127), which gives zeta_u = 1.139 and zeta_T = 3.093 in units of
lambda = 1/(2 sqrt(2) n sigma).

In the dilute gas kappa/eta is a constant c, and the equations give T + u^2/(2c) = const across
the channel whatever the boundary conditions (in units m = k_B = 1): the temperature is a
parabola in the velocity. The measured profiles are fitted in the bulk (more than `kn_skip` mean
free paths from the walls) by an odd cubic u(y) and an even quartic T(y), extrapolated to the
walls for the measured slip and jump lengths.
"""
import os

import numpy as np

from . import cli, cooling, lammpslog, lmp

EXAMPLES = {2: os.path.join(lmp.ROOT, "examples", "couette", "in.couette2d"),
            3: os.path.join(lmp.ROOT, "examples", "couette", "in.couette3d")}
FIGURE = os.path.join(lmp.ROOT, "examples", "couette", "couette.png")
SIGMA = 1.0                      # the examples' diameter and mass

# Chapman-Enskog: first Sonine eta0, kappa0 (times sqrt(T)) and the higher-Sonine factors
FIRST_SONINE = {2: (1.0 / (2.0 * np.sqrt(np.pi)), 2.0 / np.sqrt(np.pi)),
                3: (5.0 / (16.0 * np.sqrt(np.pi)), 75.0 / (64.0 * np.sqrt(np.pi)))}
SONINE_FACTOR = {2: (1.022, 1.029), 3: (1.016034, 1.025218)}
# hard spheres, diffuse walls (linearized Boltzmann equation), in units of lambda
HS_SLIP, HS_JUMP = 1.2540 * np.sqrt(np.pi) / 2.0, 2.4001 * np.sqrt(np.pi) / 2.0


def mean_free_path(n, dim):
    """Dilute mean free path of a Maxwellian gas of hard discs (2D) or spheres (3D) of unit
    diameter: the mean speed over the Boltzmann collision frequency."""
    return 1.0 / (2.0 * np.sqrt(2.0) * n) if dim == 2 else 1.0 / (np.sqrt(2.0) * np.pi * n)


def fraction(n, dim):
    return n * np.pi / 4.0 if dim == 2 else n * np.pi / 6.0


def compressibility(n, dim, model="enskog"):
    """p / (n T): 1 + 2^(d-1) phi chi (Enskog) or 1 (Boltzmann)."""
    if model == "boltzmann":
        return np.ones_like(np.asarray(n, dtype=float))
    phi = fraction(n, dim)
    return 1.0 + 2.0 ** (dim - 1) * phi * cooling.pair_correlation(phi, dim)


def density(p, T, dim, model="enskog"):
    """Number density at pressure p and temperature T (Newton on the equation of state)."""
    n = np.asarray(p / T, dtype=float)
    if model == "boltzmann":
        return n
    for _ in range(50):
        f = n * compressibility(n, dim) - p / T
        h = 1e-7 * n
        df = ((n + h) * compressibility(n + h, dim) - (n - h) * compressibility(n - h, dim)) / (2 * h)
        step = f / df
        n = n - step
        if np.all(np.abs(step) < 1e-14 * n):
            break
    return n


def transport(T, n, dim, model="enskog"):
    """Shear viscosity and heat conductivity (m = k_B = sigma = 1)."""
    e0, k0 = FIRST_SONINE[dim]
    ce, ck = SONINE_FACTOR[dim]
    rt = np.sqrt(T)
    if model == "boltzmann":
        return ce * e0 * rt, ck * k0 * rt
    phi = fraction(n, dim)
    chi = cooling.pair_correlation(phi, dim)
    d = dim
    # kinetic parts (with the Sonine factors) and collisional transfer (Garzo & Dufty 1999,
    # elastic limit; the same as Chapman & Cowling's 1/chi + 0.8 b n + 0.7614 (b n)^2 chi in 3D)
    eta = e0 * rt * (ce / chi * (1 + 2.0 ** d / (d + 2) * phi * chi) ** 2
                     + d / (d + 2.0) * 2.0 ** (2 * d + 2) / (np.pi * (d + 2)) * phi ** 2 * chi)
    kap = k0 * rt * (ck / chi * (1 + 3.0 * 2.0 ** (d - 1) / (d + 2) * phi * chi) ** 2
                     + 2.0 ** (2 * d + 2) * (d - 1) / ((d + 2) ** 2 * np.pi) * phi ** 2 * chi)
    return eta, kap


def conductivity_ratio(dim, model="boltzmann", n=0.0):
    """c = kappa/eta (the constant of T + u^2/(2c) in the dilute gas)."""
    e, k = transport(1.0, n, dim, model)
    return k / e


def slip_coefficients(dim):
    """(zeta_u, zeta_T) for diffuse walls in units of the dilute mean free path."""
    if dim == 3:
        return HS_SLIP, HS_JUMP
    ratio_u, ratio_T = HS_SLIP / maxwell_slip(3), HS_JUMP / smoluchowski_jump(3)
    return ratio_u * maxwell_slip(2), ratio_T * smoluchowski_jump(2)


def maxwell_slip(dim):
    """Maxwell's slip length (eta/p) sqrt(pi T/2) over the dilute mean free path."""
    n = 1.0
    eta, _ = transport(1.0, n, dim, "boltzmann")
    return eta / n * np.sqrt(np.pi / 2.0) / mean_free_path(n, dim)


def smoluchowski_jump(dim):
    """Smoluchowski's jump length kappa / ((d+1) n sqrt(T/(2 pi))) over the mean free path."""
    n = 1.0
    _, kap = transport(1.0, n, dim, "boltzmann")
    return kap / ((dim + 1) * n * np.sqrt(1.0 / (2.0 * np.pi))) / mean_free_path(n, dim)


def solve(dim, U, Tw, Ly, per_area, model="enskog", zeta=None, points=401):
    """Navier-Stokes across the centres' channel |y| <= h = (Ly - sigma)/2 with slip and jump
    at both walls (solve_bvp). per_area: particles per unit wall area (N / L_x, N / (L_x L_z)).
    Returns y, u, T, n and the shear stress S = eta du/dy, the pressure p, h."""
    from scipy.integrate import solve_bvp
    zu, zt = slip_coefficients(dim) if zeta is None else zeta
    h = 0.5 * (Ly - SIGMA)

    def local(T, p):
        n = density(p, T, dim, model)
        eta, kap = transport(T, n, dim, model)
        lam = mean_free_path(n, dim)
        if model == "enskog":
            lam = lam / cooling.pair_correlation(fraction(n, dim), dim)
        return n, eta, kap, lam

    def fun(y, Y, q):
        u, T, Q, M = Y
        S, p = q
        n, eta, kap, _ = local(T, p)
        return np.vstack([S / eta, Q / kap, -S * S / eta, n])

    def bc(a, b, q):
        S, p = q
        na, ea, ka, la = local(a[1], p)
        nb, eb, kb, lb = local(b[1], p)
        return np.array([a[3], b[3] - per_area,
                         a[0] - (-U + zu * la * S / ea), b[0] - (U - zu * lb * S / eb),
                         a[1] - (Tw + zt * la * a[2] / ka), b[1] - (Tw - zt * lb * b[2] / kb)])

    y = np.linspace(-h, h, points)
    nbar = per_area / (2 * h)
    eta0, _ = transport(Tw, nbar, dim, model)
    Y = np.vstack([0.8 * U * y / h, Tw + 0 * y, 0 * y, nbar * (y + h)])
    sol = solve_bvp(fun, bc, y, Y, p=[eta0 * 0.8 * U / h, nbar * Tw], tol=1e-8, max_nodes=100000)
    if not sol.success:
        raise RuntimeError("Couette boundary-value problem: " + sol.message)
    S, p = sol.p
    u, T, Q, M = sol.sol(y)
    n = density(p, T, dim, model)
    return {"y": y, "u": u, "T": T, "n": n, "S": S, "p": p, "h": h,
            "slip": U - u[-1], "jump": T[-1] - Tw, "Tc": float(sol.sol(0.0)[1]), "zeta": (zu, zt)}


# ---- the runs' output ----------------------------------------------------------------------

def steady(log):
    """The example's closing line as a dict (Pxy, Flo, Fhi, Pyy, Elo, Ehi, Lx, Ly, Lz, N, coll,
    U, T, phi, dim)."""
    return lammpslog.steady_line(log)


def read_blocks(path):
    """The example's block file (fix ave/time): rows of step, P_xy, F_lo, F_hi, P_xy A, T, P_xx,
    P_yy."""
    rows = [l.split() for l in open(path) if l.strip() and not l.startswith("#")]
    a = np.array(rows, dtype=float)
    keys = ("step", "Pxy", "Flo", "Fhi", "PxyA", "T", "Pxx", "Pyy")
    return {k: a[:, i] for i, k in enumerate(keys)}


def read_chunks(path):
    """A fix ave/chunk file: (column names, array blocks x chunks x columns)."""
    names, blocks, cur = None, [], None
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                names = line[1:].split()
                continue
            w = line.split()
            if not w:
                continue
            if len(w) == 3:
                cur = []
                blocks.append(cur)
            else:
                cur.append([float(x) for x in w])
    return names, np.array(blocks, dtype=float)


def profiles(path, dim, Ly):
    """Per block and layer: y (from the channel's middle; the outer layers at the middle of the
    part the centres reach), density n, mean v_x, temperature T and its components."""
    names, a = read_chunks(path)
    col = {k: i for i, k in enumerate(names)}
    width = a[0, 1, col["Coord1"]] - a[0, 0, col["Coord1"]]
    y = a[0, :, col["Coord1"]] - 0.5 * Ly
    n = a[:, :, col["density/number"]].copy()
    # the outer layers' centres reach only width - sigma/2 of their width
    reach = width - 0.5 * SIGMA
    n[:, 0] *= width / reach
    n[:, -1] *= width / reach
    y = y.copy()
    y[0] = -0.5 * Ly + 0.5 * SIGMA + 0.5 * reach
    y[-1] = -y[0]
    u = a[:, :, col["vx"]]
    Tc = [a[:, :, col["v_vx2"]] - u ** 2, a[:, :, col["v_vy2"]]]
    if dim == 3:
        Tc.append(a[:, :, col["v_vz2"]])
    T = sum(Tc) / dim
    return {"y": y, "n": n, "u": u, "T": T, "Tcomp": Tc, "width": width}


def mean_err(x, axis=0):
    """Mean over the blocks and its standard error."""
    x = np.asarray(x, dtype=float)
    if x.shape[axis] < 2:
        return x.mean(axis=axis), np.full_like(x.mean(axis=axis), np.nan)
    return x.mean(axis=axis), x.std(axis=axis, ddof=1) / np.sqrt(x.shape[axis])


def books(blocks, s):
    """The momentum books from the block averages: each wall's force, P_xy A L_y / (L_y - sigma)
    (what the upper wall's force equals), the sum of the two forces, and their differences;
    values (mean, standard error over the blocks)."""
    area = s["Lx"] * s["Lz"]
    pa = blocks["Pxy"] * area * s["Ly"] / (s["Ly"] - SIGMA)
    out = {"F_lo": mean_err(blocks["Flo"]), "F_hi": mean_err(blocks["Fhi"]),
           "PxyA": mean_err(blocks["Pxy"] * area), "PxyA_corr": mean_err(pa),
           "F_lo+F_hi": mean_err(blocks["Flo"] + blocks["Fhi"]),
           "F_hi-PxyA_corr": mean_err(blocks["Fhi"] - pa),
           "-F_lo-PxyA_corr": mean_err(-blocks["Flo"] - pa),
           "Pyy": mean_err(blocks["Pyy"]), "T": mean_err(blocks["T"])}
    return out


def fit_bulk(prof, h, lam_w, U, Tw, kn_skip=3.0):
    """Odd cubic u(y) and even quartic T(y) fitted per block to the layers more than kn_skip
    wall mean free paths from the walls; extrapolated to the walls (|y| = h). Returns mean and
    standard error over blocks of the slip U - u(h), the slip length (U - u(h))/u'(h), the jump
    T(h) - Tw, the jump length (T(h) - Tw)/(-T'(h)) and the centre temperature T(0)."""
    y = prof["y"]
    sel = np.abs(y) < h - kn_skip * lam_w
    res = []
    for u, T in zip(prof["u"], prof["T"]):
        # symmetrise: u odd, T even
        uu = 0.5 * (u - u[::-1])
        TT = 0.5 * (T + T[::-1])
        cu = np.linalg.lstsq(np.vstack([y[sel], y[sel] ** 3]).T, uu[sel], rcond=None)[0]
        cT = np.linalg.lstsq(np.vstack([y[sel] ** 0, y[sel] ** 2, y[sel] ** 4]).T, TT[sel],
                             rcond=None)[0]
        uh, duh = cu[0] * h + cu[1] * h ** 3, cu[0] + 3 * cu[1] * h ** 2
        Th, dTh = cT[0] + cT[1] * h ** 2 + cT[2] * h ** 4, 2 * cT[1] * h + 4 * cT[2] * h ** 3
        res.append([U - uh, (U - uh) / duh, Th - Tw, (Th - Tw) / (-dTh), cT[0], cu[0]])
    m, e = mean_err(np.array(res))
    keys = ("slip", "slip_length", "jump", "jump_length", "Tc", "du0")
    return {k: (m[i], e[i]) for i, k in enumerate(keys)}


def sampled(theory, y):
    """A theory profile at the layers' positions, in the form of profiles() (one block)."""
    yy = np.clip(y, -theory["h"], theory["h"])
    return {"y": y, "u": np.interp(yy, theory["y"], theory["u"])[None, :],
            "T": np.interp(yy, theory["y"], theory["T"])[None, :]}


def fit_parabola(prof, h, lam_w, kn_skip=3.0):
    """c of T = T0 - u^2/(2c) fitted per block in the bulk; (mean, standard error)."""
    y = prof["y"]
    sel = np.abs(y) < h - kn_skip * lam_w
    cs = []
    for u, T in zip(prof["u"], prof["T"]):
        a = np.linalg.lstsq(np.vstack([u[sel] ** 0, u[sel] ** 2]).T, T[sel], rcond=None)[0]
        cs.append(-0.5 / a[1])
    return mean_err(cs)


def analyse(work, dim):
    """Everything measured and predicted for one example's run in work."""
    name = f"couette{dim}d"
    s = steady(os.path.join(work, f"log.{name}"))
    blocks = read_blocks(os.path.join(work, f"{name}.blocks"))
    prof = profiles(os.path.join(work, f"{name}.profile"), dim, s["Ly"])
    area = s["Lx"] * s["Lz"]
    per_area = s["N"] / area
    U, Tw = s["U"], s["T"]
    th = {m: solve(dim, U, Tw, s["Ly"], per_area, m) for m in ("boltzmann", "enskog")}
    h = th["enskog"]["h"]
    b = books(blocks, s)
    S = (-b["PxyA_corr"][0] / area, b["PxyA_corr"][1] / area)
    # the mean free path at the wall, from the measured pressure and the jump temperature
    nbar = per_area / (2 * h)
    lam_bar = mean_free_path(nbar, dim)
    fit0 = fit_bulk(prof, h, lam_bar, U, Tw)
    Tjump = fit0["jump"][0] + Tw
    n_w = density(b["Pyy"][0], Tjump, dim)
    lam_w = mean_free_path(n_w, dim)
    fit = fit_bulk(prof, h, lam_w, U, Tw)
    c = fit_parabola(prof, h, lam_w)
    # the theory's profiles sampled at the layers and fitted the same way
    tfit = {m: fit_bulk(sampled(t, prof["y"]), h, lam_w, U, Tw) for m, t in th.items()}
    mid = len(prof["y"]) // 2
    anis = [tc.mean(axis=0)[mid - 1:mid + 1].mean() for tc in prof["Tcomp"]]
    return {"tfit": tfit, "anisotropy": anis, "dim": dim, "s": s, "books": b, "S": S, "prof": prof, "theory": th, "fit": fit,
            "c": c, "lam_w": lam_w, "lam_bar": lam_bar, "n_w": n_w, "nbar": nbar, "h": h,
            "blocks": blocks}


# ---- report and figure ---------------------------------------------------------------------

def pm(v, digits=4):
    m, e = v
    return f"{m:.{digits}g} ± {e:.2g}"


def report_lines(res):
    lines = []
    for r in res:
        d, s, b, th, f, tf = r["dim"], r["s"], r["books"], r["theory"], r["fit"], r["tfit"]
        eb, ee = th["boltzmann"], th["enskog"]
        zu, zt = ee["zeta"]
        lw = r["lam_w"]
        lines += [f"## {d}D: N = {s['N']:.0f}, L_x = {s['Lx']:.4g}, L_y = {s['Ly']:.4g}"
                  + (f", L_z = {s['Lz']:.4g}" if d == 3 else "")
                  + f", U = ±{s['U']:g}, T_wall = {s['T']:g}, phi = {s['phi']:g}", "",
                  f"Mean free path at the mean density {r['lam_bar']:.4g} (L_y = "
                  f"{s['Ly'] / r['lam_bar']:.1f} of them), at the walls {lw:.4g}; "
                  f"{len(r['blocks']['step'])} blocks; {s['coll']:.4g} collisions per particle "
                  f"and unit time.", "",
                  "| momentum book | value ± standard error over blocks |", "|---|---|",
                  f"| F_lo (x force on the lower wall) | {pm(b['F_lo'])} |",
                  f"| F_hi (x force on the upper wall) | {pm(b['F_hi'])} |",
                  f"| P_xy A | {pm(b['PxyA'])} |",
                  f"| P_xy A L_y/(L_y − σ) | {pm(b['PxyA_corr'])} |",
                  f"| F_lo + F_hi | {pm(b['F_lo+F_hi'], 2)} |",
                  f"| F_hi − P_xy A L_y/(L_y − σ) | {pm(b['F_hi-PxyA_corr'], 2)} |",
                  f"| −F_lo − P_xy A L_y/(L_y − σ) | {pm(b['-F_lo-PxyA_corr'], 2)} |",
                  f"| energy the walls gave the gas per unit time, lower, upper | "
                  f"{s['Elo']:.3g}, {s['Ehi']:.3g} (the walls' work 2 U F_lo = "
                  f"{2 * s['U'] * b['F_lo'][0]:.4g}) |",
                  "",
                  "| | measured | NS Boltzmann | NS Enskog |", "|---|---|---|---|",
                  f"| shear stress S = −P_xy L_y/(L_y − σ) | {pm(r['S'])} | {eb['S']:.5g} | "
                  f"{ee['S']:.5g} |",
                  f"| pressure P_yy | {pm(b['Pyy'])} | {eb['p']:.5g} | {ee['p']:.5g} |",
                  f"| centre temperature (bulk fit) | {pm(f['Tc'])} | {eb['Tc']:.5g} | "
                  f"{ee['Tc']:.5g} |",
                  f"| du/dy at the centre (bulk fit) | {pm(f['du0'])} | {tf['boltzmann']['du0'][0]:.5g} | "
                  f"{tf['enskog']['du0'][0]:.5g} |",
                  f"| slip U − u(wall), bulk fit extrapolated | {pm(f['slip'])} | "
                  f"{tf['boltzmann']['slip'][0]:.4g} | {tf['enskog']['slip'][0]:.4g} |",
                  f"| jump T(wall) − T_w, bulk fit extrapolated | {pm(f['jump'])} | "
                  f"{tf['boltzmann']['jump'][0]:.4g} | {tf['enskog']['jump'][0]:.4g} |",
                  f"| slip length / λ_wall (bulk fit) | {f['slip_length'][0] / lw:.3f} ± "
                  f"{f['slip_length'][1] / lw:.2g} | {tf['boltzmann']['slip_length'][0] / lw:.3f} | "
                  f"{tf['enskog']['slip_length'][0] / lw:.3f} |",
                  f"| jump length / λ_wall (bulk fit) | {f['jump_length'][0] / lw:.3f} ± "
                  f"{f['jump_length'][1] / lw:.2g} | {tf['boltzmann']['jump_length'][0] / lw:.3f} | "
                  f"{tf['enskog']['jump_length'][0] / lw:.3f} |",
                  f"| c = κ/η of T + u²/(2c) = const (bulk fit) | {pm(r['c'], 3)} | "
                  f"{conductivity_ratio(d, 'boltzmann'):.4g} | "
                  f"{conductivity_ratio(d, 'enskog', r['nbar']):.4g} (mean density) |",
                  "",
                  f"Slip and jump coefficients used: zeta_u = {zu:.4g}, zeta_T = {zt:.4g} (times the "
                  f"dilute mean free path, over chi for Enskog). Temperature components at the "
                  f"centre: " + ", ".join(f"T_{'xyz'[k]} = {t:.4g}" for k, t in
                                            enumerate(r["anisotropy"])) + ".", ""]
    return lines


def plot(res, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(len(res), 4, figsize=(17, 4.2 * len(res)), squeeze=False)
    for row, r in zip(ax, res):
        d, s, p = r["dim"], r["s"], r["prof"]
        lam, h = r["lam_bar"], r["h"]
        U, Tw = s["U"], s["T"]
        y = p["y"] / lam
        um, ue = mean_err(p["u"])
        Tm, Te = mean_err(p["T"])
        nm, ne = mean_err(p["n"])
        for model, style in (("enskog", "-"), ("boltzmann", "--")):
            t = r["theory"][model]
            lab = f"Navier-Stokes, {'Enskog' if model == 'enskog' else 'Boltzmann (dilute)'}"
            row[0].plot(t["y"] / lam, t["u"] / U - t["y"] / h, "k" + style, lw=1, label=lab)
            row[1].plot(t["y"] / lam, t["T"], "k" + style, lw=1, label=lab)
            row[2].plot(t["u"] / U, t["T"], "k" + style, lw=1, label=lab)
            row[3].plot(t["y"] / lam, t["n"], "k" + style, lw=1, label=lab)
        row[0].errorbar(y, um / U - p["y"] / h, ue / U, fmt="o", ms=3, color="C0",
                        label="event-driven")
        for k, Tc in enumerate(p["Tcomp"]):
            row[1].plot(y, Tc.mean(axis=0), ".", ms=3, color=f"C{k + 4}",
                        label=f"T_{'xyz'[k]} event-driven")
        row[1].errorbar(y, Tm, Te, fmt="o", ms=3, color="C3", label="T event-driven")
        row[2].errorbar(um / U, Tm, Te, fmt="o", ms=3, color="C3", label="event-driven")
        row[3].errorbar(y, nm, ne, fmt="o", ms=3, color="C2", label="event-driven")
        for a in (row[0], row[1], row[3]):
            for x in (-h / lam, h / lam):
                a.axvline(x, color="0.7", lw=0.8)
            a.set_xlabel("y / λ (λ at the mean density)")
        row[2].set_xlabel("u_x / U")
        row[0].set_ylabel("u_x / U − y / h")
        row[1].set_ylabel("T")
        row[2].set_ylabel("T")
        row[3].set_ylabel("number density")
        row[0].set_title(f"{d}D: velocity minus the no-slip line")
        row[1].set_title(f"{d}D: temperature (walls at T = {Tw:g})")
        row[2].set_title(f"{d}D: T against u (walls at u = ±{U:g})")
        row[3].set_title(f"{d}D: density")
        for a in row:
            a.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def run_example(work, dim, variables):
    name = f"couette{dim}d"
    lmp.run(EXAMPLES[dim], dict(variables), cwd=work, log=f"log.{name}")


QUICK = {2: {"nx": 32, "tavg": 200000}, 3: {"nx": 6, "tavg": 100000}}
FULL = {2: {"nx": 64, "tavg": 1000000}, 3: {"nx": 8, "tavg": 500000}}


def main(argv=None):
    def extra(ap):
        ap.add_argument("--reuse", action="store_true",
                        help="analyse the runs already in DIR/logs (no new runs)")
        ap.add_argument("--figure", default=FIGURE, help=f"the figure (default {FIGURE})")
    a = cli.scene_args(argv, __doc__, "out/couette",
                       "2D N = 1376 over 2e5, 3D N = 1188 over 1e5 time units (default; about 4 "
                       "minutes)", "2D N = 2752 over 1e6, 3D N = 2112 over 5e5 (about half an hour)",
                       extra)
    cases = FULL if a.full else QUICK
    res = []
    for dim in (2, 3):
        if not a.reuse:
            run_example(a.logs, dim, cases[dim])
        res.append(analyse(a.logs, dim))
    lines = ["# Plane Couette flow: momentum books and Navier-Stokes with slip and jump", ""]
    lines += report_lines(res)
    with open(os.path.join(a.out, "report.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    plot(res, a.figure)
    print("\n".join(lines))
    print(f"wrote {os.path.join(a.out, 'report.md')} and {a.figure}")
    return 0


if __name__ == "__main__":
    import sys
    sys.exit(main())
