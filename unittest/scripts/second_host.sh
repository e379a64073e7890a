#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
# GRANFRIC in a second LAMMPS host: the host runs unittest/scripts/in.second_host to the same
# final state, bit for bit, as the bundled LAMMPS (tools/lmp), and exits cleanly.
#   second_host.sh <tools/lmp> <workdir> <second lmp> [<plugin.so> [<plugin.so> ...]]
# With plugins, the second host loads the first one with `plugin load`, and every plugin given
# must link no LAMMPS library and record no library path (LAMMPS's plugin convention). Without,
# the second host has GRANFRIC's styles compiled in.
set -euo pipefail
lmp=$1 work=$2 lmp2=$3
shift 3
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
mkdir -p "$work"
for p in "$@"; do
  dyn=$(readelf -d "$p")
  if grep -q "liblammps" <<<"$dyn"; then
    echo "FAILED: $p links a LAMMPS library:"; grep NEEDED <<<"$dyn"; exit 1
  fi
  if grep -qE "RPATH|RUNPATH" <<<"$dyn"; then
    echo "FAILED: $p records a library path:"; grep -E "RPATH|RUNPATH" <<<"$dyn"; exit 1
  fi
done
"$lmp" -in "$here/in.second_host" -var out "$work/bundled.txt" -log "$work/log.bundled" -screen none
# (LAMMPS_PLUGIN_PATH cleared: the second host loads only the plugin it is given, if any)
env -u LAMMPS_PLUGIN_PATH "$lmp2" -in "$here/in.second_host" -var load $(($# > 0)) \
  -var plugin "${1:-none}" -var out "$work/second.txt" -log "$work/log.second" -screen none
if [ $# -gt 0 ] && ! grep -q "Loading plugin: GRANFRIC" "$work/log.second"; then
  echo "FAILED: the second host did not report loading the plugin"; exit 1
fi
if ! cmp -s <(tail -n +10 "$work/bundled.txt") <(tail -n +10 "$work/second.txt"); then
  echo "FAILED: the final states differ between the hosts"
  diff <(tail -n +10 "$work/bundled.txt") <(tail -n +10 "$work/second.txt") | head -4
  exit 1
fi
n=$(($(wc -l < "$work/second.txt") - 9))
how="GRANFRIC compiled in"
[ $# -gt 0 ] && how="the plugin loaded ($# plugin(s) without liblammps or a library path)"
echo "PASSED: $n atoms, identical final state in the bundled LAMMPS and in $lmp2 with $how"
