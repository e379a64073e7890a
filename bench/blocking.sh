#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
# What processing one system in cache-sized spatial blocks could give towards a cost per
# collision that stays flat from N = 10^3 to 10^6: bench_core at N = 10^6 as one system, as K
# independent blocks (the ideal: no shell), and as blocks that carry the shell of copies an exact
# window needs (a lower bound for any exact blocked scheme), against N = 10^3; interleaved rounds,
# the fastest of each configuration. Prints every run and a table of factors over N = 10^3 (the
# spatial-blocking table of bench/README.md). Not a test: about 10 minutes a round.
#   bash bench/blocking.sh [build dir] [rounds]            (default: build/, 3 rounds)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-${GRANFRIC_BUILD:-$root/build}}
rounds=${2:-3}
B=$build/bench_core
[ -x "$B" ] || { echo "bench/blocking.sh: $B not found (build first)" >&2; exit 1; }
out=$(mktemp)
trap 'rm -f "$out"' EXIT
for ((round = 1; round <= rounds; round++)); do
  for phi in 0.3 0.05; do
    "$B" 2 1000 $phi 1 40
    "$B" 2 10000 $phi 1 20
    "$B" 2 1000000 $phi 1 4
    "$B" 2 1000000 $phi 1 4 0 400
    for dt in 1 0.5; do
      for K in 400 100; do "$B" 2 1000000 $phi $dt 4 0 $K 1; done
    done
  done
  for phi in 0.3 0.05; do
    "$B" 3 1000 $phi 1 40
    "$B" 3 1000000 $phi 1 3
    "$B" 3 1000000 $phi 1 3 0 100
    for dt in 1 0.5; do "$B" 3 1000000 $phi $dt 3 0 100 1; done
  done
done | tee "$out"
py=/usr/bin/python3
[ -x "$py" ] || py=python3
"$py" - "$out" <<'PY'
import collections, re, sys
runs = collections.defaultdict(list)
for line in open(sys.argv[1]):
    m = re.match(r"dim (\d) N (\d+) fraction ([\d.]+) dt ([\d.]+) mft", line)
    if not m:
        continue
    rate = float(re.search(r"\| ([\d.e+]+) collisions/s", line)[1])
    blocks = re.search(r"(\d+) independent blocks of (\d+)", line)
    shell = re.search(r"shell ([\d.]+) diameters wide \(\d+ in all\): ([\d.e+]+) owned", line)
    if shell:
        rate = float(shell[2])
    key = (int(m[1]), float(m[3]), int(m[2]), float(m[4]), int(blocks[2]) if blocks else 0,
           float(shell[1]) if shell else 0.0)
    runs[key].append(rate)
print("\ncost per collision over N = 10^3 (fastest of the rounds; slowest in brackets)")
for dim in (2, 3):
    for phi in (0.3, 0.05):
        ref = runs.get((dim, phi, 1000, 1.0, 0, 0.0))
        if not ref:
            continue
        r0 = max(ref)
        print(f"{dim}D, fraction {phi}: N = 10^3 {r0:.3g} collisions/s")
        for k in sorted((k for k in runs if k[:2] == (dim, phi) and k[2] > 1000),
                        key=lambda k: (k[4] > 0, k[5] > 0, k[2], -k[3], -k[4])):
            what = (f"N = {k[2]}, one system" if k[4] == 0 else f"blocks of {k[4]}, no shell"
                    if k[5] == 0 else f"blocks of {k[4]}, shell {k[5]:.3g} diameters")
            v = runs[k]
            print(f"  {what:40s} dt {k[3]:g} mft: x{r0 / max(v):.2f} (x{r0 / min(v):.2f})")
PY
