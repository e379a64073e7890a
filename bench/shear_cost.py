# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""What a sheared box costs per collision against the same scene unsheared: bench/in.speed with
and without -var shear S (Lees-Edwards through fix deform), 2D and 3D, in interleaved rounds;
whole-process CPU time (user + sys) per collision of the whole run (equilibration included),
the fastest of the rounds, and the ratio sheared / unsheared of the fastest, and the median of
the ratios within a round (the two runs of a round side by side, on a machine whose speed
drifts). With --callgrind the instructions
of the whole process instead (valgrind, one round: reproducible, slow).

    /usr/bin/python3 bench/shear_cost.py [--dims 2 3] [--nside2 316] [--nside3 46] [--shear 0.05]
                                         [--ncoll 10] [--rounds 3] [--callgrind]

Writes bench/results/shear_cost.csv."""
import argparse
import csv
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def run(dim, nside, shear, ncoll, callgrind):
    """one in.speed run: (collisions of the whole run, CPU seconds or instructions)"""
    build = os.environ.get("GRANFRIC_BUILD", os.path.join(ROOT, "build"))
    cmd = [os.path.join(build, "lammps", "lmp"), "-in", os.path.join(HERE, "in.speed"), "-log", "none",
           "-var", "dim", str(dim), "-var", "nside", str(nside), "-var", "ncoll", str(ncoll),
           "-var", "shear", str(shear)]
    env = dict(os.environ, LAMMPS_PLUGIN_PATH=os.path.join(build, "plugins"), OMP_NUM_THREADS="1")
    with tempfile.TemporaryDirectory() as work:
        if callgrind:
            out = os.path.join(work, "cg.out")
            cmd = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}"] + cmd
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        p = subprocess.run(cmd, cwd=work, env=env, capture_output=True, text=True)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        if p.returncode != 0:
            sys.exit(f"in.speed failed ({' '.join(cmd)}):\n{p.stdout[-2000:]}{p.stderr[-2000:]}")
        total = int(re.search(r"BENCH .* total (\d+)", p.stdout).group(1))
        if callgrind:
            cost = int(re.search(r"Collected : (\d+)", p.stderr).group(1))
        else:
            cost = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return total, cost


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dims", type=int, nargs="+", default=[2, 3])
    ap.add_argument("--nside2", type=int, default=316)
    ap.add_argument("--nside3", type=int, default=46)
    ap.add_argument("--shear", type=float, default=0.05)
    ap.add_argument("--ncoll", type=int, default=10)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--callgrind", action="store_true")
    a = ap.parse_args(argv)
    rounds = 1 if a.callgrind else a.rounds
    best, each = {}, {}
    for r in range(rounds):
        for dim in a.dims:
            nside = a.nside2 if dim == 2 else a.nside3
            for shear in (0.0, a.shear):
                total, cost = run(dim, nside, shear, a.ncoll, a.callgrind)
                per = cost / total
                key = (dim, shear)
                each.setdefault(key, []).append(per)
                if key not in best or per < best[key][2]:
                    best[key] = (nside ** dim, total, per)
                print(f"round {r + 1} dim {dim} N {nside ** dim} shear {shear}: {total} collisions, "
                      f"{per:.4g} {'instructions' if a.callgrind else 'CPU s'} per collision", flush=True)
    unit = "instructions" if a.callgrind else "CPU us"
    scale = 1.0 if a.callgrind else 1e6
    rows = []
    print(f"\n| dim | N | collisions unsheared / sheared | {unit} per collision unsheared / sheared | "
          f"sheared / unsheared | median of the rounds' ratios |\n|---|---|---|---|---|---|")
    for dim in a.dims:
        n, c0, p0 = best[(dim, 0.0)]
        _, c1, p1 = best[(dim, a.shear)]
        med = statistics.median(b / u for u, b in zip(each[(dim, 0.0)], each[(dim, a.shear)]))
        rows.append({"dim": dim, "N": n, "shear": a.shear, "collisions_unsheared": c0, "collisions_sheared": c1,
                     "cost_unsheared": p0 * scale, "cost_sheared": p1 * scale, "ratio": p1 / p0,
                     "ratio_median": med, "unit": unit})
        print(f"| {dim} | {n} | {c0} / {c1} | {p0 * scale:.4g} / {p1 * scale:.4g} | x{p1 / p0:.2f} | x{med:.2f} |")
    os.makedirs(os.path.join(HERE, "results"), exist_ok=True)
    with open(os.path.join(HERE, "results", "shear_cost.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
