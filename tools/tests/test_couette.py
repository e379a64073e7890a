# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""granfric.couette: the Navier-Stokes solution of plane Couette flow with slip and jump (its
limits and invariants), the Enskog transport coefficients against Chapman & Cowling's numbers,
and the readers and fits of the example's output."""
import numpy as np
import pytest

from granfric import couette, cooling


def test_small_wall_speed_gives_linear_couette_flow_with_slip():
    # U -> 0: T = T_w, u = U y / (h + zeta_u lambda), S = eta U / (h + zeta_u lambda)
    for dim, Ly, per_area in ((2, 170.4, 10.85), (3, 72.2, 6.9)):
        r = couette.solve(dim, 1e-3, 1.0, Ly, per_area, "boltzmann")
        n = per_area / (2 * r["h"])
        lam = couette.mean_free_path(n, dim)
        eta, _ = couette.transport(1.0, n, dim, "boltzmann")
        zu, _ = couette.slip_coefficients(dim)
        assert r["S"] == pytest.approx(eta * 1e-3 / (r["h"] + zu * lam), rel=1e-6)
        assert np.allclose(r["T"], 1.0, atol=1e-6)
        assert r["p"] == pytest.approx(n, rel=1e-5)


@pytest.mark.parametrize("dim", [2, 3])
def test_dilute_solution_keeps_temperature_plus_velocity_squared_constant(dim):
    # kappa/eta = c constant: T + u^2/(2c) is the same across the channel; the profiles are
    # odd (u) and even (T), and the particles per area are those asked for
    r = couette.solve(dim, 2.0, 1.0, 100.0, 5.0, "boltzmann")
    c = couette.conductivity_ratio(dim)
    inv = r["T"] + r["u"] ** 2 / (2 * c)
    assert np.ptp(inv) < 1e-6
    assert np.allclose(r["u"], -r["u"][::-1], atol=1e-7)
    assert np.allclose(r["T"], r["T"][::-1], atol=1e-7)
    trapezoid = getattr(np, "trapezoid", None) or np.trapz
    assert trapezoid(r["n"], r["y"]) == pytest.approx(5.0, rel=1e-4)


def test_enskog_coefficients_are_chapman_and_cowlings():
    # 3D: eta/eta0 = 1/chi + 0.8 y + 0.7614 y^2 chi, kappa/kappa0 = 1/chi + 1.2 y + 0.7574 y^2
    # chi with y = 4 phi (eta0, kappa0 with the higher-Sonine factors); 2D (Gass): 1/chi + 2 phi
    # + (1 + 8/pi) phi^2 chi and 1/chi + 3 phi + (9/4 + 4/pi) phi^2 chi, the kinetic parts
    # with the Sonine factors
    for phi in (0.05, 0.2):
        n = phi / (np.pi / 6)
        chi = cooling.pair_correlation(phi, 3)
        e0, k0 = couette.transport(1.0, n, 3, "boltzmann")
        e, k = couette.transport(1.0, n, 3, "enskog")
        y = 4 * phi
        assert e / e0 == pytest.approx(1 / chi + 0.8 * y + 0.7614 * y * y * chi, rel=2e-4)
        assert k / k0 == pytest.approx(1 / chi + 1.2 * y + 0.7574 * y * y * chi, rel=2e-4)
        n2 = phi / (np.pi / 4)
        chi2 = cooling.pair_correlation(phi, 2)
        e0, k0 = couette.transport(1.0, n2, 2, "boltzmann")
        e, k = couette.transport(1.0, n2, 2, "enskog")
        ce, ck = couette.SONINE_FACTOR[2]
        assert e / e0 * ce == pytest.approx(
            ce / chi2 + ce * 2 * phi + (ce + 8 / np.pi) * phi ** 2 * chi2, rel=1e-12)
        assert k / k0 * ck == pytest.approx(
            ck / chi2 + ck * 3 * phi + (ck * 9 / 4 + 4 / np.pi) * phi ** 2 * chi2, rel=1e-12)


