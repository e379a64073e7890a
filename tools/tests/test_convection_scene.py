# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""The convection scene (examples/convection, Risso Figs 3-5) through LAMMPS: a bed of 1000
frictional discs on the vibrated base is static at kappa = 0.005 and convects in one roll at
kappa = 0.03 (q = 0, g = 0.015625), classified by K-means on (Psi1, Psi2); the static bed
is a gas, not collapsed."""

from granfric import convection


def test_static_and_one_roll_states(tmp_path):
    states = {}
    for kappa in (0.005, 0.03):
        log, _ = convection.run_point(kappa, 0.0, convection.G_HIGH, 2000, 50, str(tmp_path))
        a = convection.analyse(log)
        states[kappa] = a
    assert states[0.005]["state"] == 0, states[0.005]["class"]
    assert states[0.03]["state"] == 1, states[0.03]["class"]
    # one roll: |Psi1| well above the static bed's scatter (over 12 seeds of both runs the
    # ratio lay between 4.2 and 7.9, mean 6.4)
    c = states[0.03]["class"]["clusters"][0]["centre"]
    assert abs(c[0]) > 3 * states[0.005]["class"]["sigma"]
    # more loss per collision, lower bed
    assert states[0.03]["ycm"] < states[0.005]["ycm"]
    # the nearly elastic bed is a hot gas filling the box (mean height near half the box), not a
    # compact layer
    y, nu = states[0.005]["profile"]
    assert not convection.collapsed(y, nu)
    assert nu.max() < 0.3
