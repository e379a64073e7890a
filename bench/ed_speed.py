# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""GRANFRIC benchmark: collisions per second per core of fix hardsphere/ed through LAMMPS, for
2D and 3D, N = 10^3 ... 10^6, fractions 0.05 and 0.3, and steps of 0.1 ... 10 mean free times;
memory per particle, with the LAMMPS settings doc/fix_hardsphere_ed.rst recommends (in.speed's
default, lean = 1) and, from a short extra run of each size, with LAMMPS's defaults (lean = 0).
Prints a table and the ratios asked for (cost per collision at N = 10^6 against N = 10^3);
writes bench/results/ed_speed.csv. Not a test: figures, measured in one run.

    PYTHONPATH=tools /usr/bin/python3 bench/ed_speed.py [--quick] [--np 1]
"""
import argparse
import os
import re
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "tools"))
from granfric import cli, lmp  # noqa: E402


def run_one(dim, nside, phi, dtmft, ncoll, np_=1, lean=1, neq=5):
    t0 = time.time()
    p = lmp.run(os.path.join(HERE, "in.speed"), {"dim": dim, "nside": nside, "phi": phi,
                                                   "dtmft": dtmft, "ncoll": ncoll, "lean": lean,
                                                   "neq": neq},
                np=np_, log=os.devnull, quiet=False)
    out = p.stdout
    loop = [float(m) for m in re.findall(r"Loop time of ([0-9.eE+-]+)", out)][-1]
    bench = re.search(r"BENCH dim (\d) N (\d+) .* collisions (\d+) queue_rebuilds (\d+)", out)
    mem = re.findall(r"Per MPI rank memory allocation \(min/avg/max\) = [0-9.]+ \| ([0-9.]+)", out)
    N, coll = int(bench.group(2)), int(bench.group(3))
    return {"dim": dim, "N": N, "phi": phi, "dt_mft": dtmft, "collisions": coll,
            "seconds": loop, "coll_per_s": coll / loop / np_,
            "lammps_MB_per_rank": float(mem[-1]) if mem else float("nan"), "wall": time.time() - t0}


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="N <= 10^5, fewer steps")
    ap.add_argument("--np", type=int, default=1)
    a = ap.parse_args()
    try:
        from tqdm import tqdm
    except ImportError:
        tqdm = lambda x, **k: x
    sizes = {2: [32, 100, 316] + ([] if a.quick else [1000]), 3: [10, 22, 46] + ([] if a.quick else [100])}
    cases = []
    for dim in (2, 3):
        for nside in sizes[dim]:
            for phi in (0.05, 0.3):
                cases.append((dim, nside, phi, 1.0))
    for dtmft in (0.1, 0.3, 3.0, 10.0):
        cases.append((2, 100, 0.3, dtmft))
    rows = []
    for dim, nside, phi, dtmft in tqdm(cases, desc="benchmark runs"):
        ncoll = 10 if nside ** dim >= 10 ** 5 else 20
        r = run_one(dim, nside, phi, dtmft, ncoll, a.np)
        if dtmft == 1.0:    # memory only: a short run with LAMMPS's default settings
            d = run_one(dim, nside, phi, dtmft, 1, a.np, lean=0, neq=1)
            r["lammps_defaults_MB_per_rank"] = d["lammps_MB_per_rank"]
        else:
            r["lammps_defaults_MB_per_rank"] = float("nan")
        rows.append(r)
    path = cli.write_rows(os.path.join(HERE, "results", "ed_speed.csv"), rows)
    print("\n| dim | N | fraction | dt (mean free times) | collisions/s per core | LAMMPS MB/rank | "
          "bytes/particle | bytes/particle, LAMMPS defaults |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        dflt = r["lammps_defaults_MB_per_rank"] * 1048576 / r["N"]
        print(f"| {r['dim']} | {r['N']} | {r['phi']} | {r['dt_mft']} | {r['coll_per_s']:.3g} | "
              f"{r['lammps_MB_per_rank']:.1f} | {r['lammps_MB_per_rank'] * 1048576 / r['N']:.0f} | "
              f"{'' if dflt != dflt else f'{dflt:.0f}'} |")
    print()
    for dim in (2, 3):
        for phi in (0.05, 0.3):
            sel = [r for r in rows if r["dim"] == dim and r["phi"] == phi and r["dt_mft"] == 1.0]
            if len(sel) >= 2:
                lo, hi = sel[0], sel[-1]
                print(f"cost per collision {dim}D fraction {phi}: N={hi['N']} / N={lo['N']} = "
                      f"{lo['coll_per_s'] / hi['coll_per_s']:.2f} (target <= 1.3)")
    ref = [r for r in rows if r["dim"] == 2 and r["phi"] == 0.3 and 9000 < r["N"] < 11000]
    if ref:
        best = max(ref, key=lambda r: r["coll_per_s"])
        print(f"2D fraction 0.3 N=10^4: best {best['coll_per_s']:.3g} collisions/s per core at dt = "
              f"{best['dt_mft']} mean free times (target >= 1e6)")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
