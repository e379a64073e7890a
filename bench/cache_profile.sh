#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
# What bounds the cost per collision at large N: instructions and simulated last-level cache
# misses per collision of the event-driven core (cachegrind, reproducible on a noisy machine),
# 2D, fraction 0.3, one step per mean free time, for each N given (default 1e4 and 1e5; 1e6
# takes ~15 minutes). The last level is simulated at 4 MiB: the L3 this machine reports is 32 MiB,
# but it is shared, and what one process gets of it ends between 2 and 4 MiB (bench/mem_latency:
# a random load costs 16 ns up to 2 MiB and 140-210 ns from 4 MiB on). LL_BYTES sets another
# size (LL_BYTES=1048576: the 1 MiB L2 of one core).
#   [LL_BYTES=...] bash bench/cache_profile.sh [build dir] [N ...]
set -euo pipefail
build=${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/build}
shift || true
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(10000 100000)
l3=${LL_BYTES:-4194304}
out=$(mktemp -d)
cpp=3    # collisions per particle timed (after 5 of equilibration, which are counted too)
printf "%10s %14s %14s %12s %12s\n" N collisions "instr/coll" "D1miss/coll" "LLmiss/coll"
for N in "${sizes[@]}"; do
  valgrind --tool=cachegrind --cache-sim=yes --LL=$l3,$( [ "$l3" -ge 4194304 ] && echo 16 || echo 8 ),64 --cachegrind-out-file="$out/cg.$N" \
    "$build/bench_core" 2 "$N" 0.3 1.0 $cpp > "$out/log.$N" 2> "$out/err.$N"
  # every collision of the run (equilibration + timed) shares the counts
  coll=$(awk -v n="$N" -v c=$cpp 'BEGIN {print (5 + c) * n / 2}')
  ir=$(awk '/I *refs:/ {gsub(",","",$4); print $4}' "$out/err.$N")
  d1=$(awk '/D1 *misses:/ {gsub(",","",$4); print $4}' "$out/err.$N")
  ll=$(awk '/LLd misses:/ {gsub(",","",$4); print $4}' "$out/err.$N")
  awk -v n="$N" -v c="$coll" -v ir="$ir" -v d1="$d1" -v ll="$ll" \
    'BEGIN {printf "%10d %14d %14.0f %12.1f %12.1f\n", n, c, ir / c, d1 / c, ll / c}'
done
rm -rf "$out"
