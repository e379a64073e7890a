#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
# The whole GRANFRIC test suite: installs what is missing, builds LAMMPS + the plugin (ccache),
# runs every test through CTest (core, LAMMPS-side, scripts serial and under MPI, Python tools).
#   bash tools/test.sh            (build directory: $GRANFRIC_BUILD, default <repo>/build)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${GRANFRIC_BUILD:-$root/build}
bash "$root/tools/install-deps.sh"
# ccache: paths below the repository are hashed relative to it, so fresh clones hit the cache
export CCACHE_BASEDIR=$root
cmake -S "$root" -B "$build" -G Ninja -D CMAKE_BUILD_TYPE=Release
cmake --build "$build" --parallel "$(nproc)"
cd "$build"
ctest --output-on-failure --parallel "$(nproc)" --timeout 1800
