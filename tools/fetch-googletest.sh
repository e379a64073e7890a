#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
# googletest 1.12.1 source tarball from Debian's source package (the exact file LAMMPS's unit-test
# build downloads otherwise), for building LAMMPS's own test harness offline. Prints its path.
#   tools/fetch-googletest.sh [CACHE_DIR]
set -euo pipefail
cache=${1:-${GRANFRIC_CACHE:-$HOME/.cache/granfric}}
tarball=$cache/googletest_1.12.1.orig.tar.gz
md5=e82199374acdfda3f425331028eb4e2a
ok() { [ -f "$tarball" ] && echo "$md5  $tarball" | md5sum -c --quiet - 2>/dev/null; }
if ! ok; then
  mkdir -p "$cache"
  bash "$(dirname "${BASH_SOURCE[0]}")/deb-src.sh" >&2
  (cd "$cache" && apt-get source --download-only googletest=1.12.1-0.2 >&2) || true
  ok || { echo "fetch-googletest: could not obtain a verified $tarball" >&2; exit 1; }
fi
echo "$tarball"
