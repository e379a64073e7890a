# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""GRANFRIC against the fastest stand-alone event-driven code for hard spheres, side by side.

The peer is Smallenburg's EDMD "Single" (neighbour lists, one event per particle; MIT licence;
F. Smallenburg, Eur. Phys. J. E 45, 22 (2022)). Nothing of it is part of GRANFRIC: give the
folder of its source (the one holding mdSingle.c, or its parent with Single/) with --peer or the
environment variable GRANFRIC_PEER. Its parameters are compile-time globals, so each point gets
its own binary, built here with the peer's own compiler flags.

The scene is the peer's own benchmark: elastic smooth spheres (sigma = m = 1), 3D periodic cube,
fcc start at packing fraction phi, kT = 1, run for a fixed simulated time from the lattice.
GRANFRIC runs the same scene through LAMMPS (bench/in.peers: fix hardsphere/ed, the rough law
with r = 1 and beta = -1, i.e. elastic and smooth).

Both are measured as whole processes: CPU time (user + sys, start-up and output included for
both) and peak resident memory from the rusage of the child process. Rounds are interleaved
(every point of both codes once per round, the order alternating), and the fastest of the rounds
is kept. The collision counts and the pressures (averaged over the run, from the collision
virial) of both are printed as a guard that both simulated the same physics (each within 2 %).

    bench/peers [--peer DIR] [--rounds R] [--quick] [--points ...] [--out DIR]

Prints a table with the ratio peer CPU / GRANFRIC CPU per point ("GRANFRIC faster by") and writes
DIR/peers.csv (default DIR = bench/results). A benchmark, not a test.
"""
import argparse
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
LMP = os.path.join(ROOT, "tools", "lmp")
INPUT = os.path.join(HERE, "in.peers")
sys.path.insert(0, os.path.join(ROOT, "tools"))
from granfric import cli  # noqa: E402
PEER_SOURCES = ("mdSingle.c", "mdSingle.h", "mt19937ar.c")
PEER_CFLAGS = ["-O3", "-ffast-math", "-funroll-loops", "-march=native"]
RATE_TOLERANCE = 0.02      # the guard: collision counts of both within 2 %

# GRANFRIC's step in mean free times: 5 was at least as fast as 2 at every point (fastest of two
# or three interleaved runs each; bench/README.md)
STEP = 5.0
# (N, packing fraction, simulated time, GRANFRIC's step): 1.0 - 2.2 M collisions at N = 32 000,
# 6.5 M at 10^6
POINTS = [
    (32000, 0.10, 40.0, STEP),
    (32000, 0.25, 20.0, STEP),
    (32000, 0.35, 8.0, STEP),
    (32000, 0.45, 4.0, STEP),
    (1000188, 0.25, 2.0, STEP),
]
QUICK = [(4000, 0.25, 4.0, STEP), (4000, 0.45, 1.0, STEP)]


def fcc_cells(n):
    """ncell with n = 4 ncell^3 (the fcc lattice of both codes), or ValueError."""
    c = round((n / 4) ** (1.0 / 3.0))
    if 4 * c ** 3 != n:
        raise ValueError(f"N = {n} is not 4 ncell^3 (fcc start): try {4 * c ** 3}")
    return c


def find_peer(path):
    """The folder holding the peer's sources (path itself, or path/Single), or SystemExit."""
    if not path:
        raise SystemExit("bench/peers: give the peer's source folder with --peer DIR or "
                         "GRANFRIC_PEER=DIR (the folder holding mdSingle.c, or its parent)")
    for d in (path, os.path.join(path, "Single")):
        if all(os.path.isfile(os.path.join(d, f)) for f in PEER_SOURCES):
            return os.path.abspath(d)
    raise SystemExit(f"bench/peers: no {', '.join(PEER_SOURCES)} in {path} or {path}/Single")


