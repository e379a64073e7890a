# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""The viscoelastic normal restitution through the C API (granfric.core): E(delta) against
SciPy's integration of the collision's equation of motion, and collisions with the two
models (a measured pair r at vref, material constants with each pair's sizes and masses)."""
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from granfric import core


def scipy_restitution(delta):
    """x'' = -x^(3/2) - delta x^(1/2) x' from x = 0, x' = 1 until the force x + delta x' (times
    x^(1/2)) vanishes; E = -x' there"""
    def rhs(t, y):
        r = math.sqrt(max(y[0], 0.0))
        return [y[1], -r * (y[0] + delta * y[1])]

    def end(t, y):
        return y[0] + delta * y[1] if t > 1e-9 else 1.0
    end.terminal, end.direction = True, -1
    s = solve_ivp(rhs, [0, 100], [0.0, 1.0], events=end, rtol=1e-12, atol=1e-14, method="DOP853")
    return -s.y_events[0][0][1]


@pytest.mark.parametrize("delta", [0.003, 0.05, 0.4, 1.7, 6.0, 30.0, 300.0, 2e4])
def test_restitution_function_agrees_with_scipy(delta):
    # (past 64 relatively: E is small there; 2e4 is on the strongly damped asymptote)
    assert core.viscoelastic_restitution(delta) == pytest.approx(scipy_restitution(delta), abs=1e-9, rel=1e-6)


def test_measured_pair_sets_the_restitution_at_each_speed():
    vref, r = 1.5, 0.7
    b = brentq(lambda d: core.viscoelastic_restitution(d) - r, 1e-9, 100.0, xtol=1e-15) / vref ** 0.2
    for speed in (0.05, 1.5, 6.0):
        b1 = core.Body(v=(-speed, 0.2, 0.0), m=1.3, a=0.4)
        b2 = core.Body(v=(0.0, 0.0, 0.0), m=0.7, a=0.6)
        c = core.collide("walton", [r, 0.3, 0.5], b1, b2, (1.0, 0.0, 0.0), restitution=("viscoelastic", [vref]))
        after = c.v1[0] - c.v2[0]    # no spins: the normal contact velocity
        e = core.viscoelastic_restitution(b * speed ** 0.2)
        assert after == pytest.approx(e * speed, rel=1e-12)
        if speed == vref:
            assert e == pytest.approx(r, rel=1e-12)
        # momentum
        assert 1.3 * c.v1 + 0.7 * c.v2 == pytest.approx(np.array([-1.3 * speed, 1.3 * 0.2, 0.0]), abs=1e-13)


def test_material_constants_use_the_pairs_sizes_and_masses():
    Y, nu, A = 2e4, 0.25, 0.01
    for m2, a2 in ((1.0, 0.5), (8.0, 1.0)):
        b1 = core.Body(v=(-2.0, 0.0, 0.0), m=1.0, a=0.5)
        b2 = core.Body(m=m2, a=a2)
        c = core.collide("rough", [None, 0.0], b1, b2, (1.0, 0.0, 0.0),
                         restitution=("viscoelastic/material", [Y, nu, A]))
        R, m = 0.5 * a2 / (0.5 + a2), m2 / (1.0 + m2)
        alpha = 1.5 ** 1.5 * Y * math.sqrt(R) / (m * (1 - nu * nu))
        e = core.viscoelastic_restitution(A * alpha ** 0.4 * 2.0 ** 0.2)
        assert c.v1[0] - c.v2[0] == pytest.approx(2.0 * e, rel=1e-12)
        assert e < 0.95


def test_bad_models_are_refused():
    b = core.Body(v=(-1.0, 0.0, 0.0))
    with pytest.raises(ValueError, match="unknown restitution model"):
        core.collide("rough", [0.9, 0.0], b, core.Body(), (1, 0, 0), restitution=("plastic", [1.0]))
    with pytest.raises(ValueError, match="None"):
        core.collide("rough", [0.9, 0.0], b, core.Body(), (1, 0, 0),
                     restitution=("viscoelastic/material", [1e4, 0.3, 0.01]))
    with pytest.raises(ValueError, match="out of range"):
        core.collide("rough", [0.9, 0.0], b, core.Body(), (1, 0, 0), restitution=("viscoelastic", [0.0]))
