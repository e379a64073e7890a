# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Soak: long runs of fix hardsphere/ed, serial and on 2 MPI ranks, checked for lost atoms,
overlaps and the energy books (bench/in.soak has the scenes).

    bench/soak [--ranks 1 2] [--scale S] [--keep DIR]

Checks after every `every` steps of each run:
  atoms     the number of atoms never changes;
  overlaps  no two atoms closer than their contact distance, less 1e-9 of it (periodic images
            included), and no atom through a wall (the base counted at its lowest point);
  books     E_tr + E_rot + E_grav - (their start value) = injected - dissipated, to 1e-9 of the
            energy turned over (start energy + injected + |dissipated|).
The runs must together reach 2e7 collisions on each rank count (times --scale). The table lists
per run the collisions, the process CPU time (all ranks), the worst book residual and the
smallest gap between atoms (in contact distances). Exit status 1 if a check fails."""
import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np
from scipy.spatial import cKDTree

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "tools"))
from granfric import lammpslog  # noqa: E402

LMP = os.path.join(ROOT, "tools", "lmp")
INPUT = os.path.join(HERE, "in.soak")
TARGET = 2e7    # collisions per rank count
# scene: steps, dump interval, box (lo, hi per dimension), periodic, walls (x lo, x hi, y lo, y hi)
SCENES = {
    "driven": dict(steps=7000, every=700, lo=(0.0, 0.0), periodic=True),
    "vibrated": dict(steps=10000, every=1000, lo=(0.0, -0.1), periodic=False,
                     walls=(0.0, 60.0, -0.1, 150.0)),
}
TOL = 1e-9


def read_dumps(path):
    """Snapshots of a dump file: list of (box lo, box hi, array id radius x y ix iy)."""
    snaps = []
    with open(path) as f:
        lines = f.read().splitlines()
    k = 0
    while k < len(lines):
        assert lines[k].startswith("ITEM: TIMESTEP"), lines[k]
        n = int(lines[k + 3])
        lo, hi = zip(*(map(float, lines[k + 5 + d].split()[:2]) for d in range(2)))
        rows = np.array([l.split() for l in lines[k + 9:k + 9 + n]], dtype=float)
        snaps.append((np.array(lo), np.array(hi), rows))
        k += 9 + n
    return snaps


def smallest_gap(lo, hi, rows, periodic, walls):
    """The smallest pair distance over the contact distance, and the deepest wall overlap."""
    r, xy = rows[:, 1], rows[:, 2:4] - lo
    L = hi - lo
    if periodic:
        xy = np.mod(xy, L)
        xy[xy >= L] = 0.0
    tree = cKDTree(xy, boxsize=L if periodic else None)
    pairs = tree.query_pairs(4.0 * r.max(), output_type="ndarray")    # (contacts and near ones)
    gap = np.inf
    if len(pairs):
        d = xy[pairs[:, 0]] - xy[pairs[:, 1]]
        if periodic:
            d -= L * np.round(d / L)
        gap = (np.hypot(d[:, 0], d[:, 1]) / (r[pairs[:, 0]] + r[pairs[:, 1]])).min()
    through = 0.0
    if walls:
        x, y = rows[:, 2], rows[:, 3]
        xlo, xhi, ylo, yhi = walls
        through = max(0.0, (xlo - (x - r)).max(), ((x + r) - xhi).max(), (ylo - (y - r)).max(),
                      ((y + r) - yhi).max())
    return gap, through


def run(work, scene, ranks, scale):
    s = SCENES[scene]
    steps = max(s["every"], int(round(s["steps"] * scale / s["every"])) * s["every"])
    log, dump = f"log.{scene}.np{ranks}", f"{scene}.np{ranks}.dump"
    cmd = [LMP] + (["-np", str(ranks)] if ranks > 1 else []) + [
        "-in", INPUT, "-log", log, "-screen", "none", "-var", "scene", scene, "-var", "steps",
        str(steps), "-var", "every", str(s["every"]), "-var", "out", dump]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.monotonic()
    p = subprocess.run(cmd, cwd=work, capture_output=True, text=True)
    wall = time.monotonic() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        return dict(scene=scene, ranks=ranks, fail=["the run failed: " + (p.stdout + p.stderr)[-1500:]])
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    th = lammpslog.read_thermo(os.path.join(work, log))
    E, inj, diss, atoms = th["v_E"], th["f_ed[9]"], th["f_ed[3]"], th["Atoms"]
    turnover = abs(E[0]) + np.abs(inj) + np.abs(diss)
    books = np.abs((E - E[0]) - (inj - diss)) / turnover
    gaps = [smallest_gap(lo, hi, rows, s["periodic"], s.get("walls"))
            for lo, hi, rows in read_dumps(os.path.join(work, dump))]
    res = dict(scene=scene, ranks=ranks, steps=steps, collisions=th["f_ed[2]"][-1], cpu=cpu,
               wall=wall, books=books.max(), gap=min(g for g, _ in gaps),
               through=max(t for _, t in gaps), snapshots=len(gaps), fail=[])
    if not np.all(atoms == atoms[0]):
        res["fail"].append(f"atoms lost: {atoms[0]:.0f} -> {atoms.min():.0f}")
    if not res["books"] <= TOL:
        res["fail"].append(f"energy books off by {res['books']:.3g} of the turnover")
    if not res["gap"] >= 1.0 - TOL:
        res["fail"].append(f"atoms overlap: a pair at {res['gap']:.12g} of its contact distance")
    if not res["through"] <= TOL:
        res["fail"].append(f"an atom reaches {res['through']:.3g} through a wall")
    if len(gaps) != steps // s["every"] + 1:
        res["fail"].append(f"{len(gaps)} snapshots in the dump, expected {steps // s['every'] + 1}")
    return res


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2], help="MPI rank counts (default 1 2)")
    ap.add_argument("--scale", type=float, default=1.0,
                    help="run length relative to the full soak (default 1: 2e7 collisions per rank count)")
    ap.add_argument("--keep", help="run in this folder and keep its logs and dumps")
    a = ap.parse_args()
    work = a.keep or tempfile.mkdtemp(prefix="granfric-soak-")
    os.makedirs(work, exist_ok=True)
    print(f"{'scene':9s} {'ranks':>5s} {'steps':>6s} {'collisions':>11s} {'CPU s':>7s} "
          f"{'coll/CPU s':>10s} {'books':>9s} {'min gap':>14s}  result")
    failed = False
    for ranks in a.ranks:
        total = 0.0
        for scene in SCENES:
            r = run(work, scene, ranks, a.scale)
            if "collisions" in r:
                total += r["collisions"]
                print(f"{scene:9s} {ranks:5d} {r['steps']:6d} {r['collisions']:11.4g} {r['cpu']:7.1f} "
                      f"{r['collisions'] / r['cpu']:10.3g} {r['books']:9.2g} {r['gap']:14.12f}  "
                      + ("PASS" if not r["fail"] else "FAIL"))
            for f in r["fail"]:
                print(f"  {scene} on {ranks} rank(s): {f}")
            failed = failed or bool(r["fail"])
        if total < TARGET * a.scale:
            print(f"  {total:.4g} collisions on {ranks} rank(s), fewer than {TARGET * a.scale:.4g}")
            failed = True
    print(("FAILED" if failed else "PASSED") + f": soak of {len(SCENES)} scenes on {a.ranks} rank(s)"
          + (f" (logs and dumps in {work})" if a.keep else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
