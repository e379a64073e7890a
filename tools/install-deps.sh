#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
# Install the Debian packages GRANFRIC needs, only if some are missing (idempotent).
# Run as root (CI and these machines) or it prints the apt-get command to run.
set -euo pipefail
pkgs=(cmake ninja-build g++ ccache xz-utils libopenmpi-dev openmpi-bin
      googletest libgtest-dev libgmock-dev libyaml-dev libyaml-cpp-dev
      python3 python3-numpy python3-scipy python3-matplotlib python3-pytest python3-tqdm python3-yaml)
# the LIGGGHTS host (tools/liggghts; GRANFRIC_LIGGGHTS=0: not wanted)
[ "${GRANFRIC_LIGGGHTS:-1}" = 1 ] && pkgs+=(libliggghts-dev)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "install-deps: installing ${missing[*]}" >&2
if [ "$(id -u)" != 0 ]; then
  echo "install-deps: not root; please run: apt-get install -y ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq >&2
apt-get install -y -qq "${missing[@]}" >&2
