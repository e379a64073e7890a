# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Run GRANFRIC's LAMMPS (tools/lmp) from Python."""
import os
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def run(script, variables=None, cwd=None, np=1, log="none", quiet=True, exe=None):
    """tools/lmp -in script -var k v ...; raises RuntimeError with LAMMPS's error on failure.
    exe: another LAMMPS executable with GRANFRIC's styles (serial only)."""
    cmd = [exe] if exe else [os.path.join(ROOT, "tools", "lmp")]
    if np > 1:
        if exe:
            raise ValueError("another LAMMPS executable runs serially here")
        cmd += ["-np", str(np)]
    cmd += ["-in", script, "-log", log]
    for k, v in (variables or {}).items():
        cmd += ["-var", str(k), str(v)]
    if quiet:
        cmd += ["-screen", "none"]
    p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    if p.returncode != 0:
        err = [l for l in (p.stdout + p.stderr).splitlines() if "ERROR" in l]
        raise RuntimeError(f"LAMMPS failed ({' '.join(cmd)}): {err[:3] or p.stderr[-2000:]}")
    return p
