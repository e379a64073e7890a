# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Shared command-line pieces of the scene scripts (herbst, luding, risso)."""
import argparse
import os


def scene_args(argv, doc, default_out, quick_help, full_help, extra=None):
    """--out DIR (created), --quick (default) or --full; extra(parser) may add more options."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    if extra:
        extra(ap)
    ap.add_argument("--out", default=default_out)
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--quick", action="store_true", help=quick_help)
    g.add_argument("--full", action="store_true", help=full_help)
    a = ap.parse_args(argv)
    os.makedirs(a.out, exist_ok=True)
    return a


def progress(iterable, desc):
    """A tqdm progress bar when python3-tqdm is installed."""
    try:
        from tqdm import tqdm
        return tqdm(iterable, desc=desc)
    except ImportError:
        return iterable
