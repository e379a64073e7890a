# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Cost per base period of the 3D vibrated bed (in.convection3d, its default scene) on 1 and 2
MPI ranks. A serial warm-up of --warm periods writes a restart file; every case then runs
--periods periods from it. The cases run in interleaved rounds (1 rank, 2 ranks, ..., again) and
the fastest round of each counts: a shared machine only ever adds time. Per case: the LAMMPS
loop time (wall) per period, the CPU time per period summed over the ranks (loop time times
LAMMPS's "% CPU use", the mean over the ranks, times the ranks), the speed-up over 1 rank, the
copies per step (f_ed[21]) and the collisions per period. Every case must give the serial
collision count: from one restart file every rank count and mode follows the serial trajectory
bit for bit.

    /usr/bin/python3 examples/convection3d/cost.py [--periods 300] [--warm 1000] [--rounds 3]

Cases: 1 rank; 2 ranks with fix hardsphere/ed parallel domain (the default) on LAMMPS's own
grid (the input's default: it cuts the tall box at half height, above most of the bed); the
same with cuts along gravity only (grid across, processors * * 1: each rank gets half the
base); 2 ranks parallel gather on LAMMPS's grid.
"""
import argparse
import os
import re
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "tools"))
from granfric import lmp  # noqa: E402

SCENE = os.path.join(HERE, "in.convection3d")
CASES = [(1, "auto", "domain"), (2, "auto", "domain"), (2, "across", "domain"),
         (2, "auto", "gather")]


def measure(work, periods, np_, grid, parallel, init):
    p = lmp.run(SCENE, {"periods": periods, "every": periods, "grid": grid,
                        "parallel": parallel, "init": init},
                cwd=work, np=np_, log=os.devnull, quiet=False)
    out = p.stdout
    loop = float(re.findall(r"Loop time of ([0-9.eE+-]+)", out)[-1])
    cpu = float(re.findall(r"([0-9.]+)% CPU use", out)[-1]) / 100.0
    grid_line = re.findall(r"(\d+ by \d+ by \d+) MPI processor grid", out)
    head = re.findall(r"^\s*Step\s.*$", out, re.M)[-1].split()
    rows = [l.split() for l in out.splitlines() if re.match(r"^\s*\d+\s+[-0-9.eE+]+\s", l)]
    first, last = dict(zip(head, rows[0])), dict(zip(head, rows[-1]))
    return dict(loop=loop, cpu=loop * cpu * np_,
                grid=grid_line[-1] if grid_line else "1 by 1 by 1",
                collisions=int(float(last["f_ed[2]"])) - int(float(first["f_ed[2]"])))


def measure_copies(work, np_, grid, parallel, init):
    """Mean of f_ed[21] (copies simulated in a step, summed over the ranks) over 20 steps from
    the restart file (a copy of the input with f_ed[21] added to its thermo output; not timed)."""
    src = open(SCENE).read().replace("f_ed[2] f_ed[10] f_ed[7]", "f_ed[2] f_ed[10] f_ed[7] f_ed[21]")
    scene = os.path.join(work, "in.copies")
    with open(scene, "w") as f:
        f.write(src)
    p = lmp.run(scene, {"periods": 20, "every": 1, "grid": grid, "parallel": parallel,
                        "init": init}, cwd=work, np=np_, log=os.devnull, quiet=False)
    head = re.findall(r"^\s*Step\s.*$", p.stdout, re.M)[-1].split()
    rows = [dict(zip(head, l.split())) for l in p.stdout.splitlines()
            if re.match(r"^\s*\d+\s+[-0-9.eE+]+\s", l)]
    vals = [float(r["f_ed[21]"]) for r in rows[1:]]
    return sum(vals) / len(vals)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--periods", type=int, default=300)
    ap.add_argument("--warm", type=int, default=1000)
    ap.add_argument("--rounds", type=int, default=3)
    a = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as work:
        init = "bed3d_restart"    # (the input compares it as a word)
        lmp.run(SCENE, {"periods": a.warm, "every": a.warm, "save": init}, cwd=work)
        best = {}
        for _ in range(a.rounds):
            for case in CASES:
                r = measure(work, a.periods, *case, init)
                if case not in best or r["loop"] < best[case]["loop"]:
                    best[case] = r
        for case in CASES:
            best[case]["copies"] = measure_copies(work, *case, init) if case[0] > 1 else 0.0
    serial = best[CASES[0]]
    for case in CASES:
        if best[case]["collisions"] != serial["collisions"]:
            raise SystemExit(f"{case}: {best[case]['collisions']} collisions, not the serial "
                             f"{serial['collisions']}")
    print(f"{a.periods} base periods after {a.warm} of warm-up (N = 6000, kappa = 0.03), fastest "
          f"of {a.rounds} interleaved rounds, {os.cpu_count()} cores")
    print("| ranks | grid | parallel | wall ms / period | CPU ms / period | speed-up | "
          "copies / step | collisions / period |")
    print("|---|---|---|---|---|---|---|---|")
    for case in CASES:
        r = best[case]
        print(f"| {case[0]} | {r['grid']} ({case[1]}) | {case[2] if case[0] > 1 else '-'} | "
              f"{1e3 * r['loop'] / a.periods:.2f} | {1e3 * r['cpu'] / a.periods:.2f} | "
              f"{serial['loop'] / r['loop']:.2f} | {r['copies']:.0f} | "
              f"{r['collisions'] / a.periods:.0f} |")


if __name__ == "__main__":
    main()
