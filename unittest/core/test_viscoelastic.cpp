// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// Core tests of the viscoelastic normal restitution (core/viscoelastic.h): the function E(delta)
// against an independent integration and the literature's small-delta series, its table against
// the integration it is made of, its inverse, and collisions with it (momentum, energy, the
// restitution at the contact's speed for a measured pair and for material constants, walls).
#include "core/collision.h"
#include "core/law_table.h"
#include "core/viscoelastic.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace granfric;

namespace {

// E(delta) by the classical fourth-order Runge-Kutta method with a fixed small step, written
// here independently of the core: x'' = -x^(3/2) - delta x^(1/2) x' from x = 0, x' = 1 until
// the force x^(3/2) + delta x^(1/2) x' vanishes (linear interpolation within the last step)
double rk4_restitution(double delta, double h)
{
  auto acc = [delta](double x, double v) {
    const double r = std::sqrt(std::max(x, 0.0));
    return -r * (x + delta * v);
  };
  double x = 0.0, v = 1.0;
  for (int k = 0; k < 100000000; k++) {
    const double k1x = v, k1v = acc(x, v);
    const double k2x = v + 0.5 * h * k1v, k2v = acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v, k3v = acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v, k4v = acc(x + h * k3x, v + h * k3v);
    const double x1 = x + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    const double v1 = v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    const double f0 = x + delta * v, f1 = x1 + delta * v1;
    if (k > 0 && f1 <= 0.0) {
      const double w = f0 / (f0 - f1);
      return -(v + w * (v1 - v));
    }
    x = x1;
    v = v1;
  }
  return -1.0;
}

}    // namespace

TEST(Viscoelastic, AgreesWithAnIndependentIntegration)
{
  for (double delta : {0.02, 0.1, 0.5, 1.0, 3.0, 10.0})
    EXPECT_NEAR(viscoelastic_restitution(delta), rk4_restitution(delta, 2e-5), 2e-8) << delta;
}

// the literature's series: E = 1 - C1 delta + C2 delta^2 - ..., C1 = 1.15344, C2 = 0.79826
TEST(Viscoelastic, SmallDeltaSeries)
{
  EXPECT_EQ(viscoelastic_restitution(0.0), 1.0);
  // f(delta) = (1 - E)/delta = C1 - C2 delta + O(delta^(3/2)): C1 at delta = 1e-7, C2 from the
  // slope of f between 1e-4 and 2e-4 (the next term moves it by about 0.5 %)
  auto f = [](double d) { return (1.0 - viscoelastic_restitution_exact(d)) / d; };
  EXPECT_NEAR(f(1e-7), 1.15344, 2e-5);
  EXPECT_NEAR(-(f(2e-4) - f(1e-4)) / 1e-4, 0.79826, 0.01 * 0.79826);
}

// the table (cubic interpolation in sqrt(delta)) within 2e-11 of the integration, midway
// between its points and at random places; the table in ln delta within 5e-9 relatively
TEST(Viscoelastic, TableAgreesWithTheIntegration)
{
  std::mt19937_64 gen(5);
  std::uniform_real_distribution<double> u(0.0, 8.0);
  double worst = 0.0;
  for (int k = 0; k < 300; k++) {
    const double s = k < 100 ? (k + 0.5) * (8.0 / 4096) : u(gen);
    worst = std::max(worst, std::fabs(viscoelastic_restitution(s * s) - viscoelastic_restitution_exact(s * s)));
  }
  EXPECT_LT(worst, 2e-11);
  // the table of ln E from delta = 64 to 1e4, relatively
  worst = 0.0;
  for (int k = 0; k < 100; k++) {
    const double d = 64.0 * std::pow(1e4 / 64.0, (k + 0.37) / 100.0);
    worst = std::max(worst, std::fabs(viscoelastic_restitution(d) / viscoelastic_restitution_exact(d) - 1.0));
  }
  EXPECT_LT(worst, 5e-9);
}

// strongly damped: E delta^(5/3) tends to a constant (1.31036), which E follows past 1e4, where
// it is smooth and the integration no longer resolves it; the continuation is continuous
TEST(Viscoelastic, StronglyDampedAsymptote)
{
  const double c3 = viscoelastic_restitution_exact(3e3) * std::pow(3e3, 5.0 / 3.0);
  const double c4 = viscoelastic_restitution_exact(1e4) * std::pow(1e4, 5.0 / 3.0);
  EXPECT_NEAR(c4, 1.31036, 1e-5);
  EXPECT_NEAR(c3 / c4, 1.0, 1e-4);
  for (double d : {2e4, 1e6, 1e12})
    EXPECT_NEAR(viscoelastic_restitution(d) * std::pow(d, 5.0 / 3.0) / c4, 1.0, 1e-9) << d;
  EXPECT_NEAR(viscoelastic_restitution(std::nextafter(1e4, 1e5)) / viscoelastic_restitution(1e4), 1.0, 1e-12);
  EXPECT_NEAR(viscoelastic_restitution(std::nextafter(64.0, 0.0)) / viscoelastic_restitution(64.0), 1.0, 1e-9);
  EXPECT_NEAR(viscoelastic_restitution(viscoelastic_delta(1e-12)), 1e-12, 1e-24);
}

