#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
# GRANFRIC in a LAMMPS tree built with make: tools/install-in-tree.sh puts the package into a
# copy of the tree, `make yes-granfric` installs its files flat into src/ (every style and core
# file, not the plugin registration), each compiles there (syntax check with mpicxx, LAMMPS's
# include path: src/ alone), and `make no-granfric` removes them all again.
#   make_install.sh <lammps top folder> <workdir>
set -euo pipefail
top=$1 work=$2
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
rm -rf "$work"
mkdir -p "$work"
cp -r "$top/src" "$top/cmake" "$work/"
bash "$repo/tools/install-in-tree.sh" "$work" > /dev/null
bash "$repo/tools/install-in-tree.sh" "$work" > /dev/null    # (again: an update of the copy)
cd "$work/src"
make yes-granfric > "$work/yes.log" 2>&1
expect=()
for f in "$repo"/src/GRANFRIC/*.cpp "$repo"/src/GRANFRIC/*.h "$repo"/src/GRANFRIC/core/*.cpp \
         "$repo"/src/GRANFRIC/core/*.h; do
  [ "$(basename "$f")" = granfricplugin.cpp ] && continue
  expect+=("$(basename "$f")")
  if ! cmp -s "$f" "$(basename "$f")"; then
    echo "FAILED: make yes-granfric did not install $(basename "$f") into src/"; exit 1
  fi
done
if [ -e granfricplugin.cpp ]; then echo "FAILED: the plugin registration was installed"; exit 1; fi
n=0
for f in "${expect[@]}"; do
  case $f in
    *.cpp)
      if ! mpicxx -std=c++17 -fsyntax-only -I. "$f" 2> "$work/compile.log"; then
        echo "FAILED: $f does not compile in src/:"; head -5 "$work/compile.log"; exit 1
      fi
      n=$((n + 1));;
  esac
done
make no-granfric > "$work/no.log" 2>&1
for f in "${expect[@]}"; do
  if [ -e "$f" ]; then echo "FAILED: make no-granfric left $f in src/"; exit 1; fi
done
echo "PASSED: make yes-granfric installed ${#expect[@]} files, $n sources compile in src/, make no-granfric removed them"
