#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
# GRANFRIC benchmark: instructions per collision of the event-driven core against the width of
# its cells (callgrind, reproducible on a shared machine), for elastic smooth discs (2D) or
# spheres (3D) at several fractions; "auto" is the core's own choice (EDCore::setup_cells).
# Steady state: a run with 20 collisions per particle less one with 10 (cancels the start).
# Prints a table; not a test.
#   bash bench/cell_width.sh [build] [dim] [N]            (default: build 2 10000)
#   FRACTIONS="0.05 0.1" WIDTHS="2 3 4" bash bench/cell_width.sh build 2 10000
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$root/build}
dim=${2:-2}
N=${3:-10000}
fractions=${FRACTIONS:-0.05 0.1 0.2 0.3}
if [ "$dim" = 2 ]; then widths=${WIDTHS:-1 1.5 2 2.5 3 3.5 4}; else widths=${WIDTHS:-1 1.3 1.6 2}; fi
command -v valgrind > /dev/null || { echo "cell_width.sh needs valgrind (apt-get install valgrind)" >&2; exit 1; }

# instructions, collisions, crossings per collision and the cell width of one run
run() {    # fraction width collisions-per-particle
  local err
  err=$(mktemp)
  local line
  line=$(valgrind --tool=callgrind --callgrind-out-file=/dev/null "$build/bench_core" "$dim" "$N" "$1" 1.0 "$3" "$2" 2> "$err")
  local ir
  ir=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$err")
  rm -f "$err"
  local coll cross cw
  coll=$(sed -n 's/.*| collisions \([0-9]*\) .*/\1/p' <<< "$line")
  cross=$(sed -n 's/.*crossings\/collision \([0-9.]*\) .*/\1/p' <<< "$line")
  cw=$(sed -n 's/.*| cells \([0-9.e+-]*\) wide .*/\1/p' <<< "$line")
  echo "$ir $coll $cross $cw"
}

printf "%8s %8s %12s %18s %20s\n" fraction width "cells wide" "instr/collision" "crossings/collision"
for phi in $fractions; do
  for w in auto $widths; do
    arg=0
    [ "$w" != auto ] && arg=$w
    read -r ir1 c1 _ _ <<< "$(run "$phi" "$arg" 10)"
    read -r ir2 c2 x2 cw <<< "$(run "$phi" "$arg" 20)"
    awk -v p="$phi" -v w="$w" -v cw="$cw" -v a="$ir1" -v b="$ir2" -v c="$c1" -v d="$c2" -v x="$x2" \
      'BEGIN {printf "%8s %8s %12.3f %18.0f %20s\n", p, w, cw, (b - a) / (d - c), x}'
  done
done
