#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
# Run unittest/scripts/in.ranks on 1, 2 and 4 MPI ranks and require identical final states.
#   compare_ranks.sh <tools/lmp> <workdir>
set -euo pipefail
lmp=$1
work=$2
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
mkdir -p "$work"
"$lmp" -in "$here/in.ranks" -var make 1 -var data "$work/ranks.data" -log none -screen none
for np in 1 2 4; do
  "$lmp" -np "$np" -in "$here/in.ranks" -var out "$work/state.np$np" -var data "$work/ranks.data" -log none -screen none
done
for np in 2 4; do
  if ! cmp -s <(tail -n +10 "$work/state.np1") <(tail -n +10 "$work/state.np$np"); then
    echo "FAILED: the final state on $np ranks differs from 1 rank"
    diff <(tail -n +10 "$work/state.np1") <(tail -n +10 "$work/state.np$np") | head -5
    exit 1
  fi
  if ! cmp -s "$work/state.np1.peratom" "$work/state.np$np.peratom"; then
    echo "FAILED: the per-atom virials or collision tallies on $np ranks differ from 1 rank"
    diff "$work/state.np1.peratom" "$work/state.np$np.peratom" | head -5
    exit 1
  fi
done
# (the last step had collisions: its per-atom collision counts are not all zero)
n=$(($(wc -l < "$work/state.np1") - 9))
if ! tail -n "$n" "$work/state.np1.peratom" | awk '{ s += $5 } END { exit !(s > 0) }'; then
  echo "FAILED: no collisions in the per-atom tallies of the last step"
  exit 1
fi
echo "PASSED: $n atoms, identical final state (positions, velocities, spins, images) and per-atom virials and collision tallies on 1, 2 and 4 ranks"
