#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
# Set up GRANFRIC on a fresh Debian 12 machine and run the main job.
#   bash tools/setup.sh        -> out/ (figures + reports); build in $GRANFRIC_BUILD (default build/)
# Steps: Debian packages (if missing) -> LAMMPS 4Feb2025 source from Debian (cached in
# ~/.cache/granfric) -> LAMMPS + granfricplugin.so build (ccache) -> main job.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${GRANFRIC_BUILD:-$root/build}
out=${GRANFRIC_OUT:-$root/out}
bash "$root/tools/install-deps.sh"
export CCACHE_BASEDIR=$root
cmake -S "$root" -B "$build" -G Ninja -D CMAKE_BUILD_TYPE=Release
# (what the main job runs: LAMMPS, the plugin, the core library of the Python tools; the tests
# and their extra LAMMPS builds are tools/test.sh's)
cmake --build "$build" --parallel "$(nproc)" --target granfricplugin granfric_capi
export GRANFRIC_BUILD=$build
mkdir -p "$out"

echo "== main job (flagship): randomly driven rough spheres with friction (Herbst et al. 2005) vs model E"
PYTHONPATH="$root/tools" /usr/bin/python3 -m granfric.herbst --quick --out "$out/herbst2005"
echo "== free cooling of rough discs and spheres (Luding et al. 1998), simulation vs theory"
PYTHONPATH="$root/tools" /usr/bin/python3 -m granfric.luding --quick --out "$out/luding1998"
echo "== mean energy loss per collision (Risso et al. 2005, Fig. 1) through the C++ law"
PYTHONPATH="$root/tools" /usr/bin/python3 -m granfric reproduce risso2005 --quick --out "$out/risso2005" > /dev/null
echo "== collision laws of the three papers through the GRANFRIC core"
PYTHONPATH="$root/tools" /usr/bin/python3 -m granfric.collision_demo --out "$out/collisions" > /dev/null
echo "== done: $out/herbst2005/driven.png and report.md (flagship),"
echo "         $out/luding1998/cooling.png and report.md, $out/risso2005/energy_loss.png,"
echo "         $out/collisions/collision_laws.png"
