#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
# Put GRANFRIC into a LAMMPS source tree as a package, for builds of LAMMPS with GRANFRIC's
# styles compiled in (no plugin):
#   tools/install-in-tree.sh <lammps>       <lammps>: the folder with src/ and cmake/
# It copies src/GRANFRIC (styles, physics core, Install.sh; not the plugin registration) to
# <lammps>/src/GRANFRIC, and for LAMMPS's CMake the package module to
# <lammps>/cmake/Modules/Packages/GRANFRIC.cmake and the name GRANFRIC into the package lists of
# <lammps>/cmake/CMakeLists.txt. Running it again updates the copy (unchanged files are left as
# they are, so a rebuild recompiles only what changed). Then build LAMMPS as usual:
#   CMake: cmake -S <lammps>/cmake -B build-lammps -D PKG_GRANFRIC=on [other options]
#   make:  cd <lammps>/src && make yes-granfric && make mpi
set -euo pipefail
if [ $# -ne 1 ] || [ "$1" = "-h" ] || [ "$1" = "--help" ]; then
  sed -n '4,13p' "$0" | sed 's/^# \{0,1\}//'
  [ $# -eq 1 ] && exit 0
  exit 2
fi
top=$(cd "$1" && pwd)
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
lists=$top/cmake/CMakeLists.txt
if [ ! -f "$top/src/lammps.h" ] || [ ! -f "$lists" ]; then
  echo "install-in-tree.sh: $top is not a LAMMPS source tree (no src/lammps.h or cmake/CMakeLists.txt)" >&2
  exit 2
fi
if ! grep -q "^  GRANULAR$" "$lists" || ! grep -qE "^foreach\(PKG_WITH_INCL (GRANFRIC )?KSPACE " "$lists"; then
  echo "install-in-tree.sh: $lists does not have the package lists of LAMMPS 4Feb2025 (GRANULAR in" \
       "STANDARD_PACKAGES, foreach(PKG_WITH_INCL KSPACE ...)); register GRANFRIC there by hand" >&2
  exit 2
fi

# put: copy $1 to $2 unless $2 already has that content
put () {
  cmp -s "$1" "$2" || cp "$1" "$2"
}
dst=$top/src/GRANFRIC
mkdir -p "$dst/core"
for f in "$repo"/src/GRANFRIC/*.cpp "$repo"/src/GRANFRIC/*.h "$repo"/src/GRANFRIC/Install.sh; do
  [ "$(basename "$f")" = granfricplugin.cpp ] && continue
  put "$f" "$dst/$(basename "$f")"
done
for f in "$repo"/src/GRANFRIC/core/*.cpp "$repo"/src/GRANFRIC/core/*.h; do
  put "$f" "$dst/core/$(basename "$f")"
done
# files a previous copy had that GRANFRIC no longer has
for f in "$dst"/*.cpp "$dst"/*.h "$dst"/core/*.cpp "$dst"/core/*.h; do
  [ -e "$f" ] || continue
  rel=${f#"$dst"/}
  [ -e "$repo/src/GRANFRIC/$rel" ] || rm -f "$f"
done
rm -f "$dst/granfricplugin.cpp"    # (not part of an in-tree build)
put "$repo/tools/in-tree/GRANFRIC.cmake" "$top/cmake/Modules/Packages/GRANFRIC.cmake"

# register the package with LAMMPS's CMake (once): a standard package with a module
if ! grep -q "^  GRANFRIC$" "$lists"; then
  sed -i 's/^  GRANULAR$/  GRANFRIC\n  GRANULAR/' "$lists"
fi
if ! grep -q "^foreach(PKG_WITH_INCL GRANFRIC " "$lists"; then
  sed -i 's/^foreach(PKG_WITH_INCL KSPACE /foreach(PKG_WITH_INCL GRANFRIC KSPACE /' "$lists"
fi
echo "GRANFRIC is in $top: build LAMMPS with -D PKG_GRANFRIC=on (CMake) or make yes-granfric (make)"
