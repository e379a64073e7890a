# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""GRANFRIC benchmark "Speed against accuracy" (bench/README.md): CPU cost against accuracy of three
ways to simulate the same granular gas, on two scenes:

  cooling  Luding et al. 1998: free cooling of rough discs (q = 1/2) in 2D, constant normal
           restitution r = 0.9 and tangential restitution beta = 0, area fraction 0.05; compared
           at the fixed time t = 20 (about 4 collision times; T_tr has fallen to ~0.42).
  driven   Herbst et al. 2005: spheres (q = 2/5) in a 2D monolayer, Walton law r = 0.95,
           mu = 0.5, rt_max = 0.4, Gaussian kicks f_dr = 2, v_dr = 0.1; fractions 0.05 and 0.34;
           compared in the steady state (time averages).

Methods:
  ED    fix hardsphere/ed (exact event-driven) at steps of 0.01 ... 10 mean free times;
  DEM   LAMMPS's own soft spheres: pair_style granular (hooke normal spring with
        coeff_restitution damping, linear_history tangential spring, Coulomb limit) and
        fix nve/sphere, at contact times t_c = 1e-1 ... 1e-3 mean free times and steps
        dt = t_c/10 ... t_c/50; contact parameters from soft_params() (the mapping);
  MF    the mean-field theory (granfric.cooling; model E of granfric.meanfield): no cost.

x: CPU seconds per collision time per 1000 particles, from resource.getrusage(RUSAGE_CHILDREN)
   deltas of the LAMMPS child process, minus the CPU time of the same input without the run
   (start-up, reading the initial state, setup); a collision time is the mean time between two
   collisions of one particle in the exact ED reference.
y: relative error of T_tr and of R = T_rot/T_tr against a converged exact-ED reference (many seeds
   for cooling, a long run for the driven scene), with the statistical error bar of the
   comparison (1 sigma).

    bench/speed_accuracy [--quick | --full | --smoke] [--out DIR]

Writes DIR/speed_accuracy.png, DIR/speed_accuracy.csv, DIR/speed_accuracy.md (default
DIR = out/speed_accuracy). A benchmark, not a test: the figures are measured in one run on a shared
machine.
"""
import argparse
import math
import os
import re
import resource
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "tools"))
from granfric import cli, cooling, herbst, lammpslog  # noqa: E402

LMP = os.path.join(ROOT, "tools", "lmp")
BUILD = os.environ.get("GRANFRIC_BUILD", os.path.join(ROOT, "build"))
SOFT = os.path.join(HERE, "soft")
ACCURACY = 0.01            # "equal accuracy": |relative error of T_tr| <= 1 %

# scene parameters
COOL = dict(phi=0.05, r=0.9, beta=0.0, q=0.5, tend=20.0)
DRIVE = dict(r=0.95, mu=0.5, rtmax=0.4, q=0.4, fdr=2.0, vdr=0.1)

# run sizes. dem: {t_c / mean free time: [t_c/dt, ...]}; *_fail: the "where methods fail" runs
SIZES = {
    "smoke": dict(
        cool_nside=16, cool_ref_seeds=3, cool_test_seeds=1, ed_dt=[0.1, 1.0], cool_repeat=2,
        cool_dem={0.1: [10]}, cool_fail={1.0: [20], 0.1: [1.5]},
        drv_phis=[0.05], drv_nside=16, drv_relax=50.0, drv_ref_mft=40.0, drv_test_mft=10.0,
        drv_disc_mft=2.0, drv_avg_mft=5.0, drv_cap_steps=20000, drv_dem={0.1: [10]},
        drv_fail={}, pair_offsets=3, pair_k=[20], pair_angles=[0.5, 4.0]),
    "quick": dict(
        cool_nside=48, cool_ref_seeds=8, cool_test_seeds=1, ed_dt=[0.01, 0.1, 1.0, 10.0],
        cool_repeat=6,
        cool_dem={0.1: [10, 20], 0.03: [10], 0.01: [10, 20]},
        cool_fail={0.3: [20], 1.0: [20], 0.01: [2, 1.5]},
        drv_phis=[0.05, 0.34], drv_nside=48, drv_relax=200.0, drv_ref_mft=300.0,
        drv_test_mft=30.0, drv_disc_mft=5.0, drv_avg_mft=25.0, drv_cap_steps=60000,
        drv_dem={0.1: [10, 20], 0.03: [10], 0.01: [10]}, drv_fail={0.3: [20]},
        pair_offsets=5, pair_k=[10, 20, 50, 2, 1.5], pair_angles=[0.2, 1.0, 2.0, 4.0, 10.0]),
    "full": dict(
        cool_nside=64, cool_ref_seeds=32, cool_test_seeds=6, cool_repeat=16,
        ed_dt=[0.01, 0.03, 0.1, 0.3, 1.0, 3.0, 10.0],
        cool_dem={0.1: [10, 20, 50], 0.03: [10, 20, 50], 0.01: [10, 20, 50], 0.003: [10, 20, 50],
                  0.001: [10]},
        cool_fail={0.3: [20], 1.0: [20], 0.01: [5, 3, 2, 1.5]},
        drv_phis=[0.05, 0.34], drv_nside=64, drv_relax=300.0, drv_ref_mft=1200.0,
        drv_test_mft=100.0, drv_disc_mft=10.0, drv_avg_mft=150.0, drv_cap_steps=300000,
        drv_dem={0.1: [10, 20, 50], 0.03: [10, 20, 50], 0.01: [10, 20, 50], 0.003: [10, 20],
                 0.001: [10]},
        drv_fail={0.3: [20], 1.0: [20], 0.01: [3, 1.5]},
        pair_offsets=10, pair_k=[10, 20, 50, 5, 3, 2, 1.5],
        pair_angles=[0.2, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 10.0]),
}


# --------------------------------------------------------------------------------------------
# the soft-sphere mapping
# --------------------------------------------------------------------------------------------
def soft_params(tc, r, rt, q, m=1.0):
    """pair_style granular coefficients for equal particles of mass m and shape factor q that
    reproduce normal restitution r and, for sticking contacts, tangential restitution rt, with a
    contact duration tc:

    normal (hooke + damping coeff_restitution): m_n = m/2, zeta = -ln r / sqrt(pi^2 + ln^2 r),
      omega_d = pi/tc, kn = m_n omega_d^2/(1 - zeta^2). LAMMPS sets the dashpot to
      2 zeta sqrt(m_n kn), so the normal motion is a damped oscillator that leaves contact
      (overlap 0, no limit_damping) after tc with g_n' = -r g_n exactly (up to the time step).
    tangential (linear_history kt, no tangential damping): while the contact sticks the
      tangential contact displacement is an undamped oscillator of effective mass
      m_t = m_n q/(1+q) (doc/conventions.rst, "The collision map"), so after tc the tangential
      contact velocity is g_t cos(omega_t tc) = -rt g_t for omega_t tc = arccos(-rt):
      kt = m_t (arccos(-rt)/tc)^2, i.e. kt/kn = q/(1+q) (1 - zeta^2) (arccos(-rt)/pi)^2.
    The spring energy left in the tangential spring when the contact opens is lost, which is
    what makes rt < 1. A Coulomb limit mu (finite) lets the contact slide (Walton law only in
    its limits; see the doc page)."""
    mn = m / 2.0
    lr = math.log(r)
    zeta = -lr / math.sqrt(math.pi ** 2 + lr ** 2)
    wd = math.pi / tc
    kn = mn * wd * wd / (1.0 - zeta * zeta)
    mt = mn * q / (1.0 + q)
    kt = mt * (math.acos(-rt) / tc) ** 2
    return {"kn": kn, "kt": kt, "zeta": zeta}


def walton_rt(r, mu, rtmax, q, gt_over_gn):
    """Walton's tangential restitution for equal particles, contact velocity ratio |g_t|/|g_n|."""
    if mu == math.inf:
        return rtmax
    return min(-1.0 + mu * (1.0 + q) / q * (1.0 + r) / gt_over_gn, rtmax)