def test_equation_of_state_inverts():
    for dim in (2, 3):
        n = couette.density(0.3, 1.7, dim)
        assert n * 1.7 * couette.compressibility(n, dim) == pytest.approx(0.3, rel=1e-12)


def test_slip_coefficients():
    # hard spheres: Sone's k0 = -1.2540, d1 = 2.4001 times sqrt(pi)/2; discs: Maxwell's and
    # Smoluchowski's lengths scaled by the hard-sphere ratios
    assert couette.slip_coefficients(3) == pytest.approx((1.1113, 2.1270), abs=2e-4)
    assert couette.maxwell_slip(2) == pytest.approx(1.022)
    assert couette.smoluchowski_jump(2) == pytest.approx(1.029 * 8 / 3)
    zu, zt = couette.slip_coefficients(2)
    assert zu == pytest.approx(1.022 * 1.1113 / couette.maxwell_slip(3), rel=1e-3)
    assert zt == pytest.approx(1.029 * 8 / 3 * 2.1270 / couette.smoluchowski_jump(3), rel=1e-3)


def test_bulk_fit_recovers_slip_and_jump_of_polynomial_profiles():
    h, U, Tw = 50.0, 2.0, 1.0
    y = np.linspace(-h + 1, h - 1, 40)
    u = 0.03 * y + 1e-6 * y ** 3
    T = 1.5 - 1e-4 * y ** 2 + 1e-9 * y ** 4
    prof = {"y": y, "u": np.vstack([u, u]), "T": np.vstack([T, T])}
    f = couette.fit_bulk(prof, h, 2.0, U, Tw)
    uh, duh = 0.03 * h + 1e-6 * h ** 3, 0.03 + 3e-6 * h ** 2
    Th, dTh = 1.5 - 1e-4 * h ** 2 + 1e-9 * h ** 4, -2e-4 * h + 4e-9 * h ** 3
    assert f["slip"][0] == pytest.approx(U - uh, rel=1e-9)
    assert f["slip_length"][0] == pytest.approx((U - uh) / duh, rel=1e-9)
    assert f["jump_length"][0] == pytest.approx((Th - Tw) / -dTh, rel=1e-9)
    assert f["Tc"][0] == pytest.approx(1.5, rel=1e-12)


def test_readers(tmp_path):
    chunks = tmp_path / "c.profile"
    chunks.write_text("# Chunk-averaged data for fix prof and group all\n"
                      "# Timestep Number-of-chunks Total-count\n"
                      "# Chunk Coord1 Ncount density/number vx v_vx2 v_vy2\n"
                      "10 2 4\n  1 1 2 0.1 -1 2 1\n  2 3 2 0.1 1 2 1\n"
                      "20 2 4\n  1 1 2 0.1 -1 3 2\n  2 3 2 0.1 1 3 2\n")
    p = couette.profiles(str(chunks), 2, 4.0)
    assert p["u"].shape == (2, 2)
    assert np.allclose(p["T"], [[1, 1], [2, 2]])
    # the outer layers' density over the part of the layer the centres reach (2 - 0.5)
    assert np.allclose(p["n"], 0.1 * 2 / 1.5)
    assert np.allclose(p["y"], [-0.75, 0.75])   # the middle of [0.5, 2] and of [2, 3.5]
    blocks = {"Pxy": np.array([-0.01, -0.012]), "Flo": np.array([0.5, 0.7]),
              "Fhi": np.array([-0.5, -0.7]), "Pyy": np.array([0.1, 0.1]),
              "T": np.array([1.0, 1.0])}
    b = couette.books(blocks, {"Lx": 50.0, "Lz": 1.0, "Ly": 101.0})
    assert b["PxyA_corr"][0] == pytest.approx(-0.011 * 50 * 101 / 100)
    assert b["F_lo+F_hi"][0] == 0.0