TEST(Viscoelastic, DecreasingAndInverted)
{
  double last = 1.0;
  for (double d = 1e-3; d < 200.0; d *= 1.3) {
    const double e = viscoelastic_restitution(d);
    EXPECT_LT(e, last) << d;
    EXPECT_GT(e, 0.0) << d;
    last = e;
  }
  for (double e : {0.999, 0.9, 0.5, 0.1, 0.01})
    EXPECT_NEAR(viscoelastic_restitution(viscoelastic_delta(e)), e, 1e-14) << e;
  EXPECT_EQ(viscoelastic_delta(1.0), 0.0);
}

// A law from a measured pair (r at vref): each collision's normal restitution is E at its normal
// speed, the one at vref itself is r, faster impacts are less elastic; momentum is conserved and
// the closed-form energy change is the kinetic energy's, for the three laws, between particles
// and at a wall
TEST(Viscoelastic, CollisionsAtTheContactsSpeed)
{
  const RestitutionSpec &ve = *find_restitution("viscoelastic");
  const double vref = 2.0;
  for (int kind = 0; kind < NLAWS; kind++) {
    const LawSpec &spec = law_spec(kind);
    const double c[3][4] = {{0.8, 0.3}, {0.8, 0.4, 0.3}, {0.1, 0.35, 0.4, 0.4}};
    LawParams law = spec.make(c[kind]);
    ASSERT_EQ(ve.apply(law, &vref), nullptr);
    EXPECT_GT(law.visco, 0.0);
    for (double speed : {0.01, 0.5, 2.0, 7.0}) {
      Body b1, b2;
      b1.v = Vec3(-speed, 0.3, 0.0);
      b1.w = Vec3(0.0, 0.0, 1.0);
      b2.m = 2.0;
      b2.q = 0.5;
      const Vec3 n(1.0, 0.0, 0.0);
      for (bool wall : {false, true}) {
        const Body partner = wall ? Body::wall(Vec3()) : b2;
        const Collision col = collide(law, b1, partner, n);
        const double r = viscoelastic_restitution(law.visco * std::pow(speed, 0.2));
        const Body a1{col.v1, col.w1, b1.m, b1.a, b1.q};
        const Vec3 g1 = a1.v - col.v2 - cross(a1.a * a1.w + (wall ? Vec3() : partner.a * col.w2), n);
        EXPECT_NEAR(dot(g1, n), r * speed, 1e-14 * (1.0 + speed)) << kind << " " << speed << " " << wall;
        if (speed == vref) EXPECT_NEAR(r, law.r, 1e-13);
        if (!wall) {
          const Body a2{col.v2, col.w2, b2.m, b2.a, b2.q};
          const Vec3 p0 = b1.m * b1.v + b2.m * b2.v, p1 = b1.m * a1.v + b2.m * a2.v;
          EXPECT_NEAR(norm(p1 - p0), 0.0, 1e-14 * (1.0 + speed));
          EXPECT_NEAR(col.dE, kinetic_energy(a1) + kinetic_energy(a2) - kinetic_energy(b1) - kinetic_energy(b2),
                      1e-13 * (1.0 + speed * speed));
        }
      }
    }
  }
}

// from material constants: delta = A alpha^(2/5) v^(1/5) with alpha = (3/2)^(3/2) Y sqrt(R_eff) /
// (m_eff (1 - nu^2)), R_eff and m_eff of the pair (a wall: the particle's own)
TEST(Viscoelastic, MaterialConstantsAndThePairsSizes)
{
  const RestitutionSpec &vm = *find_restitution("viscoelastic/material");
  const double Y = 1e5, nu = 0.3, A = 0.004, mc[3] = {Y, nu, A};
  EXPECT_EQ(first_bad_restitution_coeff(vm, mc), -1);
  LawParams law = LawParams::rough(1.0, 0.2);
  ASSERT_EQ(vm.apply(law, mc), nullptr);
  Body b1, b2;
  b1.a = 0.5, b1.m = 1.0, b2.a = 1.5, b2.m = 27.0;
  const double v = 1.3;
  b1.v = Vec3(-v, 0.0, 0.0);
  const Vec3 n(1.0, 0.0, 0.0);
  for (bool wall : {false, true}) {
    const double R = wall ? b1.a : b1.a * b2.a / (b1.a + b2.a);
    const double m = wall ? b1.m : b1.m * b2.m / (b1.m + b2.m);
    const double alpha = std::pow(1.5, 1.5) * Y * std::sqrt(R) / (m * (1.0 - nu * nu));
    const double r = viscoelastic_restitution(A * std::pow(alpha, 0.4) * std::pow(v, 0.2));
    const Collision c = collide(law, b1, wall ? Body::wall(Vec3()) : b2, n);
    const double after = dot(c.v1 - c.v2, n);    // (no spin: the normal contact velocity)
    EXPECT_NEAR(after, r * v, 1e-13) << wall;
    EXPECT_LT(r, 0.99) << wall;    // (the test means something: the restitution is well below 1)
  }
  // ranges
  const double bad_nu[3] = {Y, 0.6, A}, bad_Y[3] = {0.0, 0.3, A}, bad_A[3] = {Y, 0.3, -1.0};
  EXPECT_EQ(first_bad_restitution_coeff(vm, bad_nu), 1);
  EXPECT_EQ(first_bad_restitution_coeff(vm, bad_Y), 0);
  EXPECT_EQ(first_bad_restitution_coeff(vm, bad_A), 2);
  LawParams zero = LawParams::rough(0.0, 0.2);
  const double vref = 1.0;
  EXPECT_NE(find_restitution("viscoelastic")->apply(zero, &vref), nullptr);    // r = 0 at vref
}
