# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Reference logs of the examples: every example input run whole in a short form (variables
that shorten it to a few seconds), named the way LAMMPS names its example logs,
log.DDMonYY.NAME.g++.NP (NP MPI ranks), next to the input.

    tools/regenerate-example-logs          (= PYTHONPATH=tools /usr/bin/python3 -m granfric.examples)

regenerates all of them (the old ones of each example are removed; the one machine-specific
line, the directory LAMMPS loaded the plugin from, is written as <build>/plugins). compare()
checks a new log against a reference the way tools/tests/test_examples.py does, within the
tolerances of two realisations of the same gas; differences_as_printed() checks that a serial
run reproduces the serial reference log value by value, as it does with the build (compiler
and flags) that wrote it.
"""
import glob
import os
import re
import sys
import tempfile
import time

import numpy as np

from . import lammpslog, lmp

EXAMPLES = os.path.join(lmp.ROOT, "examples")

# (directory under examples/, input, log name, variables of the short form)
SHORT = [
    ("cooling", "in.cooling2d", "cooling2d", {"tend": 400}),
    ("cooling", "in.cooling3d", "cooling3d", {"tend": 400}),
    ("driven", "in.driven", "driven", {"nside": 32, "tend": 200}),
    ("compaction", "in.compaction", "compaction", {"tend": 4000}),
    ("convection", "in.convection", "convection", {"periods": 1000}),
    ("shear", "in.shear2d", "shear2d", {"nside": 32, "trelax": 200, "tavg": 800}),
    ("shear", "in.shear3d", "shear3d", {"nside": 10, "trelax": 200, "tavg": 800}),
    ("couette", "in.couette2d", "couette2d", {"trelax": 400, "tavg": 4000, "nblock": 4}),
    ("couette", "in.couette3d", "couette3d", {"trelax": 200, "tavg": 2000, "nblock": 4}),
    ("convection3d", "in.convection3d", "convection3d", {"periods": 500}),
    ("viscoelastic", "in.cooling_ve", "cooling_ve", {"nside": 10, "nrun": 5}),
]
RANKS = (1, 2)

# Later rows (every row but the first of the whole run): |new - ref| <= tol * max|ref| over the
# column, tol per example and column (default RTOL; None: the column is not compared row by row,
# its samples fluctuate by as much as their scale between runs). The values: 2.5 times the
# largest deviation measured between 1 and 2 MPI ranks, or between two seeds (seed 777 against
# 4321), rounded up to 0.02, 0.05, 0.1, 0.2, 0.3 or 0.5. The dynamics is chaotic: a run on 2
# ranks (or from another build) follows a different trajectory after a few collisions per
# particle, so later rows agree only as two realisations of the same gas do; a rerun of the
# same build on 1 rank reproduces the log bit for bit.
RTOL = 0.05
TOL = {
    "cooling2d": {"Press": 0.02, "c_T[1]": 0.05, "c_T[2]": 0.2, "c_T[3]": 0.2, "f_ed[2]": 0.05,
                  "c_C[1]": 0.5, "v_flowfrac": None},
    "cooling3d": {"Press": 0.02, "c_T[1]": 0.05, "c_T[2]": 0.2, "c_T[3]": 0.2, "f_ed[2]": 0.02,
                  "c_C[1]": 0.3, "v_flowfrac": None},
    "driven": {"Press": 0.05, "c_T[1]": 0.2, "c_T[2]": 0.5, "c_T[3]": 0.5, "f_ed[2]": 0.02,
               "c_C[1]": None, "c_C[3]": None, "f_ed[9]": 0.05, "f_ed[3]": 0.05},
    "compaction": {"v_ycm": None, "c_T[1]": 0.1, "c_T[2]": None, "f_ed[2]": 0.2, "f_ed[10]": 0.1},
    "convection": {"c_psi[1]": None, "c_psi[2]": None, "v_ycm": 0.3, "c_T[1]": 0.3,
                   "c_T[2]": 0.5, "f_ed[2]": 0.2, "f_ed[10]": 0.05, "f_ed[7]": None},
    "shear2d": {"c_T[1]": 0.5, "c_T[2]": 0.5, "c_T[3]": None, "v_pxx": 0.3, "v_pyy": 0.5,
                "v_pxy": None, "f_ed[2]": 0.05},
    "shear3d": {"c_T[1]": 0.5, "c_T[2]": 0.5, "c_T[3]": 0.3, "v_pxx": 0.5, "v_pyy": 0.5,
                "v_pxy": None, "f_ed[2]": 0.05},
    "couette2d": {"c_Tp": 0.3, "f_th[1]": None, "f_th[2]": None, "f_th[3]": None, "f_th[4]": None,
                  "f_ed[2]": 0.05, "f_blk[1]": 0.3, "f_blk[2]": 0.5, "f_blk[3]": 0.5, "f_blk[4]": 0.3},
    "couette3d": {"c_Tp": 0.2, "f_th[1]": None, "f_th[2]": None, "f_th[3]": None, "f_th[4]": None,
                  "f_ed[2]": 0.05, "f_blk[1]": 0.2, "f_blk[2]": 0.3, "f_blk[3]": 0.2, "f_blk[4]": 0.2},
    "convection3d": {"c_psi[1]": None, "c_psi[2]": None, "c_psi[3]": None, "c_psi[4]": None,
                     "v_zcm": 0.05, "c_T[1]": 0.05, "c_T[2]": 0.2, "f_ed[2]": 0.05,
                     "f_ed[10]": 0.05, "f_ed[7]": 0.2},
    "cooling_ve": {"c_T[1]": 0.2, "f_ed[2]": 0.02, "c_C[1]": None, "v_flowfrac": None},
}
EXACT = 1e-10     # the first row of the run: the initial state, no dynamics yet


def log_name(name, np, date=None):
    """log.DDMonYY.NAME.g++.NP with the date of today (LAMMPS's convention, e.g. 3Dec26)."""
    t = time.localtime() if date is None else date
    return f"log.{t.tm_mday}{time.strftime('%b%y', t)}.{name}.g++.{np}"


def command(entry, np, log):
    """The command line of one short run, from the example's directory."""
    _, script, _, variables = entry
    words = ["../../tools/lmp"] + (["-np", str(np)] if np > 1 else []) + ["-in", script]
    for k, v in variables.items():
        words += ["-var", k, str(v)]
    return " ".join(words + ["-log", log])


def reference(entry, np):
    """Path of the reference log of an example on np ranks (None when there is none)."""
    directory, _, name, _ = entry
    found = sorted(glob.glob(os.path.join(EXAMPLES, directory, f"log.*.{name}.g++.{np}")))
    return found[-1] if found else None


def run(entry, np, workdir, log, extra=None, exe=None):
    """Run the short form of an example in workdir (its side files land there) with -log log;
    extra variables override or add to the short form's; exe: another LAMMPS (serial)."""
    directory, script, _, variables = entry
    v = dict(variables, **(extra or {}))
    lmp.run(os.path.join(EXAMPLES, directory, script), v, cwd=workdir, np=np, log=log, exe=exe)
    return os.path.join(workdir, log)


def compare(ref, new, tol=None, exact=EXACT):
    """Differences between the thermo output of two logs (empty list: they agree): the same
    blocks, columns and steps; the first row of the run to `exact` (relative to the value, or
    absolute below 1); every later value within tol[column] (default RTOL) of the column's
    largest magnitude in the reference."""
    tol = tol or {}
    a, b = lammpslog.read_thermo_blocks(ref), lammpslog.read_thermo_blocks(new)
    if len(a) != len(b):
        return [f"{len(b)} thermo blocks, the reference has {len(a)}"]
    bad = []
    for k, ((ca, da), (cb, db)) in enumerate(zip(a, b)):
        if ca != cb:
            bad.append(f"block {k}: columns {cb}, the reference has {ca}")
            continue
        if da.shape != db.shape or not np.array_equal(da[:, 0], db[:, 0]):
            bad.append(f"block {k}: steps differ from the reference's")
            continue
        for j, c in enumerate(ca[1:], start=1):
            x, y = da[:, j], db[:, j]
            if k == 0:
                d0 = abs(y[0] - x[0])
                if d0 > exact * max(1.0, abs(x[0])):
                    bad.append(f"block {k} {c} step {da[0, 0]:.0f}: {y[0]!r} vs {x[0]!r}")
                x, y, steps = x[1:], y[1:], da[1:, 0]
            else:
                steps = da[:, 0]
            rtol = tol.get(c, RTOL)
            if not len(x) or rtol is None:
                continue
            scale = max(np.max(np.abs(da[:, j])), 1e-300)
            dev = np.abs(y - x) / scale
            i = int(np.argmax(dev))
            if dev[i] > rtol:
                bad.append(f"block {k} {c} step {steps[i]:.0f}: {y[i]!r} vs {x[i]!r} "
                           f"({dev[i]:.3g} of the column's scale, more than {rtol})")
    return bad


def differences_as_printed(ref, new):
    """Differences between the thermo output of two logs value by value, as printed (empty
    list: every row of every block is the same): what a serial rerun of the build that wrote
    the reference gives."""
    a, b = lammpslog.read_thermo_blocks(ref), lammpslog.read_thermo_blocks(new)
    if len(a) != len(b):
        return [f"{len(b)} thermo blocks, the reference has {len(a)}"]
    bad = []
    for k, ((ca, da), (cb, db)) in enumerate(zip(a, b)):
        if ca != cb or da.shape != db.shape:
            bad.append(f"block {k}: other columns or rows than the reference's")
            continue
        rows, cols = np.nonzero(da != db)
        if len(rows):
            i, j = rows[0], cols[0]
            bad.append(f"block {k} {ca[j]} step {da[i, 0]:.0f}: {db[i, j]!r} vs {da[i, j]!r} "
                       f"(the first of {len(rows)} values that differ)")
    return bad


def regenerate(out=sys.stdout):
    """Run every example in its short form on 1 and 2 ranks; replace its reference logs."""
    for entry in SHORT:
        directory, _, name, _ = entry
        for old in glob.glob(os.path.join(EXAMPLES, directory, f"log.*.{name}.g++.*")):
            os.remove(old)
        for np_ in RANKS:
            log = log_name(name, np_)
            with tempfile.TemporaryDirectory() as work:
                run(entry, np_, work, log)
                with open(os.path.join(work, log)) as f:
                    text = re.sub(r"(?m)^(Loaded \d+ plugins? from ).*$", r"\1<build>/plugins",
                                  f.read())
                with open(os.path.join(EXAMPLES, directory, log), "w") as f:
                    f.write(text)
            out.write(f"examples/{directory}: {command(entry, np_, log)}\n")
    return 0


def check(exe, out=sys.stdout):
    """Run every example in its short form, serially, with the LAMMPS executable exe (e.g. one
    with GRANFRIC built in) and compare with the reference logs on one rank; 0 if all agree."""
    failed = 0
    for entry in SHORT:
        with tempfile.TemporaryDirectory() as work:
            bad = compare(reference(entry, 1), run(entry, 1, work, "log.check", exe=exe),
                          TOL[entry[2]])
        failed += bool(bad)
        out.write(f"{entry[2]}: " + ("agrees with its reference log\n" if not bad else
                                     "FAILED\n  " + "\n  ".join(bad) + "\n"))
    out.write(("FAILED" if failed else "PASSED") + f": {len(SHORT) - failed} of {len(SHORT)} "
              f"examples agree with their reference logs ({exe})\n")
    return 1 if failed else 0


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--check":
        sys.exit(check(os.path.abspath(sys.argv[2])))
    if len(sys.argv) > 1:
        sys.exit("usage: tools/regenerate-example-logs            regenerate the reference logs\n"
                 "       tools/regenerate-example-logs --check LMP  run the examples with LMP "
                 "(serially) and compare")
    sys.exit(regenerate())