# --------------------------------------------------------------------------------------------
# running LAMMPS and measuring its CPU time
# --------------------------------------------------------------------------------------------
def cpu_children():
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


def lammps(script, variables, log, cwd=None):
    """tools/lmp -in script -var ...; returns the CPU seconds (user + system) of the child.
    Raises RuntimeError with LAMMPS's error message on failure."""
    cmd = [LMP, "-in", os.path.join(SOFT, script), "-log", log, "-screen", "none"]
    for k, v in variables.items():
        cmd += ["-var", str(k), str(v)]
    c0 = cpu_children()
    p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    cpu = cpu_children() - c0
    if p.returncode != 0:
        text = p.stdout + p.stderr
        if os.path.exists(log):
            text += open(log, errors="replace").read()
        err = [line for line in text.splitlines() if "ERROR" in line]
        raise RuntimeError(err[0] if err else text[-500:])
    return cpu


def baseline(script, variables, log, repeats=3):
    """CPU time of the input without its run (variable run = 0): start-up, read_data, setup."""
    v = dict(variables, run=0)
    return float(np.median([lammps(script, v, log) for _ in range(repeats)]))


def pair_collision(kn, r, kt, mu, dt, gn, gt, offset, inertia, tc, work):
    """Two-particle collision through bench/soft/in.pair2; returns the measured normal and
    tangential restitution (g_n' = -r g_n, g_t' = -rt g_t along the fixed normal (-1, 0))."""
    dump = os.path.join(work, "pair2.dump")
    lammps("in.pair2", dict(kn=kn, r=r, kt=kt, mu=mu, dt=dt, gn=gn, gt=gt, offset=offset,
                            inertia=inertia, tmax=3.0 * tc + 3.0 * dt, out=dump),
           os.path.join(work, "log.pair2"))
    a = np.loadtxt(dump, skiprows=9)
    a = a[np.argsort(a[:, 0])]
    g = a[0, 3:5] - a[1, 3:5]                  # v1 - v2
    wsum = 0.5 * (a[0, 5] + a[1, 5])           # a1 w1 + a2 w2 (radius 0.5)
    gc = g - wsum * np.array([0.0, -1.0])      # minus (w z) x n, n = (-1, 0)
    r_meas = -gc[0] / gn                       # g.n = -g_x; before: g.n = -gn
    rt_meas = -gc[1] / gt if gt else float("nan")
    return r_meas, rt_meas


def pair_restitution(tc, k, r, rt, mu, q, gt_over_gn, offsets, work):
    """Mean (and spread) over contact phases (first contact at a fraction of a step) of the
    restitutions of one soft collision with t_c = tc and dt = tc/k."""
    p = soft_params(tc, r, rt, q)
    inertia = "disc" if q == 0.5 else "sphere"
    res = np.array([pair_collision(p["kn"], r, p["kt"], mu, tc / k, 1.0, gt_over_gn, o, inertia,
                                   tc, work)
                    for o in (np.arange(offsets) + 0.5) / offsets])
    return res.mean(axis=0), res.std(axis=0)


# --------------------------------------------------------------------------------------------
# helpers
# --------------------------------------------------------------------------------------------
class Bar:
    def __init__(self, total):
        try:
            from tqdm import tqdm
            self.t = tqdm(total=total, desc="speed/accuracy runs", unit="run")
        except ImportError:
            self.t = None

    def __call__(self, text=None):
        if self.t is not None:
            if text:
                self.t.set_postfix_str(text, refresh=False)
            self.t.update(1)

    def close(self):
        if self.t is not None:
            self.t.close()


def row(scene, method, role, **kw):
    base = {"scene": scene, "method": method, "role": role, "tc_mft": "", "dt_over_tc": "",
            "dt_mft": "", "N": "", "cpu_s": "", "collision_times": "", "cost": "",
            "Ttr": "", "R": "", "err_Ttr": "", "sig_Ttr": "", "err_R": "", "sig_R": "",
            "status": "ok", "note": ""}
    base.update(kw)
    return base


