#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
# Obtain the LAMMPS 4Feb2025 source tree from Debian's (trixie) source package, verify its
# checksum and unpack it into a cache outside the repository. Prints the path of the unpacked
# tree's top directory on stdout (the last line). Idempotent: a verified tree is reused.
#
#   tools/fetch-lammps.sh [CACHE_DIR]      (default: ${GRANFRIC_CACHE:-$HOME/.cache/granfric})
set -euo pipefail

cache=${1:-${GRANFRIC_CACHE:-$HOME/.cache/granfric}}
version=20250204+dfsg.1-2
tarball=lammps_20250204+dfsg.1.orig.tar.xz
sha256=3671165bd52fad36734e0a9136c5bc5ecb225e03988f8c89aa13366a8b53b1c7
tree=$cache/lammps-4Feb2025

log() { echo "fetch-lammps: $*" >&2; }

if [ -f "$tree/.granfric-verified" ] && [ -f "$tree/src/lammps.h" ]; then
  echo "$tree"
  exit 0
fi
mkdir -p "$cache"

if ! { [ -f "$cache/$tarball" ] && echo "$sha256  $cache/$tarball" | sha256sum -c --quiet - 2>/dev/null; }; then
  bash "$(dirname "${BASH_SOURCE[0]}")/deb-src.sh" >&2
  log "downloading Debian source package lammps=$version (orig tarball only)"
  # The .dsc of this version may answer 404 and apt then exits 100 although the orig
  # tarball arrived; the checksum below is what decides success.
  (cd "$cache" && apt-get source --download-only "lammps=$version" >&2) || true
  if ! [ -f "$cache/$tarball" ]; then
    apt-get update -qq >&2 || true
    (cd "$cache" && apt-get source --download-only "lammps=$version" >&2) || true
  fi
  [ -f "$cache/$tarball" ] || { log "download of $tarball failed"; exit 1; }
  echo "$sha256  $cache/$tarball" | sha256sum -c --quiet - \
    || { log "checksum mismatch for $tarball; removing it"; rm -f "$cache/$tarball"; exit 1; }
fi

log "unpacking $tarball"
rm -rf "$tree" "$cache/unpack.tmp"
mkdir -p "$cache/unpack.tmp"
tar -xJf "$cache/$tarball" -C "$cache/unpack.tmp"
top=$(find "$cache/unpack.tmp" -mindepth 1 -maxdepth 1 -type d | head -n 1)
[ -f "$top/src/lammps.h" ] || { log "unexpected tarball layout"; exit 1; }
mv "$top" "$tree"
rm -rf "$cache/unpack.tmp"
touch "$tree/.granfric-verified"
echo "$tree"
