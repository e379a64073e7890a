# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""Risso's mean energy loss per collision, by Monte Carlo through the C++ law."""
import math

import pytest

from granfric import energyloss


@pytest.mark.parametrize("q", [0.0, 0.025, 0.1, 0.2])
def test_frictionless_equals_eq8(q):
    m, se, sl = energyloss.mean_dE(0.0, q, qt=q, n=100000)
    assert abs(m - energyloss.frictionless_dE(q)) < 4 * se + 1e-15
    assert energyloss.q_eff(energyloss.frictionless_dE(q)) == pytest.approx(q, abs=1e-12)


@pytest.mark.parametrize("kappa,q", [(0.05, 0.0), (0.3, 0.025), (0.3, 0.1), (1.0, 0.05), (5.0, 0.2)])
def test_monte_carlo_equals_closed_form(kappa, q):
    m, se, sl = energyloss.mean_dE(kappa, q, n=100000, seed=7)
    assert abs(m - energyloss.closed_form_dE(kappa, q)) < 4 * se


def test_maximum_loss_near_kappa_0p3():
    # Risso et al.: for fixed q the loss |<dE>| is largest at kappa ~ 0.3 (0.26-0.33 with the
    # averaging of doc/conventions.rst, correction 9)
    for q in (0.0, 0.025, 0.1):
        k = energyloss.kappa_of_max_loss(q)
        assert 0.2 < k < 0.4, (q, k)
    # and it is a maximum of |<dE>| seen by the Monte Carlo too
    lo = energyloss.mean_dE(0.05, 0.025, n=100000, seed=3)
    mid = energyloss.mean_dE(0.3, 0.025, n=100000, seed=4)
    hi = energyloss.mean_dE(3.0, 0.025, n=100000, seed=5)
    assert mid[0] < lo[0] - 4 * (lo[1] + mid[1]) and mid[0] < hi[0] - 4 * (hi[1] + mid[1])


def test_q_eff_undefined_beyond_minus_T0():
    assert energyloss.q_eff(-1.2) is None
    assert energyloss.q_eff(-1.0) == pytest.approx(0.5)
    assert energyloss.q_eff(0.0) == 0.0


# Risso's Table I: <dE> averaged over each transition line and the q_eff printed next to it
TABLE_I = [(-0.090, 0.023), (-0.351, 0.097), (-0.377, 0.105), (-0.614, 0.190),
           (-0.047, 0.012), (-0.137, 0.035), (-0.147, 0.038), (-0.290, 0.079)]


@pytest.mark.parametrize("dE,q", TABLE_I)
def test_table_one_is_consistent_with_eq_9(dE, q):
    """Each printed q_eff is eq 9 of the printed <dE> (to the table's rounding: <dE> to 1e-3
    moves q_eff by at most 1e-3 / (4 sqrt(1 + dE)))."""
    tol = 0.5e-3 + 0.5e-3 / (4.0 * (1.0 + dE) ** 0.5)
    assert energyloss.q_eff(dE) == pytest.approx(q, abs=tol)


def test_laws_come_from_the_core_table():
    from granfric import core
    table = core.laws()
    assert list(table) == ["rough", "walton", "jz"]
    assert [n for n, _ in table["jz"][1]] == ["qn", "qt", "kappa_s", "kappa_d"]
    assert core.law_index("walton", [0.9, math.inf, 0.3])[0] == 1
    with pytest.raises(ValueError, match=r"rtmax = 1.5 is out of range \(-1 <= rtmax <= 1\)"):
        core.collide("walton", [0.9, 0.4, 1.5], core.Body(), core.Body(), (1, 0, 0))
    with pytest.raises(ValueError, match="kappa_d = inf needs kappa_s = inf"):
        core.mean_energy_changes("jz", [0.1, 0.2, 0.3, math.inf], 0.4, 3, 1.0, 1.0, n=10)
    with pytest.raises(ValueError, match="takes 2 coefficients"):
        core.law_index("rough", [0.9])
    with pytest.raises(ValueError, match="unknown collision law 'soft'"):
        core.law_index("soft", [0.9])
