# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""GRANFRIC benchmark: strong scaling of fix hardsphere/ed over MPI ranks (parallel domain),
2D elastic discs at area fractions 0.05 and 0.3, N = 10^4 ... 10^6, steps of 1 ... 8 mean
free times. For each case: CPU time per collision on 1 and 2 ranks (LAMMPS loop time), the
speedup and parallel efficiency, the conflict rate (windows with a conflict, repaired, per
window) and the communication per window (doubles received per rank). Figures measured in one
run, not a test. Writes bench/results/mpi_scaling.csv and prints a markdown table.

    /usr/bin/python3 bench/mpi_scaling.py [--quick | --full] [--ranks 2] [--repeat K] [--n NSIDE]
    /usr/bin/python3 bench/mpi_scaling.py --callgrind [--ranks 2]
    /usr/bin/python3 bench/mpi_scaling.py --comm [--ranks 2 4 8 16] [--n NSIDE] [--dt DT]
    /usr/bin/python3 bench/mpi_scaling.py --conflicts [--ranks 4 16 64] [--n NSIDE] [--dt DT ...]
                                          [--phi PHI ...] [--ncoll C]

--callgrind: the efficiency from instruction counts instead (N = 99856), for the whole short
run and for its steady state (see callgrind_table); MPI's waiting and the serial run's
prefetching are not counted (see work_instructions).

--comm: what parallel domain exchanges as the rank count grows (ranks oversubscribed on this
machine's cores; a short run of 2 collisions per particle after 2 of equilibration, N = 632^2 =
399424 by default, fraction 0.3, a step of one mean free time): per rank count the processor
grid, the doubles received per rank per window and their ratio to the first rank count's, the
same ratio of the subdomains' boundary length per rank (the surface model: a rank receives the
atoms of the shell around its subdomain), the conflicts and the windows redone, and LAMMPS's
peak memory per rank. Writes
bench/results/mpi_comm.csv.

--conflicts: how often a window needs a repair, against the rank count, the fraction and the
step (ranks oversubscribed; C collisions per particle, default 10, after 2 of equilibration;
defaults N = 632^2, fractions 0.05 and 0.3, steps of 0.5, 1 and 2 mean free times, 4, 16 and
64 ranks). A conflict arises where a chain of collisions crosses a subdomain boundary from
beyond the shell, so the model is a rate per unit length of boundary: a window needs a repair
with probability q = 1 - exp(-lambda B), B the total length of the boundaries between
subdomains (in diameters). lambda is fitted per fraction and step over the rank counts, and
the table gives q and the expected rounds per window at 10^3 ranks (a 32 x 32 grid) for
N = 10^6 and 10^9 at the same fraction. Writes bench/results/mpi_conflicts.csv.

