# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
# Install (mode 1), update (mode 2) or uninstall (mode 0) the GRANFRIC package in a LAMMPS
# source tree built with make (`make yes-granfric`, `make no-granfric`): its styles and its
# physics core are copied flat into src/ (the styles include the core's headers by name). The
# plugin registration (granfricplugin.cpp) is not part of an in-tree build.
mode=$1
LC_ALL=C
export LC_ALL

# action FILE: copy FILE (a path below this folder) to ../<its name>, or remove it there
action () {
  dest=../$(basename "$1")
  if test "$mode" = 0; then
    rm -f "$dest"
  elif ! cmp -s "$1" "$dest"; then
    cp "$1" "$dest"
    if test "$mode" = 2; then echo "  updating src/$(basename "$1")"; fi
  fi
}

for file in *.cpp *.h core/*.cpp core/*.h; do
  test "$file" = granfricplugin.cpp && continue
  action "$file"
done
