# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Readers for LAMMPS output: thermo blocks of log files and fix ave/time files."""
import numpy as np


def read_thermo_blocks(path):
    """Every thermo table of a LAMMPS log file, one per run section in order: a list of
    (column names, numpy array of rows). A warning printed within a table (a fix warns once
    during a run) is passed over."""
    blocks = []
    cols = None
    rows = []
    with open(path) as f:
        for line in f:
            words = line.split()
            if words and words[0] == "Step":
                cols, rows = words, []
                continue
            if cols is not None:
                if words and words[0] == "WARNING:":
                    continue
                if len(words) == len(cols):
                    try:
                        rows.append([float(w) for w in words])
                        continue
                    except ValueError:
                        pass
                if rows or (words and words[0] == "Loop"):
                    blocks.append((cols, rows))
                cols = None
    if cols is not None and rows:
        blocks.append((cols, rows))
    return [(cols, np.array(rows, dtype=float).reshape(-1, len(cols))) for cols, rows in blocks]


def read_thermo(path, block=-1):
    """Thermo table of a LAMMPS log file as a dict column -> numpy array. block selects one run
    section (default: the last one)."""
    blocks = read_thermo_blocks(path)
    if not blocks:
        raise ValueError(f"no thermo output in {path}")
    cols, data = blocks[block]
    return {c: data[:, k] for k, c in enumerate(cols)}


def read_ave_time(path):
    """A fix ave/time file (scalar/vector mode): dict column -> array (column names from the
    second comment line)."""
    names, rows = None, []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                words = line[1:].split()
                if words:
                    names = words
                continue
            if line.strip():
                rows.append([float(w) for w in line.split()])
    data = np.array(rows, dtype=float)
    names = names if names and len(names) == data.shape[1] else [f"c{k}" for k in range(data.shape[1])]
    return {n: data[:, k] for k, n in enumerate(names)}


def block_mean(x, nblocks=4):
    """Mean of a time series and its standard error from the means of nblocks consecutive
    blocks (nan with fewer than two non-empty blocks)."""
    x = np.asarray(x, dtype=float)
    means = np.array([b.mean() for b in np.array_split(x, nblocks) if len(b)])
    err = float(means.std(ddof=1) / np.sqrt(len(means))) if len(means) > 1 else float("nan")
    return float(x.mean()), err


def steady_line(path):
    """The closing line 'steady: name value name value ...' that an example prints (print
    command) as a dict of floats ('collisions/(particle time)' is read as 'coll')."""
    with open(path) as f:
        for line in f:
            line = line.strip()
            if line.startswith("steady: "):
                w = line[len("steady: "):].replace("collisions/(particle time)", "coll").split()
                return {w[k]: float(w[k + 1]) for k in range(0, len(w), 2)}
    raise ValueError("no steady state line in " + path)
