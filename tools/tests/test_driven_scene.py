# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""The driven scene (examples/driven, Herbst et al. 2005) in the steady state against the
mean-field theory where it is closed form: mu = inf (constant tangential restitution, model A):
R = B/C (the rotational equation has no driving) and T_tr^3/2 = H_dr / (G (A - B R)), with
H_dr = f_dr m v_dr^2 (1 - 1/N) (kicks keep the momentum zero). Dilute (fraction 0.05, N = 4096).
Measured at r = 0.95, rt = 0.4 over 16 runs of this length (seeds 11-17 and 4321, each with the
cell grids of 2026-12-02 and of 2026-12-03, which give other rounding and so other chaotic
trajectories): T_tr +0.4 %, R -2.3 +- 0.3 % against model A, and a run's R scatters by 1 %. The
R offset is the mean field's own error (it assumes homogeneity and molecular chaos; Herbst et
al. relate the remaining deviations to these), so R is held to 5 %, the accuracy documented for
the mean field at this fraction (doc/choosing_a_method.rst), and T_tr to 3 %."""
import math

import pytest

from granfric import cooling, herbst


@pytest.mark.parametrize("r,rt", [(0.95, 0.4), (0.95, -1.0)])
def test_driven_steady_state_equals_model_A(tmp_path, r, rt):
    d = herbst.simulate(r, "inf", rt, 0.05, 600.0, str(tmp_path / "log"))
    s = herbst.steady(d)
    c = cooling.coefficients(r, rt, 0.4, 2)
    R = c.B / c.C if c.C > 0 else 0.0
    G = cooling.time_scale_G(0.05, 0.5, 1.0, 2)
    H = 2.0 * 0.1 ** 2 * (1 - 1 / 4096)
    T = (H / (G * (c.A - c.B * R))) ** (2 / 3)
    assert s["Ttr"] == pytest.approx(T, rel=0.03)
    if R > 0:
        assert s["R"] == pytest.approx(R, rel=0.05)
    else:
        assert s["R"] == 0.0
    # the energy books close: injected - dissipated = kinetic energy now - at t = 0 (to the 10
    # digits of the thermo output; the 1e-9 check is in test_fix_hardsphere_ed)
    E = 4096 * (d["c_T[1]"] + 0.5 * d["c_T[2]"])
    assert d["f_ed[9]"][-1] - d["f_ed[3]"][-1] - (d["f_ed[9]"][0] - d["f_ed[3]"][0]) == \
        pytest.approx(E[-1] - E[0], rel=1e-7)