def tau_int(x, blocks=10):
    """Integrated autocorrelation time of a series (in samples) from batch means."""
    n = len(x) // blocks
    if n < 2:
        return 1.0
    m = np.asarray(x[:n * blocks]).reshape(blocks, n).mean(axis=1)
    return max(0.5, 0.5 * n * m.var(ddof=1) / max(np.var(x), 1e-300))


# --------------------------------------------------------------------------------------------
# cooling scene
# --------------------------------------------------------------------------------------------
def plan_cooling(S):
    nref, ntest = S["cool_ref_seeds"], S["cool_test_seeds"]
    ndem = sum(len(v) for v in S["cool_dem"].values()) + sum(len(v) for v in S["cool_fail"].values())
    return (nref + ntest) + nref + 2 + len(S["ed_dt"]) + ntest * (len(S["ed_dt"]) + ndem)


def cooling_scene(S, work, bar):
    c = COOL
    nside = S["cool_nside"]
    N = nside * nside
    mft0 = 1.0 / cooling.collision_frequency(1.0, c["phi"], 0.5, 1.0, 2)   # at T = 1
    tend = c["tend"]
    ref_seeds = [1000 + s for s in range(S["cool_ref_seeds"])]
    test_seeds = [1 + s for s in range(S["cool_test_seeds"])]
    data = {}
    for s in ref_seeds + test_seeds:
        data[s] = os.path.join(work, f"cool_init_{s}.data")
        lammps("in.init", dict(phi=c["phi"], nside=nside, seed=s, data=data[s]),
               os.path.join(work, "log.init"))
        bar("cooling: initial states")

    def ed(seed, dt, tag):
        log = os.path.join(work, f"log.cool_ed_{tag}_{seed}")
        cpu = lammps("in.cooling_ed", dict(data=data[seed], r=c["r"], beta=c["beta"], tend=tend,
                                           dt=dt), log)
        d = lammpslog.read_thermo(log)
        return cpu, d["c_T[1]"][-1], d["c_T[3]"][-1], d["f_ed[2]"][-1], d["Time"][-1]

    # reference: exact ED, many seeds, step 1 mean free time
    ref, ref_cpu = [], 0.0
    dt_ref = tend / round(tend / mft0)
    for s in ref_seeds:
        x = ed(s, dt_ref, "ref")
        ref.append(x[1:4])
        ref_cpu += x[0]
        bar("cooling: ED reference")
    ref = np.array(ref)
    Tref, Rref = ref[:, 0].mean(), ref[:, 1].mean()
    sT1, sR1 = ref[:, 0].std(ddof=1) / Tref, ref[:, 1].std(ddof=1) / Rref   # one run, relative
    nref = len(ref_seeds)
    ncoll_times = float(np.mean(2.0 * ref[:, 2] / N))       # collisions per particle up to tend
    info = {"N": N, "phi": c["phi"], "mft0": mft0, "Tref": Tref, "Rref": Rref, "sT_ref": sT1 / math.sqrt(nref),
            "sR_ref": sR1 / math.sqrt(nref), "sT1": sT1, "sR1": sR1, "collision_times": ncoll_times}
    ntest = len(test_seeds)
    sigT = sT1 * math.sqrt(1.0 / ntest + 1.0 / nref)
    sigR = sR1 * math.sqrt(1.0 / ntest + 1.0 / nref)
    rows = []

    base_ed = baseline("in.cooling_ed", dict(data=data[test_seeds[0]], r=c["r"], beta=c["beta"]),
                       os.path.join(work, "log.base"))
    bar("cooling: baselines")
    p0 = soft_params(0.01 * mft0, c["r"], c["beta"], c["q"])
    base_dem = baseline("in.cooling_soft", dict(data=data[test_seeds[0]], kn=p0["kn"], kt=p0["kt"],
                                                r=c["r"]), os.path.join(work, "log.base"))
    bar("cooling: baselines")
    info["base_ed"], info["base_dem"] = base_ed, base_dem

    def cost(cpu_total, base, n):
        return max(cpu_total - n * base, 1e-9) / n / ncoll_times / (N / 1000.0)

    # One ED cooling run is short (~10^4 collisions, ~20 ms of CPU against a process start-up of
    # ~0.12 s, which a baseline cannot be subtracted from to better than a few ms): its cost is
    # measured on the run repeated in one process, against the same repetitions without the run,
    # fastest of interleaved pairs.
    def ed_cost(dt, tag):
        rep = S["cool_repeat"]
        v = dict(data=data[test_seeds[0]], r=c["r"], beta=c["beta"], tend=tend, dt=dt, repeat=rep)
        log = os.path.join(work, f"log.cool_ed_cost_{tag}")
        with_run = min(lammps("in.cooling_ed", v, log) for _ in range(2))
        without = min(lammps("in.cooling_ed", dict(v, run=0), log) for _ in range(2))
        return cost(with_run, without, 1) / rep

    info["ref_cost_single"] = cost(ref_cpu, base_ed, nref)   # from the single reference runs
    info["ref_cost"] = ed_cost(dt_ref, "ref")
    info["dt_ref_mft"] = dt_ref / mft0

    # exact ED against the step
    ed_values = []
    for dtm in S["ed_dt"]:
        dt = tend / max(1, round(tend / (dtm * mft0)))
        res = [ed(s, dt, f"dt{dtm}") for s in test_seeds]
        for _ in test_seeds:
            bar("cooling: ED")
        c_ed = ed_cost(dt, f"dt{dtm}")
        bar("cooling: ED (cost)")
        T, R = np.mean([x[1] for x in res]), np.mean([x[2] for x in res])
        ed_values.append([x[1] for x in res])
        rows.append(row("cooling", "ED", "curve", dt_mft=dt / mft0, N=N,
                        cpu_s=np.mean([x[0] for x in res]), collision_times=ncoll_times,
                        cost=c_ed, Ttr=T, R=R,
                        err_Ttr=T / Tref - 1, sig_Ttr=sigT, err_R=R / Rref - 1, sig_R=sigR,
                        note=f"dt = {dt:.4g}" + (" (one window: the whole run)" if dt >= tend else "")))
    ed_values = np.array(ed_values)
    info["ed_spread"] = float(np.max(np.abs(ed_values / ed_values[0] - 1)))

    # soft-sphere DEM
    def dem(f, k, role):
        tc = f * mft0
        nsteps = max(1, round(tend / (tc / k)))
        dt = tend / nsteps
        p = soft_params(tc, c["r"], c["beta"], c["q"])
        res, err = [], None
        for s in test_seeds:
            log = os.path.join(work, f"log.cool_dem_{f}_{k}_{s}")
            try:
                cpu = lammps("in.cooling_soft", dict(data=data[s], kn=p["kn"], kt=p["kt"], r=c["r"],
                                                     mu=1e8, tend=tend, dt=dt), log)
                d = lammpslog.read_thermo(log)
                res.append((cpu, d["c_T[1]"][-1], d["c_T[3]"][-1]))
            except (RuntimeError, ValueError) as e:
                err = str(e)
            bar(f"cooling: DEM tc={f} mft dt=tc/{k}")
        kw = dict(tc_mft=f, dt_over_tc=1.0 / k, dt_mft=dt / mft0, N=N, collision_times=ncoll_times)
        if err or not res:
            return row("cooling", "DEM", role, status="failed", note=err or "no output", **kw)
        cpu = sum(x[0] for x in res)
        T, R = np.mean([x[1] for x in res]), np.mean([x[2] for x in res])
        status = "ok"
        if not (math.isfinite(T) and math.isfinite(R)) or T > 10 * Tref:
            status = "failed"
            kw["note"] = f"energy blow-up: T_tr = {T:.3g} instead of {Tref:.3g}"
        return row("cooling", "DEM", role, cpu_s=cpu / len(res), cost=cost(cpu, base_dem, len(res)),
                   Ttr=T, R=R, err_Ttr=T / Tref - 1, sig_Ttr=sigT, err_R=R / Rref - 1, sig_R=sigR,
                   status=status, **kw)

    for f, ks in S["cool_dem"].items():
        for k in ks:
            rows.append(dem(f, k, "curve"))
    for f, ks in S["cool_fail"].items():
        for k in ks:
            rows.append(dem(f, k, "failure"))

    # mean field
    _, Tth, Troth = cooling.integrate(c["r"], c["beta"], c["q"], 2, c["phi"], T0=(1.0, 0.0),
                                      times=[0.0, tend])
    rows.append(row("cooling", "MF", "curve", cost=0.0, Ttr=Tth[-1], R=Troth[-1] / Tth[-1],
                    err_Ttr=Tth[-1] / Tref - 1, sig_Ttr=info["sT_ref"],
                    err_R=Troth[-1] / Tth[-1] / Rref - 1, sig_R=info["sR_ref"],
                    note="homogeneous-cooling mean field (granfric.cooling)"))
    return rows, info