def patch_peer_source(text, n, phi, tmax):
    """The peer's main file with its globals set for one point: fcc start, N, packing fraction,
    simulated time. Each global must occur exactly once (else ValueError: a changed source)."""
    settings = {"maxtime": repr(float(tmax)), "initialconfig": "1", "N": str(int(n)),
                "packfrac": repr(float(phi))}
    for name, value in settings.items():
        pattern = re.compile(r"^((?:double|int)\s+" + name + r"\s*=\s*)[^;]*;", re.M)
        text, count = pattern.subn(lambda m, v=value: m.group(1) + v + ";", text)
        if count != 1:
            raise ValueError(f"the peer's source sets '{name}' {count} times (expected once)")
    return text


def build_peer(src, workdir, n, phi, tmax):
    """Compile the peer for one point in workdir; returns the executable's path."""
    os.makedirs(workdir, exist_ok=True)
    for f in PEER_SOURCES:
        shutil.copy(os.path.join(src, f), workdir)
    main = os.path.join(workdir, "mdSingle.c")
    with open(main) as fh:
        text = patch_peer_source(fh.read(), n, phi, tmax)
    with open(main, "w") as fh:
        fh.write(text)
    exe = os.path.join(workdir, "md")
    subprocess.run(["gcc", *PEER_CFLAGS, main, "-o", exe, "-lm"], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return exe


def measure(cmd, cwd):
    """Run cmd as one child process: (CPU seconds user + sys, peak RSS in bytes, stdout)."""
    with tempfile.TemporaryFile() as out:
        proc = subprocess.Popen(cmd, cwd=cwd, stdout=out, stderr=subprocess.STDOUT)
        _, status, ru = os.wait4(proc.pid, 0)
        proc.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        text = out.read().decode(errors="replace")
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({proc.returncode}):\n{text[-2000:]}")
    return ru.ru_utime + ru.ru_stime, ru.ru_maxrss * 1024, text


def parse_peer(text):
    """(collisions, reduced pressure) from the peer's output: its last collision count and the
    total of its final 'Measured pressure' line."""
    counts = re.findall(r"Collisions:\s*(\d+)", text)
    press = re.search(r"Measured pressure\s*:\s*\S+\s*\+\s*\S+\s*=\s*([-+0-9.eE]+)", text)
    if not counts:
        raise ValueError("no 'Collisions:' line in the peer's output")
    return int(counts[-1]), float(press.group(1)) if press else math.nan


def parse_granfric(text):
    """(collisions, pressure) from bench/in.peers' PEERS line"""
    m = re.search(r"^PEERS N (\d+) phi \S+ time \S+ steps (\d+) collisions (\d+) pressure (\S+)",
                  text, re.M)
    if not m:
        raise ValueError("no PEERS line in the LAMMPS output")
    return int(m.group(3)), float(m.group(4))


def granfric_cmd(n, phi, tmax, dtmft):
    return [LMP, "-log", "none", "-in", INPUT, "-var", "ncell", str(fcc_cells(n)), "-var", "phi",
            str(phi), "-var", "tmax", str(tmax), "-var", "dtmft", str(dtmft)]


def agree(peer, ours, tol=RATE_TOLERANCE):
    """the guard: ours within tol of the peer's (collision counts, pressures)"""
    return peer > 0 and abs(ours - peer) <= tol * peer


def run(points, peer_src, rounds, out):
    work = tempfile.mkdtemp(prefix="granfric-peers-")
    exes = [build_peer(peer_src, os.path.join(work, f"p{k}"), n, phi, tmax)
            for k, (n, phi, tmax, _) in enumerate(points)]
    best = [dict(peer=math.inf, ours=math.inf, rss_peer=0, rss_ours=0) for _ in points]
    for r in range(rounds):
        for k, (n, phi, tmax, dtmft) in enumerate(points):
            runs = [("peer", [exes[k]], os.path.dirname(exes[k])),
                    ("ours", granfric_cmd(n, phi, tmax, dtmft), work)]
            if (r + k) % 2:
                runs.reverse()
            for who, cmd, cwd in runs:
                cpu, rss, text = measure(cmd, cwd)
                b = best[k]
                if who == "peer":
                    b["coll_peer"], b["press_peer"] = parse_peer(text)
                else:
                    b["coll_ours"], b["press_ours"] = parse_granfric(text)
                b[who] = min(b[who], cpu)
                b["rss_" + who] = max(b["rss_" + who], rss)
                print(f"round {r + 1}: N {n} phi {phi} {who} {cpu:.2f} s", flush=True)
    shutil.rmtree(work, ignore_errors=True)
    return report(points, best, rounds, out)


def report(points, best, rounds, out):
    os.makedirs(out, exist_ok=True)
    rows = []
    lines = [f"GRANFRIC (fix hardsphere/ed through LAMMPS) against Smallenburg's EDMD Single, "
             f"fastest of {rounds} interleaved rounds, whole-process CPU (user + sys)", "",
             "| N | phi | time | collisions peer / GRANFRIC | P* peer / GRANFRIC | guard "
             "| CPU s peer | CPU s GRANFRIC | GRANFRIC faster by | peak RSS B/particle peer / GRANFRIC |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for (n, phi, tmax, dtmft), b in zip(points, best):
        ok = agree(b["coll_peer"], b["coll_ours"]) and agree(b["press_peer"], b["press_ours"])
        ratio = b["peer"] / b["ours"]
        rows.append(dict(N=n, phi=phi, time=tmax, dtmft=dtmft, coll_peer=b["coll_peer"],
                         coll_granfric=b["coll_ours"], pressure_peer=b["press_peer"],
                         pressure_granfric=b["press_ours"], same_physics=ok, cpu_peer=b["peer"],
                         cpu_granfric=b["ours"], ratio=ratio, rss_peer=b["rss_peer"] / n,
                         rss_granfric=b["rss_ours"] / n))
        lines.append(f"| {n} | {phi} | {tmax:g} | {b['coll_peer']} / {b['coll_ours']} | "
                     f"{b['press_peer']:.3f} / {b['press_ours']:.3f} | {'same' if ok else 'DIFFER'} | "
                     f"{b['peer']:.2f} | {b['ours']:.2f} | x{ratio:.2f} | "
                     f"{b['rss_peer'] / n:.0f} / {b['rss_ours'] / n:.0f} |")
    print("\n".join(lines))
    cli.write_rows(os.path.join(out, "peers.csv"), rows)
    return rows


def parse_point(s):
    parts = s.split(":")
    if len(parts) not in (3, 4):
        raise argparse.ArgumentTypeError("a point is N:phi:time[:dtmft]")
    n, phi, tmax = int(parts[0]), float(parts[1]), float(parts[2])
    fcc_cells(n)
    return (n, phi, tmax, float(parts[3]) if len(parts) == 4 else STEP)


def main(argv=None):
    ap = argparse.ArgumentParser(prog="bench/peers", description=__doc__.split("\n\n")[0])
    ap.add_argument("--peer", default=os.environ.get("GRANFRIC_PEER"),
                    help="the peer's source folder (default: $GRANFRIC_PEER)")
    ap.add_argument("--rounds", type=int, default=3, help="interleaved rounds (default 3)")
    ap.add_argument("--quick", action="store_true", help="two small points, one round")
    ap.add_argument("--points", nargs="+", type=parse_point, metavar="N:phi:time[:dtmft]",
                    help="points to run instead of the default five")
    ap.add_argument("--out", default=os.path.join(HERE, "results"), help="folder of peers.csv")
    a = ap.parse_args(argv)
    if a.rounds < 1:
        ap.error("--rounds must be at least 1")
    points = a.points or (QUICK if a.quick else POINTS)
    rounds = 1 if a.quick and a.rounds == 3 else a.rounds
    run(points, find_peer(a.peer), rounds, a.out)


if __name__ == "__main__":
    sys.exit(main())
