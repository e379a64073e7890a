# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""The catalogue of bad inputs (unittest/lammps/error_catalogue.yaml) under the LIGGGHTS host.

Each entry's setup and input, with LAMMPS's `comm_modify vel` written as LIGGGHTS's
`communicate single vel` (in the expected message too) and LAMMPS's default region units
(lattice) said explicitly, runs through tools/liggghts. An entry applies when LIGGGHTS reads
its setup and every input line but the last; then the last line must end the run with an ERROR
line that holds the entry's text, as under LAMMPS. An error before the last line that comes from
GRANFRIC's sources (a valid input refused) fails the test; one from LIGGGHTS's own sources (a
command or syntax LIGGGHTS 3.8 lacks) means the entry does not apply. Most entries must apply.
"""
import os
import re
import subprocess
from concurrent.futures import ThreadPoolExecutor

import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
CATALOGUE = os.path.join(ROOT, "unittest", "lammps", "error_catalogue.yaml")
LIGGGHTS = os.path.join(ROOT, "tools", "liggghts")
ERROR = re.compile(r"^ERROR(?: on proc \d+)?: (.*) \(([^():]*):\d+\)\s*$")


def to_liggghts(text):
    """LAMMPS's ghost velocities and its default region units (lattice, once a lattice is set)
    in LIGGGHTS's words"""
    out, lattice = [], False
    for ln in re.sub(r"comm_modify vel (yes|no)", r"communicate single vel \1", text).split("\n"):
        words = ln.split()
        lattice = lattice or (words[:1] == ["lattice"])
        if words[:1] == ["region"] and "units" not in words and lattice:
            ln += " units lattice"
        out.append(ln)
    return "\n".join(out)


def run_entry(entry, setups, work):
    """(name, outcome, detail): outcome 'ok', 'fail' or 'n/a'"""
    if entry.get("host", "liggghts") != "liggghts":
        return entry["name"], "n/a", "an entry for LAMMPS only"
    lines = [ln for ln in to_liggghts(setups[entry["setup"]] + "\n" + entry["input"]).split("\n") if ln.strip()]
    script = os.path.join(work, entry["name"] + ".in")
    with open(script, "w") as f:
        f.write("\n".join(lines) + "\n")
    p = subprocess.run([LIGGGHTS, "-echo", "screen", "-in", script, "-log", "none"], cwd=work,
                       capture_output=True, text=True, errors="replace")
    out = p.stdout.split("\n")
    where = next((k for k, ln in enumerate(out) if ERROR.match(ln)), None)
    if where is None:
        return entry["name"], "fail", "no ERROR line"
    msg, source = ERROR.match(out[where]).groups()
    commands = {x.strip() for x in lines}
    echoed = [ln.strip() for ln in out[:where] if ln.strip() in commands]
    ours = "GRANFRIC" in source
    at_last = bool(echoed) and echoed[-1] == lines[-1].strip()
    if not at_last:
        return entry["name"], ("fail" if ours else "n/a"), f"{msg} ({source}) before the last line"
    if to_liggghts(entry["error"]) in msg:
        return entry["name"], "ok", msg
    return entry["name"], ("fail" if ours else "n/a"), f"{msg} ({source})"


def test_catalogue_under_liggghts(tmp_path):
    doc = yaml.safe_load(open(CATALOGUE))
    setups, entries = doc["setups"], doc["entries"]
    with ThreadPoolExecutor(max_workers=2) as pool:
        results = list(pool.map(lambda e: run_entry(e, setups, str(tmp_path)), entries))
    failed = [r for r in results if r[1] == "fail"]
    applied = [r for r in results if r[1] == "ok"]
    skipped = [r for r in results if r[1] == "n/a"]
    print(f"{len(applied)} of {len(entries)} entries apply under LIGGGHTS; not applicable:")
    for name, _, detail in skipped:
        print(f"  {name}: {detail}")
    assert not failed, "\n".join(f"{n}: {d}" for n, _, d in failed)
    assert len(applied) >= 0.8 * len(entries)