# --------------------------------------------------------------------------------------------
# driven scene
# --------------------------------------------------------------------------------------------
def plan_driven(S):
    ndem = sum(len(v) for v in S["drv_dem"].values()) + sum(len(v) for v in S["drv_fail"].values())
    return len(S["drv_phis"]) * (1 + 1 + 2 + len(S["ed_dt"]) + ndem)


def snap_step(dt, P):
    """A step that divides the kick period P into an even number of steps, or is a multiple of
    P, close to dt."""
    if dt < P:
        return P / (2 * max(1, round(P / (2 * dt))))
    return P * round(dt / P)


def driven_scene(phi, S, work, bar):
    c = DRIVE
    nside = S["drv_nside"]
    N = nside * nside
    P = 1.0 / c["fdr"]
    scene = f"driven {phi}"
    data = os.path.join(work, f"drv_init_{phi}.data")
    lammps("in.init", dict(phi=phi, nside=nside, seed=4321, data=data, drive=1, r=c["r"], mu=c["mu"],
                           rtmax=c["rtmax"], fdr=c["fdr"], vdr=c["vdr"], trelax=S["drv_relax"]),
           os.path.join(work, "log.init"))
    bar(f"{scene}: initial state")
    law = dict(r=c["r"], fdr=c["fdr"], vdr=c["vdr"])

    def ed(dt, tend, seed, tag):
        series = os.path.join(work, f"T.{phi}.ed_{tag}")
        every = max(1, round(P / dt)) if dt < P else 1
        cpu = lammps("in.driven_ed", dict(law, data=data, mu=c["mu"], rtmax=c["rtmax"], seed=seed,
                                          tend=tend, dt=dt, every=every, series=series),
                     os.path.join(work, f"log.{phi}.ed_{tag}"))
        a = np.loadtxt(series, ndmin=2)
        t = a[:, 0] * dt
        sel = np.abs(np.round(t / P) - t / P) < 1e-6        # half-way between two kicks
        return cpu, t[sel], a[sel, 1], a[sel, 2] / a[sel, 1], a[-1, 3]

    # reference: one long exact-ED run; its mean free time and autocorrelation times
    mft_guess = 5.0 if phi < 0.1 else 1.0
    tref = P * round(S["drv_ref_mft"] * mft_guess / P)
    _, _, Ts, Rs, coll = ed(P, tref, 11, "ref")
    bar(f"{scene}: ED reference")
    mft = N * tref / (2.0 * coll)
    tauT, tauR = tau_int(Ts), tau_int(Rs)       # in samples (one per kick period)
    Tref, Rref = Ts.mean(), Rs.mean()
    sdT, sdR = Ts.std() / Tref, Rs.std() / Rref

    def sigma(nsamples):
        """relative 1-sigma of a time average over nsamples kick periods, and of the reference"""
        sT = sdT * math.sqrt(2 * tauT / max(nsamples, 1))
        sR = sdR * math.sqrt(2 * tauR / max(nsamples, 1))
        return sT, sR

    sTref, sRref = sigma(len(Ts))
    info = {"N": N, "phi": phi, "mft": mft, "Tref": Tref, "Rref": Rref, "sT_ref": sTref, "sR_ref": sRref,
            "tauT_mft": tauT * P / mft, "tauR_mft": tauR * P / mft, "tref_mft": tref / mft}
    base_ed = baseline("in.driven_ed", dict(law, data=data, mu=c["mu"], rtmax=c["rtmax"],
                                            series=os.path.join(work, "T.base")),
                       os.path.join(work, "log.base"))
    bar(f"{scene}: baselines")
    p0 = soft_params(0.01 * mft, c["r"], c["rtmax"], c["q"])
    base_dem = baseline("in.driven_soft", dict(law, data=data, kn=p0["kn"], kt=p0["kt"], mu=c["mu"],
                                               series=os.path.join(work, "T.base")),
                        os.path.join(work, "log.base"))
    bar(f"{scene}: baselines")
    info["base_ed"], info["base_dem"] = base_ed, base_dem
    rows = []

    def cost(cpu, base, tend):
        return max(cpu - base, 1e-9) / (tend / mft) / (N / 1000.0)

    # exact ED against the step (another kick seed than the reference: statistically independent;
    # the same kicks at every step, so the same trajectory)
    ttest = P * round(S["drv_test_mft"] * mft / P)
    series_by_dt = []
    for dtm in S["ed_dt"]:
        dt = snap_step(dtm * mft, P)
        tend = dt * max(1, round(ttest / dt))
        cpu, t_s, T_s, R_s, _ = ed(dt, tend, 12, f"dt{dtm}")
        bar(f"{scene}: ED")
        series_by_dt.append(dict(zip(np.round(t_s / P).astype(int), T_s)))
        T, R = T_s.mean(), R_s.mean()
        sT, sR = sigma(len(T_s))
        rows.append(row(scene, "ED", "curve", dt_mft=dt / mft, N=N, cpu_s=cpu,
                        collision_times=tend / mft, cost=cost(cpu, base_ed, tend), Ttr=T, R=R,
                        err_Ttr=T / Tref - 1, sig_Ttr=math.hypot(sT, sTref), err_R=R / Rref - 1,
                        sig_R=math.hypot(sR, sRref),
                        note=f"dt = {dt:.4g}, run {tend:.4g}, {len(T_s)} samples"))
    # T_tr at the sample times common to all steps
    # within the first 2 collision times: later, round-off differences between steps (another order
    # of operations) grow by molecular chaos and the runs become statistically independent
    common = set.intersection(*[set(d) for d in series_by_dt])
    early = [k for k in common if k * P <= 2.0 * mft]
    info["ed_spread"] = float(max((abs(d[k] / series_by_dt[0][k] - 1) for d in series_by_dt
                                   for k in early), default=float("nan")))
    info["ed_common"] = len(early)

    def dem(f, k, role):
        tc = f * mft
        dt = snap_step(tc / k, P)
        t_run = min(S["drv_disc_mft"] + S["drv_avg_mft"], S["drv_cap_steps"] * dt / mft)
        t_run = max(t_run, S["drv_disc_mft"] + 2 * P / mft)
        tend = P * max(2, round(t_run * mft / P))
        p = soft_params(tc, c["r"], c["rtmax"], c["q"])
        series = os.path.join(work, f"T.{phi}.dem_{f}_{k}")
        kw = dict(tc_mft=f, dt_over_tc=dt / tc, dt_mft=dt / mft, N=N, collision_times=tend / mft)
        try:
            cpu = lammps("in.driven_soft", dict(law, data=data, kn=p["kn"], kt=p["kt"], mu=c["mu"],
                                                tend=tend, dt=dt, seed=13, series=series),
                         os.path.join(work, f"log.{phi}.dem_{f}_{k}"))
        except RuntimeError as e:
            bar(f"{scene}: DEM tc={f} mft dt=tc/{k}")
            return row(scene, "DEM", role, status="failed", note=str(e), **kw)
        bar(f"{scene}: DEM tc={f} mft dt=tc/{k}")
        a = np.loadtxt(series, ndmin=2)
        t = a[:, 0] * dt
        sel = (t > S["drv_disc_mft"] * mft) & (np.abs(t / P - np.round(t / P)) < 1e-6)
        if not np.any(sel):
            return row(scene, "DEM", role, status="failed", note="no samples", **kw)
        T, R = a[sel, 1].mean(), (a[sel, 2] / a[sel, 1]).mean()
        sT, sR = sigma(int(np.count_nonzero(sel)))
        status = "ok" if (math.isfinite(T) and math.isfinite(R) and T < 10 * Tref) else "failed"
        blow = f"energy blow-up: T_tr = {T:.3g} instead of {Tref:.3g}; " if status != "ok" else ""
        return row(scene, "DEM", role, cpu_s=cpu, cost=cost(cpu, base_dem, tend), Ttr=T, R=R,
                   err_Ttr=T / Tref - 1, sig_Ttr=math.hypot(sT, sTref), err_R=R / Rref - 1,
                   sig_R=math.hypot(sR, sRref), status=status,
                   note=blow + f"averaged over {np.count_nonzero(sel) * P / mft:.0f} collision times after "
                        f"{S['drv_disc_mft']:g}", **kw)

    for f, ks in S["drv_dem"].items():
        for k in ks:
            rows.append(dem(f, k, "curve"))
    for f, ks in S["drv_fail"].items():
        for k in ks:
            rows.append(dem(f, k, "failure"))

    R_E, T_E = herbst.theory(c["r"], c["mu"], c["rtmax"], phi, N, c["fdr"], c["vdr"])
    rows.append(row(scene, "MF", "curve", cost=0.0, Ttr=T_E, R=R_E, err_Ttr=T_E / Tref - 1,
                    sig_Ttr=sTref, err_R=R_E / Rref - 1, sig_R=sRref,
                    note="mean-field model E (granfric.meanfield via granfric.herbst.theory)"))
    return rows, info


