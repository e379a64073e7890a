# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""K-means classification of convection states (Risso Fig. 4) on synthetic (Psi1, Psi2) samples
whose states are known, the collapse test on constructed density profiles, and the command line
`python3 tools/granfric`."""
import os
import subprocess
import sys

import numpy as np
import pytest

from granfric import convection, kmeans

NOISE = 0.03    # per-sample scatter of the order parameters of 1000 discs (measured: 0.01-0.03)


def blob(rng, centre, n):
    return np.asarray(centre) + NOISE * rng.standard_normal((n, 2))


def test_kmeans_finds_well_separated_centres():
    rng = np.random.default_rng(1)
    centres = np.array([[-0.4, 0.0], [0.4, 0.1], [0.0, 0.5]])
    X = np.vstack([blob(rng, c, 200) for c in centres])
    C, labels, inertia = kmeans.kmeans(X, 3, seed=3)
    found = sorted(map(tuple, np.round(C, 1)))
    assert found == sorted(map(tuple, np.round(centres, 1)))
    assert inertia == pytest.approx(((X - C[labels]) ** 2).sum())
    # each true blob is one cluster
    for j in range(3):
        assert len(set(labels[200 * j:200 * (j + 1)])) == 1


def test_kmeans_is_deterministic_for_a_seed():
    rng = np.random.default_rng(2)
    X = np.vstack([blob(rng, c, 100) for c in ((-0.2, 0.0), (0.2, 0.0), (0.0, 0.3))])
    C1, l1, i1 = kmeans.kmeans(X, 3, seed=5)
    C2, l2, i2 = kmeans.kmeans(X, 3, seed=5)
    assert np.array_equal(C1, C2) and np.array_equal(l1, l2) and i1 == i2


def test_kmeans_rejects_bad_k():
    with pytest.raises(ValueError, match="k = 4"):
        kmeans.kmeans(np.zeros((3, 2)), 4)


@pytest.mark.parametrize("centres,weights,rolls,coexisting", [
    ([(0.0, 0.0)], [1.0], 0, [0]),                                   # static bed
    ([(0.15, 0.03)], [1.0], 1, [1]),                                 # one roll, clockwise
    ([(0.14, -0.02), (-0.14, 0.03)], [0.5, 0.5], 1, [1]),            # roll jumping sense
    ([(0.0, 0.13)], [1.0], 2, [2]),                                  # two rolls, rising middle
    ([(0.0, 0.13), (0.14, 0.0), (-0.14, 0.0)], [0.5, 0.25, 0.25], 2, [1, 2]),   # Fig. 4 coexistence
])
def test_classify_known_states(centres, weights, rolls, coexisting):
    rng = np.random.default_rng(7)
    X = np.vstack([blob(rng, c, int(400 * w)) for c, w in zip(centres, weights)])
    r = kmeans.classify(X)
    assert r["rolls"] == rolls
    assert r["coexisting"] == coexisting
    # the heaviest cluster's centre is the heaviest true centre
    assert np.allclose(r["clusters"][0]["centre"], centres[int(np.argmax(weights))], atol=3 * NOISE / 10)


def test_pure_noise_is_one_static_cluster_for_any_seed():
    for seed in range(5):
        X = np.random.default_rng(seed).standard_normal((300, 2)) * NOISE
        r = kmeans.classify(X, seed=seed)
        assert len(r["clusters"]) == 1 and r["rolls"] == 0


def test_collapse_needs_a_dense_layer_above_a_gas():
    y = np.arange(1.0, 60.0, 2.0)
    bed = np.where(y < 20, 0.7, 0.02)               # dense at the bottom: not collapsed
    gas = 0.3 * np.exp(-y / 15.0)                     # fluidised: not collapsed
    lid = np.where((y > 20) & (y < 30), 0.75, 0.05)   # a compact layer floating on a gas
    assert not convection.collapsed(y, bed)
    assert not convection.collapsed(y, gas)
    assert convection.collapsed(y, lid)


def test_transitions_of_a_scan():
    pts = [{"kappa": k, "q": 0.0, "state": s} for k, s in
           ((0.01, 0), (0.04, 1), (0.09, 2), (0.3, 3), (3.0, 2), (10.0, 1))]
    t = convection.transitions(pts)
    assert [x[0] for x in t] == ["0-1", "1-2", "2-collapse", "2-collapse", "1-2"]
    assert t[0][1] == pytest.approx(0.02)


def test_command_line_is_tools_granfric():
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    p = subprocess.run([sys.executable, os.path.join(here, "granfric"), "reproduce", "nowhere"],
                       capture_output=True, text=True)
    assert p.returncode != 0
    assert "herbst2005, luding1998 or risso2005" in p.stderr
