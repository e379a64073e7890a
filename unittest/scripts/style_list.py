#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""GRANFRIC's one list of styles (GRANFRIC_STYLES in granfric_styles.h, which the plugin and the
LIGGGHTS host expand) against what a LAMMPS with GRANFRIC in-tree compiles in: the PairStyle(),
FixStyle() and ComputeStyle() lines of the style headers, from which LAMMPS generates its
style_*.h. Both must name the same styles, with the same classes, in the same headers; each such
header must be one LAMMPS looks in (pair_*.h, fix_*.h, compute_*.h) and be included by the list.
  style_list.py <src/GRANFRIC>                      the list against the headers
  style_list.py <src/GRANFRIC> --host <lmp>         also: `lmp -h` of a LAMMPS built with GRANFRIC
                                                    in-tree names every style of the list, and no
                                                    other hardsphere style"""
import argparse
import glob
import os
import re
import subprocess
import sys

KINDS = {"PAIR": "Pair", "FIX": "Fix", "COMPUTE": "Compute"}
# (LAMMPS's CMake and make builds look for a style's macro only in headers named like this)
PREFIX = {"Pair": "pair_", "Fix": "fix_", "Compute": "compute_"}
SECTION = {"Pair": "Pair styles", "Fix": "Fix styles", "Compute": "Compute styles"}


def listed_styles(src):
    """{(kind, name, class, header)} of GRANFRIC_STYLES and the headers the list includes."""
    with open(os.path.join(src, "granfric_styles.h")) as f:
        text = f.read()
    includes = set(re.findall(r'^#include "([^"]+)"', text, re.M))
    body = text[text.index("#define GRANFRIC_STYLES"):].replace("\\\n", " ")
    entries = re.findall(r'\b(PAIR|FIX|COMPUTE)\(\s*"([^"]+)"\s*,\s*(\w+)\s*,\s*"([^"]+)"', body)
    return {(KINDS[k], name, cls, hdr) for k, name, cls, hdr in entries}, includes


def header_styles(src):
    """{(kind, name, class, header)} of every *Style(name,Class) line of the style headers."""
    found = set()
    for path in sorted(glob.glob(os.path.join(src, "*.h"))):
        with open(path) as f:
            for kind, name, cls in re.findall(r"^\s*(\w+)Style\(\s*([^,\s]+)\s*,\s*(\w+)\s*\)",
                                              f.read(), re.M):
                found.add((kind, name, cls, os.path.basename(path)))
    return found


def host_styles(lmp):
    """{(kind, name)} of the hardsphere styles in the style sections of `lmp -h`."""
    out = subprocess.run([lmp, "-h"], capture_output=True, text=True, check=True).stdout
    found = set()
    for kind, title in SECTION.items():
        m = re.search(r"^\* " + title + r":?\n(.*?)(?=^\* |\Z)", out, re.M | re.S)
        if not m:
            sys.exit(f"FAILED: `{lmp} -h` has no section '* {title}'")
        found |= {(kind, n) for n in m.group(1).split() if n.startswith("hardsphere/")}
    return found


def describe(entries):
    return "\n".join(f"  {k}Style({n},{c}) in {h}" for k, n, c, h in sorted(entries))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("src", help="src/GRANFRIC")
    ap.add_argument("--host", help="lmp of a LAMMPS built with GRANFRIC in-tree")
    args = ap.parse_args()
    listed, includes = listed_styles(args.src)
    if not listed:
        sys.exit("FAILED: no style found in GRANFRIC_STYLES of granfric_styles.h")
    headers = header_styles(args.src)
    bad = []
    if listed - headers:
        bad.append("in granfric_styles.h, not in the headers' *Style() lines:\n"
                   + describe(listed - headers))
    if headers - listed:
        bad.append("in the headers' *Style() lines, not in granfric_styles.h:\n"
                   + describe(headers - listed))
    misnamed = {e for e in headers if e[0] not in PREFIX or not e[3].startswith(PREFIX[e[0]])}
    if misnamed:
        bad.append("in headers LAMMPS does not look in for that kind of style:\n"
                   + describe(misnamed))
    if {e[3] for e in listed} - includes:
        bad.append("headers of the list that granfric_styles.h does not include: "
                   + ", ".join(sorted({e[3] for e in listed} - includes)))
    if args.host:
        want = {(k, n) for k, n, _, _ in listed}
        have = host_styles(args.host)
        if want != have:
            bad.append(f"`{args.host} -h` differs from the list: missing "
                       f"{sorted(want - have)}, not listed {sorted(have - want)}")
    if bad:
        print("FAILED: the style list and the in-tree package disagree")
        print("\n".join(bad))
        return 1
    where = f" and in {args.host}" if args.host else ""
    print(f"PASSED: the {len(listed)} styles of granfric_styles.h are the headers' *Style() "
          f"lines{where}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
