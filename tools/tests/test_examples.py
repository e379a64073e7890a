# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Every example input, run whole in its short form on 1 and 2 MPI ranks, against its reference
log (examples/*/log.DDMonYY.NAME.g++.NP, tools/regenerate-example-logs): the same thermo blocks,
columns and steps; the first row of the run (the initial state) to 1e-10; later rows within the
per-column tolerances of granfric.examples.TOL. Those come from measurement: 2.5 times the
largest deviation seen between 1 and 2 ranks or between two seeds, because the hard-sphere gas
is chaotic and another build or rank count follows another trajectory after a few collisions
per particle. A rerun of the same build on 1 rank is identical bit for bit: its every printed
value must equal the serial log's, so a log made before a change that moved trajectories
fails (regenerate it with tools/regenerate-example-logs in the same commit). A changed
restitution coefficient must make the comparison fail, and each example README must show the
command of its reference logs."""
import os

import pytest

from granfric import examples, lammpslog

CASES = [(e, np) for e in examples.SHORT for np in examples.RANKS]


@pytest.mark.parametrize("entry,np", CASES, ids=[f"{e[2]}.np{np}" for e, np in CASES])
def test_example_matches_its_reference_log(entry, np, tmp_path):
    ref = examples.reference(entry, np)
    assert ref, f"no reference log for {entry[2]} on {np} ranks (tools/regenerate-example-logs)"
    new = examples.run(entry, np, str(tmp_path), "log.new")
    bad = examples.compare(ref, new, examples.TOL[entry[2]])
    assert not bad, "\n".join(bad)
    if np == 1:
        # (a serial rerun of the build that wrote the log is the same trajectory: a stale log,
        # made before a change that moved trajectories, fails here)
        stale = examples.differences_as_printed(ref, new)
        assert not stale, "the serial reference log is not this build's (tools/regenerate-example-logs):\n" + \
            "\n".join(stale)


# restitution changes that a run must not pass for: smaller than the paper scans' steps
CHANGED = [("cooling2d", {"r": 0.8}), ("cooling3d", {"r": 0.8}), ("driven", {"r": 0.85}),
           ("compaction", {"q": 0.05}), ("convection", {"q": 0.02}), ("shear2d", {"r": 0.8}),
           ("shear3d", {"r": 0.8}), ("couette2d", {"r": 0.9}), ("couette3d", {"r": 0.9}),
           ("convection3d", {"q": 0.02}), ("cooling_ve", {"r": 0.6})]


@pytest.mark.parametrize("name,change", CHANGED, ids=[c[0] for c in CHANGED])
def test_a_changed_restitution_fails_the_comparison(name, change, tmp_path):
    entry = next(e for e in examples.SHORT if e[2] == name)
    new = examples.run(entry, 1, str(tmp_path), "log.changed", extra=change)
    assert examples.compare(examples.reference(entry, 1), new, examples.TOL[name])


def test_a_changed_initial_state_fails_the_first_row(tmp_path):
    # another seed: other initial velocities, the same temperature; the convection order
    # parameters of step 0 (the initial flow field) differ
    entry = next(e for e in examples.SHORT if e[2] == "convection")
    new = examples.run(entry, 1, str(tmp_path), "log.seed", extra={"seed": 777})
    bad = examples.compare(examples.reference(entry, 1), new, examples.TOL["convection"])
    assert any("step 0:" in b for b in bad), bad


@pytest.mark.parametrize("entry,np", CASES, ids=[f"{e[2]}.np{np}" for e, np in CASES])
def test_example_readme_shows_the_reference_command(entry, np):
    ref = examples.reference(entry, np)
    assert ref
    with open(os.path.join(examples.EXAMPLES, entry[0], "README.md")) as f:
        readme = f.read()
    assert examples.command(entry, np, os.path.basename(ref)) in readme


def test_a_changed_printed_digit_fails_the_serial_check(tmp_path):
    # the serial check compares every printed value: one digit of the last row is enough
    ref = examples.reference(examples.SHORT[0], 1)
    with open(ref) as f:
        lines = f.read().split("\n")
    _, data = lammpslog.read_thermo_blocks(ref)[-1]
    step = f"{data[-1, 0]:.0f}"
    at = max(i for i, l in enumerate(lines) if l.split()[:1] == [step])
    words = lines[at].split()
    words[-1] = words[-1][:-1] + ("2" if words[-1][-1] == "1" else "1")
    lines[at] = " ".join(words)
    new = tmp_path / "log.changed"
    new.write_text("\n".join(lines))
    assert examples.differences_as_printed(ref, str(new))
    assert not examples.differences_as_printed(ref, ref)


def test_warning_within_a_thermo_table_is_passed_over(tmp_path):
    """A fix that warns once during a run prints the warning between two thermo rows: the table
    goes on after it (else the rows after it would be lost and the logs compared short)."""
    log = tmp_path / "log.warned"
    log.write_text("   Step          Temp     \n         0   1.0   \n        10   0.9   \n"
                   "WARNING: Fix hardsphere/ed ed: in step 12 one atom collided 20000 times (x.cpp:1)\n"
                   "        20   0.8   \n        30   0.7   \nLoop time of 1.0 on 1 procs\n")
    blocks = lammpslog.read_thermo_blocks(str(log))
    assert len(blocks) == 1
    cols, data = blocks[0]
    assert cols == ["Step", "Temp"]
    assert data[:, 0].tolist() == [0, 10, 20, 30]
