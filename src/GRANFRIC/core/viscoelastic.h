// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the normal restitution of viscoelastic spheres.
//
// Two viscoelastic spheres (Hertz contact with a dissipative term proportional to the rate of
// deformation) that meet at normal speed v leave with the normal restitution
//
//   epsilon(v) = E(delta),   delta = A alpha^(2/5) v^(1/5),
//   alpha = (3/2)^(3/2) Y sqrt(R_eff) / (m_eff (1 - nu^2))
//
// (Y Young's modulus, nu Poisson's ratio, A the material's dissipative constant, R_eff and m_eff
// the reduced radius and mass). E is one function of one variable: with the compression xi
// scaled by its elastic maximum and the time by the collision's, the equation of motion is
//
//   x'' = -x^(3/2) - d x^(1/2) x',   x(0) = 0, x'(0) = 1,   d = delta (as defined above),
//
// and the collision ends when the contact force, x^(3/2) + d x^(1/2) x', vanishes (the spheres
// do not pull on each other): E = -x' then. For small delta, E = 1 - C1 delta + C2 delta^2 - ...
// with C1 = 1.15344 and C2 = 0.79826 (the literature's series; tested in unittest/core).
//
// E is computed once per process by an adaptive Dormand-Prince integration of the equation
// above, on a table uniform in s = sqrt(delta) up to delta = 64 (E is a smooth function of s
// there) and a table of ln E uniform in ln delta from 64 to 1e4, each read with cubic
// interpolation; past 1e4 (E < 3e-7) E follows the strongly damped asymptote E ~ delta^(-5/3)
// from its value at 1e4. The same numbers on every rank and host (the tables' arithmetic is the
// same everywhere).
#ifndef GRANFRIC_CORE_VISCOELASTIC_H
#define GRANFRIC_CORE_VISCOELASTIC_H

namespace granfric {

// E(delta) for delta >= 0 (1 at delta = 0, decreasing toward 0)
double viscoelastic_restitution(double delta);
// E(delta) integrated afresh (the tables' values; for tests, up to delta = 1e4)
double viscoelastic_restitution_exact(double delta);
// the delta with E(delta) = e, for 0 < e <= 1 (0 at e = 1)
double viscoelastic_delta(double e);

}    // namespace granfric

#endif
