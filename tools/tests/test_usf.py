# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""The DSMC of uniform shear flow (granfric.usf): in the steady state the shear's work, -a P_xy
per volume and time, is what the collisions dissipate (an identity of the balance equation of the
energy, which holds only when the shear term, the finite-density shift of colliding pairs, the
collisional stress and the kernel agree); the normal stresses differ as in shear flow."""
import numpy as np

from granfric import usf


def test_shear_work_is_the_dissipation():
    for law, coeffs, phi in (("rough", (0.9, 0.0), 0.05), ("rough", (0.8, -1.0), 0.2)):
        r = usf.run(law, coeffs, 2, phi, 0.05, 150.0, 150.0, N=4000, seed=5,
                    T0=(0.05 / 0.5 / usf.cooling.collision_frequency(1.0, phi, 0.5, 1.0, 2)) ** 2)
        work = -0.05 * r["P"][0, 1]
        # (the energy of the peculiar motion drifts little over the averaging: within 3 %)
        assert abs(work / r["dissipation"] - 1.0) < 0.03, (law, coeffs, phi, work, r["dissipation"])
        assert r["P"][0, 0] > r["P"][1, 1] > 0.0 > r["P"][0, 1]
        assert 0.2 < r["a_star"] < 1.0


def test_dsmc_agrees_with_the_exact_dynamics_at_finite_density(tmp_path):
    """At area fraction 0.2 the flow's velocity difference across a colliding pair matters (its
    sign changes the steady temperature by a fifth): the DSMC's steady T_tr and shear stress are
    those of the event-driven gas of examples/shear (256 discs) within 5 %"""
    from granfric import shear
    log = shear.run_example(str(tmp_path), 2, 0.2, 16, 8000.0)
    ed = shear.reduced(shear.steady(log), 2)
    th, _, _ = shear.theory(2, 0.2, 10000, 2)
    for k in ("T_tr", "a*", "P*xy"):
        assert abs(ed[k] / th[k] - 1.0) < 0.05, (k, ed[k], th[k])