--repeat K (default 3): each case runs K times on 1 and on several ranks, interleaved, and the
efficiency is taken from the fastest run of each (a shared machine only ever adds time, and two
ranks on two cores suffer most from it); the table also gives the spread of the per-round
efficiencies. --n 316 restricts the cases to one system size (N = 316^2).
"""
import argparse
import math
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "tools"))
from granfric import cli, lmp  # noqa: E402


def run_callgrind(nside, phi, dtmft, ncoll, np_, work):
    """Instructions executed inside fix hardsphere/ed (its window, MPI calls included) per
    rank, counted by callgrind: reproducible on a shared machine. Returns (collisions, list of
    instruction counts per rank)."""
    import glob
    import subprocess
    env = dict(os.environ)
    paths = {}
    with open(os.path.join(lmp.ROOT, "build", "granfric-paths.sh")) as f:
        for line in f:
            k, _, v = line.strip().partition("=")
            paths[k] = v.strip("'")
    env["LAMMPS_PLUGIN_PATH"] = paths["GRANFRIC_PLUGIN_DIR"]
    for old in glob.glob(os.path.join(work, "cg.out.*")):
        os.remove(old)
    cmd = ["mpirun", "--oversubscribe", "-np", str(np_)]
    if os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    cmd += ["valgrind", "--tool=callgrind", "--toggle-collect=*FixHardsphereED::initial_integrate*",
            "--callgrind-out-file=" + os.path.join(work, "cg.out.%q{OMPI_COMM_WORLD_RANK}"), paths["GRANFRIC_LMP"],
            "-in", os.path.join(HERE, "in.speed"), "-log", "none", "-var", "dim", "2",
            "-var", "nside", str(nside), "-var", "phi", str(phi), "-var", "dtmft", str(dtmft),
            "-var", "ncoll", str(ncoll), "-var", "neq", "1"]
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if p.returncode != 0:
        raise RuntimeError(p.stderr[-2000:])
    b = re.search(r"BENCH dim 2 N (\d+) .* collisions (\d+)", p.stdout)
    ir = []
    for path in sorted(glob.glob(os.path.join(work, "cg.out.*")), key=lambda f: f.rsplit(".", 1)[1]):
        ir.append(work_instructions(path))
    return int(b.group(1)), int(b.group(2)), ir


MPI_LIBS = ("libmpi", "libopen-pal", "libopen-rte", "mca_", "libucp", "libuct", "libucs",
            "libpmix", "libevent", "libhwloc", "libfabric", "libpsm")


# the event loop asking the memory for the records of events to come (EDCore::
# prefetch_upcoming and what it calls): from 5 MiB of records (EDOptions::prefetch_bytes), so a
# serial run of N = 99856 does it and so does a rank's half; it buys time, not work, and
# counting it would weigh the two runs unequally
PREFETCH = ("EDCore::prefetch_around", "EDCore::prefetch_upcoming", "EventQueue::prefetch")


def work_instructions(path):
    """Instructions of a callgrind profile outside the MPI libraries and the prefetching:
    waiting for another rank spins inside MPI (busy polling), which is idle time, not work."""
    import subprocess
    out = subprocess.run(["callgrind_annotate", "--inclusive=no", "--threshold=100", path],
                         capture_output=True, text=True).stdout
    total = 0
    for line in out.splitlines():
        m = re.match(r"\s*([0-9,]+)\s+\([ 0-9.]+%\)\s+(.*)$", line)
        if not m or "PROGRAM TOTALS" in line:
            continue
        obj = re.search(r"\[([^\]]*)\]\s*$", m.group(2))
        if obj and any(k in obj.group(1) for k in MPI_LIBS):
            continue
        if any(k in m.group(2) for k in PREFETCH):
            continue
        total += int(m.group(1).replace(",", ""))
    return total


def run(nside, phi, dtmft, ncoll, np_, parallel="domain"):
    p = lmp.run(os.path.join(HERE, "in.speed"), {"dim": 2, "nside": nside, "phi": phi,
                                                   "dtmft": dtmft, "ncoll": ncoll,
                                                   "parallel": parallel},
                np=np_, log=os.devnull, quiet=False)
    out = p.stdout
    loop = [float(m) for m in re.findall(r"Loop time of ([0-9.eE+-]+)", out)][-1]
    b = re.search(r"BENCH dim 2 N (\d+) .* collisions (\d+)", out)
    par = parallel_line(out)
    return dict(par, N=int(b.group(1)), collisions=int(b.group(2)), loop=loop)


def parallel_line(out):
    """The PARALLEL line of in.speed: windows, copies in conflict, windows repaired (or redone
    gathered), doubles received, repair rounds, windows redone by single ranks in them,
    windows redone gathered, copies simulated by all ranks in the last window."""
    m = re.search(r"PARALLEL windows (\S+) conflicts (\S+) redone (\S+) comm (\S+) rounds (\S+) "
                  r"ranks_redone (\S+) gathered (\S+) copies (\S+)", out)
    keys = ("windows", "conflicts", "redone", "comm", "rounds", "ranks_redone", "gathered", "copies")
    return {k: float(v) for k, v in zip(keys, m.groups())}


def comm_table(ranks, nside, dtmft, phi=0.3):
    """The exchange of parallel domain against the rank count (see --comm)."""
    rows = []
    for np_ in cli.progress(ranks, "ranks"):
        p = lmp.run(os.path.join(HERE, "in.speed"), {"dim": 2, "nside": nside, "phi": phi,
                                                       "dtmft": dtmft, "ncoll": 2, "neq": 2},
                    np=np_, log=os.devnull, quiet=False)
        out = p.stdout
        grid = re.findall(r"(\d+) by (\d+) by (\d+) MPI processor grid", out)[-1]
        par = parallel_line(out)
        mem = [float(m) for m in re.findall(r"Per MPI rank memory allocation \(min/avg/max\) = "
                                            r"[0-9.]+ \| [0-9.]+ \| ([0-9.]+) Mbytes", out)]
        b = re.search(r"BENCH dim 2 N (\d+) .* collisions (\d+)", out)
        N = int(b.group(1))
        windows = max(par["windows"], 1.0)
        rows.append({"ranks": np_, "grid": "x".join(grid[:2]), "N": N,
                     "windows": windows, "conflicts": par["conflicts"],
                     "redone": par["redone"], "rounds": par["rounds"],
                     "ranks_per_round": par["ranks_redone"] / max(par["rounds"], 1.0),
                     "gathered": par["gathered"],
                     "collisions_per_rank_per_window": int(b.group(2)) / windows / np_,
                     "copies_per_owned_atom": par["copies"] / N,
                     "doubles_per_rank_per_window": par["comm"] / windows / np_,
                     "peak_MB_per_rank": max(mem) if mem else float("nan")})
    # the surface model: a rank receives the atoms within the shell around its subdomain,
    # so the data per rank follows the length of the subdomain's boundary with other
    # subdomains (2D, square box; a dimension split into one part has no boundary)
    for x in rows:
        px, py = (int(v) for v in x["grid"].split("x"))
        x["boundary_per_rank_over_L"] = (2.0 / py if px > 1 else 0.0) + (2.0 / px if py > 1 else 0.0)
    base = rows[0]["doubles_per_rank_per_window"]
    bound0 = rows[0]["boundary_per_rank_over_L"]
    path = cli.write_rows(os.path.join(HERE, "results", "mpi_comm.csv"), rows)
    print(f"N = {rows[0]['N']}, fraction {phi}, steps of {dtmft} mean free times")
    print(f"| ranks | grid | windows | copies in conflict | windows repaired | rounds | ranks redone "
          f"per round | gathered | collisions per rank per window | copies per owned atom | doubles "
          f"received per rank per window | against {rows[0]['ranks']} ranks | the boundary model's "
          f"ratio | peak memory per rank (MB) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for x in rows:
        print(f"| {x['ranks']} | {x['grid']} | {x['windows']:.0f} | {x['conflicts']:.0f} | "
              f"{x['redone']:.0f} | {x['rounds']:.0f} | {x['ranks_per_round']:.1f} | "
              f"{x['gathered']:.0f} | {x['collisions_per_rank_per_window']:.0f} | "
              f"{x['copies_per_owned_atom']:.3f} | "
              f"{x['doubles_per_rank_per_window']:.0f} | "
              f"{x['doubles_per_rank_per_window'] / base:.2f} | "
              f"{x['boundary_per_rank_over_L'] / bound0:.2f} | {x['peak_MB_per_rank']:.1f} |")
    print(f"\nwritten {path}")


def boundary_length(grid, nside, phi):
    """Total length of the boundaries between subdomains (diameters) of a square periodic box of
    nside^2 discs at area fraction phi split px x py: px vertical and py horizontal lines of the
    box's length (none in a direction split into one part)."""
    px, py = (int(v) for v in grid.split("x"))
    L = nside * math.sqrt(math.pi / (4.0 * phi))
    return L * ((px if px > 1 else 0) + (py if py > 1 else 0))


