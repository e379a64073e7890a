#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
# Make Debian source packages of trixie (LAMMPS 4Feb2025) and bookworm (googletest 1.12.1)
# available to apt-get source. Idempotent; needs root the first time.
set -euo pipefail
src_list=/etc/apt/sources.list.d/granfric-trixie-src.sources
want="Types: deb-src
URIs: http://deb.debian.org/debian
Suites: trixie bookworm
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg"
if [ -f "$src_list" ] && [ "$(cat "$src_list")" = "$want" ]; then
  exit 0
fi
if [ "$(id -u)" != 0 ]; then
  echo "deb-src: need root to write $src_list (or pass -D LAMMPS_SOURCE_DIR to use your own LAMMPS)" >&2
  exit 1
fi
echo "deb-src: writing $src_list" >&2
printf '%s\n' "$want" > "$src_list"
apt-get update -qq