# --------------------------------------------------------------------------------------------
# mapping check: two-particle collisions
# --------------------------------------------------------------------------------------------
def plan_mapping(S):
    return len(S["pair_k"]) + len(S["pair_angles"])


def mapping_check(S, work, bar):
    """Restitutions of one soft collision (t_c = 1e-3, dimensionless with the approach speed):
    the cooling mapping (discs, r = 0.9, beta = 0, mu = 1e8) against dt/t_c; the driven mapping
    (spheres, r = 0.95, rt_max = 0.4, mu = 0.5) against |g_t|/|g_n| (dt = t_c/50), with
    Walton's law for comparison."""
    tc, out = 1e-3, {"cooling": [], "walton": []}
    for k in S["pair_k"]:
        (rm, bm), (rs, bs) = pair_restitution(tc, k, COOL["r"], COOL["beta"], 1e8, COOL["q"], 0.5,
                                              S["pair_offsets"], work)
        out["cooling"].append(dict(k=k, r=rm, r_sd=rs, beta=bm, beta_sd=bs))
        bar("two-particle collisions")
    c = DRIVE
    for x in S["pair_angles"]:
        (rm, tm), _ = pair_restitution(tc, 50, c["r"], c["rtmax"], c["mu"], c["q"], x,
                                       S["pair_offsets"], work)
        out["walton"].append(dict(gt_over_gn=x, r=rm, rt=tm,
                                  rt_walton=walton_rt(c["r"], c["mu"], c["rtmax"], c["q"], x)))
        bar("two-particle collisions")
    return out


