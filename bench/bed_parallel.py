# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""GRANFRIC benchmark: the vibrated bed (Risso et al. 2005, bench/in.bed) on 1, 2 and 4 MPI
ranks, unbalanced and balanced (balance before the run and fix balance every 10 steps: shift,
or rcb under comm_style tiled), in 2D and 3D. The bed fills the lower part of its box, so the
upper subdomains hold few atoms or none. Each case starts from the same equilibrated bed (a
serial warm-up, written to a restart file) and runs the same number of base periods; the cases
run in interleaved rounds and the fastest round of each counts (a shared machine only ever adds
time). Each rank count runs on LAMMPS's own processor grid (auto) and with the ranks stacked
along the vertical (vertical: the upper ranks hold little of the bed, the case balancing is for). Printed per case: the LAMMPS loop time per base period, the speed-up over 1 rank and the
efficiency (speed-up per core used: ranks beyond the machine's cores share them), the copies
per step, the windows with a conflict and the collisions. Every case must give the serial
collision count (each rank count and balancing gives the serial trajectory bit for bit).
Writes bench/results/bed_parallel.csv and prints a markdown table. Figures measured in one run,
not a test.

    /usr/bin/python3 bench/bed_parallel.py [--dims 2 3] [--scale2 4] [--scale3 2] [--periods 300]
                                           [--warm 300] [--sub 1] [--rounds 3] [--ranks 1 2 4]

--scale2 / --scale3: the 2D box and N (1000 discs) widened by that factor, the 3D base by it
in both directions (2000 spheres times its square); --sub: time steps per base period.
"""
import argparse
import csv
import os
import re
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "tools"))
from granfric import lmp  # noqa: E402

SCENE = os.path.join(HERE, "in.bed")
BALANCE = ("none", "shift", "rcb")


def run_case(work, dim, scale, periods, sub, np_, split, balance, init):
    """One measured run from the restart file init: loop time, and the last thermo row."""
    p = lmp.run(SCENE, {"dim": dim, "scale": scale, "periods": periods, "sub": sub,
                        "split": split, "balance": balance, "init": init},
                cwd=work, np=np_, log=os.devnull, quiet=False)
    out = p.stdout
    loop = float(re.findall(r"Loop time of ([0-9.eE+-]+)", out)[-1])
    head = re.findall(r"^\s*Step\s.*$", out, re.M)[-1].split()
    rows = [l.split() for l in out.splitlines() if re.match(r"^\s*\d+\s+[-0-9.eE+]+\s", l)]
    last = dict(zip(head, rows[-1]))
    return dict(loop=loop, collisions=int(float(last["f_ed[2]"])),
                conflicts=float(last["f_ed[14]"]), redone=float(last["f_ed[15]"]),
                copies=float(last["f_ed[21]"]))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--dims", type=int, nargs="+", default=[2, 3])
    ap.add_argument("--scale2", type=int, default=4)
    ap.add_argument("--scale3", type=int, default=2)
    ap.add_argument("--periods", type=int, default=300)
    ap.add_argument("--warm", type=int, default=300)
    ap.add_argument("--sub", type=int, default=1)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2, 4])
    a = ap.parse_args(argv)
    cores = os.cpu_count() or 1
    # (ranks, split, balance): LAMMPS's grid, and the ranks stacked along the vertical
    cases = [(n, sp, b) for n in a.ranks for sp in (("auto",) if n == 1 else ("auto", "vertical"))
             for b in (("none",) if n == 1 else BALANCE)]
    results = []
    with tempfile.TemporaryDirectory() as work:
        for dim in a.dims:
            scale = a.scale2 if dim == 2 else a.scale3
            init = f"bed{dim}_restart"    # (the input compares it as a word)
            lmp.run(SCENE, {"dim": dim, "scale": scale, "periods": a.warm, "sub": 1,
                            "save": init}, cwd=work)
            best = {}
            for _ in range(a.rounds):
                for case in cases:
                    r = run_case(work, dim, scale, a.periods, a.sub, *case, init)
                    if case not in best or r["loop"] < best[case]["loop"]:
                        best[case] = r
            serial = best[(1, "auto", "none")]
            for n, sp, b in cases:
                r = best[(n, sp, b)]
                if r["collisions"] != serial["collisions"]:
                    raise SystemExit(f"{dim}D, {n} ranks ({sp}), {b}: {r['collisions']} collisions, "
                                     f"not the serial {serial['collisions']}")
                speedup = serial["loop"] / r["loop"]
                results.append(dict(dim=dim, N=(1000 * scale if dim == 2 else 2000 * scale * scale),
                                    ranks=n, split=sp, balance=b, ms_per_period=1e3 * r["loop"] / a.periods,
                                    speedup=speedup, efficiency=speedup / min(n, cores),
                                    copies=r["copies"], conflict_windows=r["redone"],
                                    collisions=r["collisions"]))
    os.makedirs(os.path.join(HERE, "results"), exist_ok=True)
    with open(os.path.join(HERE, "results", "bed_parallel.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(results[0]))
        w.writeheader()
        w.writerows(results)
    print(f"{a.periods} base periods after {a.warm} of warm-up, {a.sub} step(s) per period, "
          f"fastest of {a.rounds} interleaved rounds, {cores} cores")
    print("| dim | N | ranks | grid | balance | ms / period | speed-up | efficiency | copies / step | "
          "windows repaired | collisions |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in results:
        print(f"| {r['dim']}D | {r['N']} | {r['ranks']} | {r['split']} | {r['balance']} | {r['ms_per_period']:.3f} | "
              f"{r['speedup']:.2f} | {r['efficiency']:.2f} | {r['copies']:.0f} | "
              f"{r['conflict_windows']:.0f} | {r['collisions']} |")


if __name__ == "__main__":
    main()
