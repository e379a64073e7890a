#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
# Instruction-level profile of the event-driven core (reproducible on a noisy machine):
# callgrind on bench_core, 2D, fraction 0.3, N = 10^4, 5 collisions per particle.
#   bash bench/profile_core.sh [build dir]
set -euo pipefail
build=${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/build}
out=$(mktemp -d)
valgrind --tool=callgrind --callgrind-out-file="$out/cg.out" "$build/bench_core" 2 10000 0.3 1.0 5 2>/dev/null
callgrind_annotate "$out/cg.out" 2>/dev/null | head -30
total=$(callgrind_annotate "$out/cg.out" 2>/dev/null | awk '/PROGRAM TOTALS/ {gsub(",","",$1); print $1}')
echo "instructions in total: $total"