def conflict_table(ranks, nside, dts, phis, ncoll):
    """Windows repaired against rank count, fraction and step, and the boundary-rate model."""
    rows = []
    cases = [(phi, dt, np_) for phi in phis for dt in dts for np_ in ranks]
    for phi, dt, np_ in cli.progress(cases, "conflicts"):
        p = lmp.run(os.path.join(HERE, "in.speed"), {"dim": 2, "nside": nside, "phi": phi,
                                                       "dtmft": dt, "ncoll": ncoll, "neq": 2},
                    np=np_, log=os.devnull, quiet=False)
        out = p.stdout
        grid = "x".join(re.findall(r"(\d+) by (\d+) by (\d+) MPI processor grid", out)[-1][:2])
        par = parallel_line(out)
        B = boundary_length(grid, nside, phi)
        rows.append({"phi": phi, "dtmft": dt, "ranks": np_, "grid": grid, "windows": par["windows"],
                     "repaired": par["redone"], "gathered": par["gathered"],
                     "rounds_per_repair": par["rounds"] / max(par["redone"], 1.0),
                     "ranks_per_round": par["ranks_redone"] / max(par["rounds"], 1.0),
                     "boundary": B, "lambda": -math.log(max(1.0 - par["redone"] / par["windows"], 1e-12)) / B})
    path = cli.write_rows(os.path.join(HERE, "results", "mpi_conflicts.csv"), rows)
    print(f"N = {nside}^2, {ncoll} collisions per particle; lambda: repairs per window per diameter "
          f"of boundary")
    print("| fraction | step (mft) | ranks (grid) | windows | repaired | gathered | rounds per repair | "
          "ranks redone per round | boundary (diameters) | lambda |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for x in rows:
        print(f"| {x['phi']} | {x['dtmft']} | {x['ranks']} ({x['grid']}) | {x['windows']:.0f} | "
              f"{x['repaired']:.0f} | {x['gathered']:.0f} | {x['rounds_per_repair']:.2f} | "
              f"{x['ranks_per_round']:.1f} | {x['boundary']:.0f} | {x['lambda']:.2e} |")
    print("\nfitted lambda (pooled over the rank counts: repairs / sum of windows x boundary) and "
          "the model at 10^3 ranks (32 x 32)")
    print("| fraction | step (mft) | lambda | q at N = 10^6 | q at N = 10^9 | repairs in the runs |")
    print("|---|---|---|---|---|---|")
    for phi in phis:
        for dt in dts:
            sel = [x for x in rows if x["phi"] == phi and x["dtmft"] == dt]
            reps = sum(x["repaired"] for x in sel)
            lam = reps / sum(x["windows"] * x["boundary"] for x in sel)
            q = {n: 1.0 - math.exp(-lam * 64 * math.sqrt(n * math.pi / (4.0 * phi))) for n in (1e6, 1e9)}
            print(f"| {phi} | {dt} | {lam:.2e} | {q[1e6]:.3f} | {q[1e9]:.3f} | {reps:.0f} |")
    print(f"\nwritten {path}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--quick", action="store_true")
    g.add_argument("--full", action="store_true")
    ap.add_argument("--ranks", type=int, nargs="+", default=None,
                    help="rank count (default 2; --comm: several, default 2 4 8 16)")
    ap.add_argument("--comm", action="store_true",
                    help="data received per rank against the rank count (see above)")
    ap.add_argument("--conflicts", action="store_true",
                    help="windows repaired against rank count, fraction and step (see above)")
    ap.add_argument("--phi", type=float, nargs="+", default=None, help="--conflicts: fractions")
    ap.add_argument("--ncoll", type=float, default=10.0,
                    help="--conflicts: collisions per particle per run")
    ap.add_argument("--repeat", type=int, default=3,
                    help="interleaved runs per case; the fastest of each rank count is used")
    ap.add_argument("--n", type=int, default=0, help="only this lattice side (N = n^2)")
    ap.add_argument("--dt", type=float, nargs="+", default=None,
                    help="only these steps (mean free times)")
    ap.add_argument("--callgrind", action="store_true",
                    help="parallel efficiency from instruction counts (N = 1e5, slow but reproducible)")
    a = ap.parse_args(argv)
    if a.comm:
        return comm_table(a.ranks or [2, 4, 8, 16], a.n or 632, (a.dt or [1.0])[0])
    if a.conflicts:
        return conflict_table(a.ranks or [4, 16, 64], a.n or 632, a.dt or [0.5, 1.0, 2.0],
                              a.phi or [0.05, 0.3], a.ncoll)
    a.ranks = (a.ranks or [2])[0]
    if a.callgrind:
        return callgrind_table(a.ranks)
    if a.quick:
        cases = [(100, phi, dt) for phi in (0.05, 0.3) for dt in (1, 4)]
    elif a.full:
        cases = [(n, phi, dt) for n in (100, 316, 1000) for phi in (0.05, 0.3) for dt in (1, 2, 4, 8)]
    else:
        cases = [(n, phi, dt) for n in (100, 316) for phi in (0.05, 0.3) for dt in (1, 2, 4, 8)]
    if a.n:
        cases = [c for c in cases if c[0] == a.n] or [(a.n, phi, dt) for phi in (0.05, 0.3) for dt in (0.5, 1, 2)]
    if a.dt:
        sides = sorted({c[0] for c in cases})
        cases = [(n, phi, dt) for n in sides for phi in (0.05, 0.3) for dt in a.dt]
    rows = []
    for nside, phi, dt in cli.progress(cases, "scaling"):
        ncoll = 10 if nside >= 316 else 20
        # interleaved: a slow spell of the machine then hits both rank counts alike
        t1, tp, effs = [], [], []
        for _ in range(max(1, a.repeat)):
            one = run(nside, phi, dt, ncoll, 1)
            par = run(nside, phi, dt, ncoll, a.ranks)
            t1.append(one["loop"] / one["collisions"])
            tp.append(par["loop"] / par["collisions"])
            effs.append(t1[-1] / tp[-1] / a.ranks)
        speedup = min(t1) / min(tp)
        rows.append({"N": one["N"], "phi": phi, "dt_mft": dt,
                     "us_per_coll_1": 1e6 * min(t1),
                     f"us_per_coll_{a.ranks}": 1e6 * min(tp),
                     "speedup": speedup, "efficiency": speedup / a.ranks,
                     "efficiency_rounds_min": min(effs), "efficiency_rounds_max": max(effs),
                     "repeats": len(effs),
                     "windows": par["windows"], "redone_fraction": par["redone"] / max(par["windows"], 1),
                     "conflicts_per_window": par["conflicts"] / max(par["windows"], 1),
                     "comm_doubles_per_window_per_rank": par["comm"] / max(par["windows"], 1) / a.ranks,
                     "comm_per_particle": par["comm"] / max(par["windows"], 1) / a.ranks / one["N"]})
    path = cli.write_rows(os.path.join(HERE, "results", "mpi_scaling.csv"), rows)
    r = a.ranks
    print(f"| N | fraction | dt (mean free times) | us/collision 1 rank (fastest) | us/collision {r} "
          f"ranks (fastest) | efficiency | per-round efficiencies | windows redone | doubles received "
          f"per rank per window (per particle) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for x in rows:
        print(f"| {x['N']} | {x['phi']} | {x['dt_mft']} | {x['us_per_coll_1']:.2f} | "
              f"{x[f'us_per_coll_{r}']:.2f} | {100 * x['efficiency']:.0f} % | "
              f"{100 * x['efficiency_rounds_min']:.0f}-{100 * x['efficiency_rounds_max']:.0f} % "
              f"({x['repeats']}) | "
              f"{100 * x['redone_fraction']:.1f} % | {x['comm_doubles_per_window_per_rank']:.0f} "
              f"({x['comm_per_particle']:.2f}) |")
    print(f"\nwritten {path}")


def callgrind_table(ranks, ncoll=10):
    """Instructions per collision on 1 and `ranks` ranks, N = 316^2, ncoll collisions per
    particle timed (about ncoll / dt windows after one equilibration window). Each run also
    pays once for its starts (the equilibration run's and the timed run's: cells, predictions,
    the overlap check), which a long run spreads over many more collisions; the steady-state
    columns take the difference of a run with 2 * ncoll and one with ncoll collisions per
    particle, which cancels those one-off costs."""
    import tempfile
    work = tempfile.mkdtemp(prefix="granfric_cg_")
    print(f"| N | fraction | dt (mean free times) | instructions/collision 1 rank | busiest of {ranks} "
          "ranks (MPI waiting excluded) | efficiency (instructions) | steady state: 1 rank | "
          f"busiest of {ranks} | steady-state efficiency |")
    print("|---|---|---|---|---|---|---|---|---|")
    for phi, dt in ((0.3, 1), (0.3, 2), (0.05, 0.5), (0.05, 1), (0.05, 2)):
        N, c1, ir1 = run_callgrind(316, phi, dt, ncoll, 1, work)
        _, c2, ir2 = run_callgrind(316, phi, dt, ncoll, ranks, work)
        _, d1, jr1 = run_callgrind(316, phi, dt, 2 * ncoll, 1, work)
        _, d2, jr2 = run_callgrind(316, phi, dt, 2 * ncoll, ranks, work)
        e1, e2 = sum(ir1) / c1, max(ir2) / c2
        # per rank (files named by rank), the longer run less the shorter; the busiest rank
        s1 = (sum(jr1) - sum(ir1)) / (d1 - c1)
        s2 = max(b - a for a, b in zip(ir2, jr2)) / (d2 - c2)
        print(f"| {N} | {phi} | {dt} | {e1:.0f} | {e2:.0f} | {100 * e1 / (ranks * e2):.0f} % | "
              f"{s1:.0f} | {s2:.0f} | {100 * s1 / (ranks * s2):.1f} % |", flush=True)


if __name__ == "__main__":
    main()
