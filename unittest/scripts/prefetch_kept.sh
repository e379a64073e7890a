#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
# Did the compiler keep the event loop's prefetching? GCC counts a prefetch as touching no
# memory, so it drops every call to a function that only prefetches unless the function has an
# effect (the empty volatile asm of EventQueue::prefetch_ahead and of the functions it calls).
# Nothing else would notice: the trajectories are the same, only large systems get slower (at
# N = 10^6 by half). The pipeline's stages (EDCore::prefetch_upcoming) must call
# prefetch_around, or hold its prefetches inlined.
#   prefetch_kept.sh BINARY ...
set -euo pipefail
for bin in "$@"; do
  body=$(objdump -d --no-show-raw-insn -C "$bin" |
    awk '/<granfric::EDCore::prefetch_upcoming\(\)>:$/ {on = 1; next} /^$/ {on = 0} on')
  if [ -z "$body" ]; then
    echo "FAIL: $bin has no EDCore::prefetch_upcoming"
    exit 1
  fi
  calls=$(grep -c 'call.*prefetch_around' <<< "$body" || true)
  prefetches=$(grep -cE 'prefetch(t[0-2]|nta|w) ' <<< "$body" || true)
  echo "$bin: prefetch_upcoming calls prefetch_around $calls times, $prefetches prefetch instructions"
  if [ "$calls" -lt 1 ] && [ "$prefetches" -lt 100 ]; then
    echo "FAIL: $bin: the calls of prefetch_around were dropped"
    exit 1
  fi
done
echo "PASSED: prefetching kept in $# binaries"
