#!/usr/bin/env bash
# Set up GRANFRIC on a fresh Debian 12 machine and run the main job.
#   bash tools/setup.sh        -> out/ (figure + table); build in $GRANFRIC_BUILD (default build/)
# Steps: Debian packages (if missing) -> LAMMPS 4Feb2025 source from Debian (cached in
# ~/.cache/granfric) -> LAMMPS + granfricplugin.so build (ccache) -> main job.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${GRANFRIC_BUILD:-$root/build}
out=${GRANFRIC_OUT:-$root/out}
bash "$root/tools/install-deps.sh"
export CCACHE_BASEDIR=$root
cmake -S "$root" -B "$build" -G Ninja -D CMAKE_BUILD_TYPE=Release
cmake --build "$build" --parallel "$(nproc)"
export GRANFRIC_BUILD=$build
mkdir -p "$out"

echo "== main job: collision laws of the three papers through the GRANFRIC core and LAMMPS"
PYTHONPATH="$root/tools" /usr/bin/python3 -m granfric.collision_demo --out "$out"
for s in "$root"/examples/collisions/in.*; do
  (cd "$root/examples/collisions" && "$root/tools/lmp" -in "$(basename "$s")" -var outdir "$out" \
     -log "$out/log.$(basename "$s" | sed 's/^in\.//')" -screen none)
done
echo "== done: $out/collision_laws.png, $out/collision_table.md, $out/log.* and $out/contacts.*"
