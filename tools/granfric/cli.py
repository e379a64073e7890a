# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Shared command-line pieces of the scene scripts (herbst, luding, risso)."""
import argparse
import csv
import importlib
import os
import sys

DEPS = ("numpy", "scipy", "matplotlib")
DEBIAN = "python3-numpy python3-scipy python3-matplotlib"


def missing_deps():
    """The names of numpy, scipy and matplotlib that cannot be imported."""
    missing = []
    for name in DEPS:
        try:
            importlib.import_module(name)
        except ImportError:
            missing.append(name)
    return missing


def require_deps():
    """0 when numpy, scipy and matplotlib import; otherwise a message on stderr naming the Debian
    packages and the install script, and 2 (the exit status for the caller)."""
    missing = missing_deps()
    if not missing:
        return 0
    sys.stderr.write(
        f"granfric: the Python tools need numpy, scipy and matplotlib; {', '.join(missing)} "
        f"cannot be imported by {sys.executable}.\n"
        f"Install Debian's packages {DEBIAN} (as root: bash tools/install-deps.sh, or "
        f"apt-get install {DEBIAN}) and run the tools with /usr/bin/python3.\n")
    return 2


def logs_dir(out):
    """out/logs (created): where the LAMMPS logs and their side files of a job go, below the
    figures and reports at the top of out."""
    path = os.path.join(out, "logs")
    os.makedirs(path, exist_ok=True)
    return path


def scene_args(argv, doc, default_out, quick_help, full_help, extra=None):
    """--out DIR (created), --quick (default) or --full; extra(parser) may add more options.
    a.logs is DIR/logs (created) for the LAMMPS logs."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    if extra:
        extra(ap)
    ap.add_argument("--out", default=default_out,
                    help=f"figures and report here, LAMMPS logs in its logs/ (default {default_out})")
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--quick", action="store_true", help=quick_help)
    g.add_argument("--full", action="store_true", help=full_help)
    a = ap.parse_args(argv)
    os.makedirs(a.out, exist_ok=True)
    a.logs = logs_dir(a.out)
    return a


def progress(iterable, desc):
    """A tqdm progress bar when python3-tqdm is installed."""
    try:
        from tqdm import tqdm
        return tqdm(iterable, desc=desc)
    except ImportError:
        return iterable


def write_rows(path, rows, float_format=None):
    """rows (dicts with the same keys) as a CSV table at path, its folder made if missing;
    floats formatted with float_format (e.g. "{:.6g}") if given. Returns path."""
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: (float_format.format(v) if float_format and isinstance(v, float) else v)
                        for k, v in r.items()})
    return path


def write_report(out, lines):
    """lines as out/report.md (out made if missing), and on standard output"""
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "report.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