# --------------------------------------------------------------------------------------------
# the ceiling on the ratio: exact ED's event core alone against the DEM run
# --------------------------------------------------------------------------------------------
def core_floor(N, phi, size):
    """bench_kick on the event core alone (no LAMMPS; elastic smooth discs at the scene's N and
    fraction, all in cache): seconds per collision, and per particle and kick (a kick re-predicts
    every particle). None if bench_kick is not built."""
    exe = os.path.join(BUILD, "bench_kick")
    if not os.access(exe, os.X_OK):
        return None
    mfts, rounds = {"smoke": (4, 2), "quick": (10, 3), "full": (20, 5)}[size]
    p = subprocess.run([exe, "2", str(N), f"{phi:g}", "10", str(mfts), str(rounds)],
                       capture_output=True, text=True, check=True)
    per_coll = float(re.search(r"([-+.\deE]+) us per collision", p.stdout)[1]) * 1e-6
    per_kick = float(re.search(r"one kick costs ([-+.\deE]+) us per particle", p.stdout)[1]) * 1e-6
    return dict(coll=per_coll, kick=per_kick, line=p.stdout.strip())


def ceiling(scene, d, info, floor):
    """What the ratio against DEM run d could be at most, if exact ED cost only what its event core
    costs alone (floor, from core_floor): DEM's cost per collision time over the core's (half a
    collision per particle and collision time, plus the kicks, which re-predict every particle).
    The kicks alone bound it by (DEM steps per kick) x (DEM cost of a particle step) / (core
    cost of re-predicting a particle)."""
    if scene == "cooling":
        steps = COOL["tend"] / (d["dt_mft"] * info["mft0"]) / info["collision_times"]
        kicks = 0.0
    else:
        steps = 1.0 / d["dt_mft"]
        kicks = DRIVE["fdr"] * info["mft"]
    step_cost = d["cost"] / 1000.0 / steps          # CPU s per particle and DEM step
    ed_floor = 1000.0 * (0.5 * floor["coll"] + kicks * floor["kick"])
    text = (f"{scene}: ceiling against {label(d)}: a DEM particle step costs "
            f"{1e9 * step_cost:.0f} ns ({steps:.0f} steps per collision time); exact ED's event "
            f"core alone (bench_kick: no LAMMPS, data in cache, elastic smooth discs at N = "
            f"{info['N']} and this fraction) costs {1e6 * floor['coll']:.2f} us per collision")
    if kicks > 0:
        text += (f" and {1e6 * floor['kick']:.3f} us per particle and kick ({kicks:.1f} kicks per "
                 f"collision time)")
    text += (f": {ed_floor:.3g} s per collision time per 1000 particles, so the ratio is at most "
             f"**{d['cost'] / ed_floor:.0f}**")
    if kicks > 0:
        text += (f"; the kicks alone cap it at {steps / kicks:.0f} DEM steps per kick x "
                 f"{1e9 * step_cost:.0f} ns / {1e9 * floor['kick']:.0f} ns = "
                 f"**{d['cost'] / (1000.0 * kicks * floor['kick']):.0f}**")
    return text


# --------------------------------------------------------------------------------------------
# analysis, table, chart
# --------------------------------------------------------------------------------------------
def best(rows, scene, method, accuracy=ACCURACY, converged=False):
    """Cheapest run of a method on a scene with |error of T_tr| <= accuracy. For DEM the
    statistical error bar must also be below 0.7 % (else the statement means little); with
    converged=True the run must lie on a curve (same dt/t_c) whose stiffer runs are all within the
    accuracy too (no lucky cancellation of two errors). Exact ED has no systematic error: its
    cheapest run counts."""
    runs = [r for r in rows if r["scene"] == scene and r["method"] == method and r["role"] == "curve"
            and r["status"] == "ok" and r["cost"] != ""]
    if method == "ED":
        return min(runs, key=lambda r: r["cost"]) if runs else None

    def good(r):
        return abs(r["err_Ttr"]) <= accuracy and r["sig_Ttr"] <= 0.007

    ok = []
    for r in runs:
        if not good(r):
            continue
        if converged:
            k = round(1 / r["dt_over_tc"])
            stiffer = [x for x in runs if round(1 / x["dt_over_tc"]) == k and x["tc_mft"] < r["tc_mft"]]
            if not all(good(x) for x in stiffer):
                continue
        ok.append(r)
    return min(ok, key=lambda r: r["cost"]) if ok else None


def label(r):
    if r["method"] == "ED":
        return f"ED dt={r['dt_mft']:.3g} mft"
    if r["method"] == "DEM":
        return f"DEM t_c={r['tc_mft']:g} mft, dt=t_c/{1 / r['dt_over_tc']:.3g}"
    return "mean field"


def fmt_pct(x, s=None):
    if x == "" or x is None:
        return ""
    return f"{100 * x:+.2f} %" + (f" ± {100 * s:.2f}" if s not in ("", None) else "")


def write_markdown(path, rows, infos, mapping, ratios, size, ceilings=()):
    L = [f"# Speed against accuracy ({size})", "",
         "x = CPU seconds (user + system of the LAMMPS process, minus its start-up/read/setup "
         "baseline) per collision time per 1000 particles; errors are relative to the exact-ED "
         "reference, ± 1 sigma statistical.", ""]
    for scene, info in infos.items():
        L.append(f"## {scene}")
        L.append("")
        if scene == "cooling":
            L.append(f"N = {info['N']}, mean free time at T = 1: {info['mft0']:.3f}; compared at "
                     f"t = {COOL['tend']:g} ({info['collision_times']:.2f} collision times). Reference: "
                     f"{S_used['cool_ref_seeds']} exact-ED runs, T_tr = {info['Tref']:.5f} "
                     f"(± {100 * info['sT_ref']:.2f} %), R = {info['Rref']:.5f} "
                     f"(± {100 * info['sR_ref']:.2f} %); one run scatters by {100 * info['sT1']:.2f} % "
                     f"(T_tr) and {100 * info['sR1']:.2f} % (R). ED at all steps: largest relative "
                     f"difference of T_tr between steps {info['ed_spread']:.1e} (same trajectory). "
                     f"CPU time of ED at dt = {info['dt_ref_mft']:.3g} mft: {info['ref_cost']:.3g} s "
                     f"per collision time per 1000 particles (the run repeated "
                     f"{S_used['cool_repeat']} times in one process, as for every ED step; "
                     f"{info['ref_cost_single']:.3g} from the single reference runs minus the "
                     f"baseline); baselines "
                     f"(start-up, read, setup): ED {info['base_ed']:.3f} s, DEM {info['base_dem']:.3f} s.")
        else:
            L.append(f"N = {info['N']}, mean free time {info['mft']:.3f}; reference: exact ED over "
                     f"{info['tref_mft']:.0f} collision times, T_tr = {info['Tref']:.5f} "
                     f"(± {100 * info['sT_ref']:.2f} %), R = {info['Rref']:.5f} "
                     f"(± {100 * info['sR_ref']:.2f} %); correlation times {info['tauT_mft']:.1f} "
                     f"(T_tr) and {info['tauR_mft']:.1f} (R) collision times. ED at all steps: "
                     f"largest relative difference of T_tr between steps at {info['ed_common']} common "
                     f"sample times within 2 collision times {info['ed_spread']:.1e} (same trajectory; "
                     f"later, round-off differences grow by molecular chaos); baselines ED "
                     f"{info['base_ed']:.3f} s, DEM {info['base_dem']:.3f} s.")
        L.append("")
        L.append("| method | role | CPU s / collision time / 1000 | error T_tr | error R | status |")
        L.append("|---|---|---|---|---|---|")
        for r in rows:
            if r["scene"] != scene:
                continue
            cst = f"{r['cost']:.3g}" if r["cost"] not in ("", 0.0) else ("0 (theory)" if r["cost"] == 0.0 else "")
            st = r["status"] + (f": {r['note']}" if r["status"] != "ok" else "")
            L.append(f"| {label(r)} | {r['role']} | {cst} | {fmt_pct(r['err_Ttr'], r['sig_Ttr'])} | "
                     f"{fmt_pct(r['err_R'], r['sig_R'])} | {st} |")
        L.append("")
    L.append("## Soft/ED cost ratio at equal accuracy (T_tr within 1 %)")
    L.append("")
    for line in ratios:
        L.append(f"- {line}")
    L.append("")
    if ceilings:
        L.append("## What bounds the ratio: exact ED's event core alone (same run)")
        L.append("")
        for line in ceilings:
            L.append(f"- {line}")
        L.append("")
    L.append("## The soft-sphere mapping, two-particle collisions (t_c = 1e-3, approach speed 1)")
    L.append("")
    L.append("Cooling law (discs, r = 0.9, beta = 0, mu = 1e8), mean ± spread over contact phases:")
    L.append("")
    L.append("| dt | normal restitution | tangential restitution (target 0) |")
    L.append("|---|---|---|")
    for m in mapping["cooling"]:
        L.append(f"| t_c/{m['k']:g} | {m['r']:.4f} ± {m['r_sd']:.4f} | {m['beta']:+.4f} ± {m['beta_sd']:.4f} |")
    L.append("")
    L.append("Driven law (spheres, r = 0.95, mu = 0.5, rt_max = 0.4), dt = t_c/50, against Walton's law:")
    L.append("")
    L.append("| abs(g_t)/abs(g_n) | normal restitution | rt soft | rt Walton |")
    L.append("|---|---|---|---|")
    for m in mapping["walton"]:
        L.append(f"| {m['gt_over_gn']:g} | {m['r']:.4f} | {m['rt']:+.4f} | {m['rt_walton']:+.4f} |")
    L.append("")
    with open(path, "w") as f:
        f.write("\n".join(L) + "\n")


def plot(path, rows, infos):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    scenes = list(infos)
    fig, axes = plt.subplots(len(scenes), 2, figsize=(12.5, 3.9 * len(scenes)), squeeze=False)
    colors = {10: "C1", 20: "C2", 50: "C3"}
    clip = lambda x: max(-1.5, min(1.5, x))
    for i, scene in enumerate(scenes):
        info = infos[scene]
        for j, (key, sig, name, sref) in enumerate((("err_Ttr", "sig_Ttr", "T_tr", "sT_ref"),
                                                    ("err_R", "sig_R", "R = T_rot/T_tr", "sR_ref"))):
            ax = axes[i, j]
            ax.axhspan(-ACCURACY, ACCURACY, color="#d8f0d8", zorder=0, label="within 1 %")
            ax.axhspan(-info[sref], info[sref], color="0.75", zorder=0,
                       label="reference: ± 1 sigma")
            ax.axhline(0.0, color="k", lw=0.5)
            sel = [r for r in rows if r["scene"] == scene and r["status"] == "ok" and r["cost"] not in ("", 0.0)]
            ed = sorted([r for r in sel if r["method"] == "ED"], key=lambda r: r["cost"])
            if ed:
                ax.errorbar([r["cost"] for r in ed], [r[key] for r in ed],
                            yerr=[r[sig] for r in ed], fmt="o-", color="C0", ms=5, capsize=2,
                            label="exact ED (label: dt in mean free times)")
                for r in ed:
                    ax.annotate(f"{r['dt_mft']:.2g}", (r["cost"], r[key]), fontsize=6,
                                xytext=(2, 4), textcoords="offset points", color="C0")
            for k, col in colors.items():
                dem = sorted([r for r in sel if r["method"] == "DEM" and r["role"] == "curve"
                              and abs(1 / r["dt_over_tc"] - k) < 0.5], key=lambda r: r["cost"])
                if dem:
                    ax.errorbar([r["cost"] for r in dem], [clip(r[key]) for r in dem],
                                yerr=[r[sig] for r in dem], fmt="s-", color=col, ms=4, capsize=2,
                                label=f"soft DEM, dt = t_c/{k} (label: t_c in mft)")
                    for r in dem:
                        ax.annotate(f"{r['tc_mft']:g}", (r["cost"], clip(r[key])), fontsize=6,
                                    xytext=(3, -9), textcoords="offset points", color=col)
            fail = [r for r in rows if r["scene"] == scene and r["method"] == "DEM"
                    and r["role"] == "failure" and r["cost"] not in ("", 0.0)]
            if fail:
                ax.plot([r["cost"] for r in fail], [clip(r[key]) for r in fail], "x", color="k",
                        ms=7, label="soft DEM: failure runs (see table)")
            mf = [r for r in rows if r["scene"] == scene and r["method"] == "MF"]
            if mf:
                ax.axhline(mf[0][key], color="C4", ls="--", lw=1.2,
                           label=f"mean field (no cost): {100 * mf[0][key]:+.1f} %")
            ax.set_xscale("log")
            ax.set_yscale("symlog", linthresh=0.02, linscale=1.5)
            ax.set_ylim(-1.6, 1.6)
            ax.set_yticks([-1, -0.1, -0.02, -0.01, 0, 0.01, 0.02, 0.1, 1])
            ax.set_yticklabels(["-100%", "-10%", "-2%", "-1%", "0", "1%", "2%", "10%", "100%"])
            ax.set_xlabel("CPU s per collision time per 1000 particles")
            ax.set_ylabel(f"relative error of {name}")
            ax.set_title(f"{scene}: {name}", fontsize=9)
            ax.legend(fontsize=5.5, loc="lower left" if j == 0 else "upper left", ncol=2)
    fig.suptitle("Speed against accuracy: exact event-driven (fix hardsphere/ed) vs soft-sphere DEM "
                 "(pair_style granular) vs mean field\n(errors against the exact-ED reference; "
                 "symlog axis, linear within ± 2 %; failure runs clipped at ± 150 %)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


S_used = {}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--quick", action="store_true", help="small sizes, a few minutes")
    g.add_argument("--full", action="store_true", help="the default sizes (~20-30 CPU minutes)")
    g.add_argument("--smoke", action="store_true", help="smallest configuration (tests, ~30 s)")
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "speed_accuracy"))
    a = ap.parse_args(argv)
    size = "quick" if a.quick else "smoke" if a.smoke else "full"
    S = SIZES[size]
    S_used.clear()
    S_used.update(S)
    os.makedirs(a.out, exist_ok=True)
    work = os.path.join(a.out, "work")
    os.makedirs(work, exist_ok=True)

    bar = Bar(plan_mapping(S) + plan_cooling(S) + plan_driven(S))
    mapping = mapping_check(S, work, bar)
    rows, infos = [], {}
    r, infos["cooling"] = cooling_scene(S, work, bar)
    rows += r
    for phi in S["drv_phis"]:
        r, infos[f"driven {phi}"] = driven_scene(phi, S, work, bar)
        rows += r
    bar.close()

    ratios, ceilings, floors = [], [], {}
    for scene in infos:
        e = best(rows, scene, "ED")
        for conv in (False, True):
            d = best(rows, scene, "DEM", converged=conv)
            what = ("converged: it and every stiffer run with the same dt/t_c within 1 %" if conv
                    else "first run within 1 %")
            if e and d:
                ratios.append(f"{scene} ({what}): soft DEM {label(d)}, {d['cost']:.3g} s / exact ED "
                              f"{label(e)}, {e['cost']:.3g} s = **{d['cost'] / e['cost']:.0f}**")
                key = (infos[scene]["N"], infos[scene]["phi"])
                if key not in floors:
                    floors[key] = core_floor(*key, size)
                if floors[key]:
                    ceilings.append(ceiling(scene, d, infos[scene], floors[key]) + f" ({what})")
            elif e:
                ratios.append(f"{scene} ({what}): no soft DEM run with T_tr within 1 % (and error bar "
                              f"<= 0.7 %); exact ED {label(e)}: {e['cost']:.3g} s")

    csv_path = os.path.join(a.out, "speed_accuracy.csv")
    cli.write_rows(csv_path, rows, "{:.6g}")
    md_path = os.path.join(a.out, "speed_accuracy.md")
    write_markdown(md_path, rows, infos, mapping, ratios, size, ceilings)
    png_path = os.path.join(a.out, "speed_accuracy.png")
    plot(png_path, rows, infos)
    print(open(md_path).read())
    print("\n".join(ratios))
    print("\n".join(ceilings))
    print(f"wrote {csv_path}, {md_path}, {png_path}")
    return rows, infos, mapping


if __name__ == "__main__":
    main()
