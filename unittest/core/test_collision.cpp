// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// Core tests of the collision laws: conservation laws, restitution relations, energy closed form,
// Coulomb limit, limits between the laws (rough = walton mu->inf, jz = walton for kappa_s = kappa_d),
// Risso eqs 6 (corrected) and 7, and the wall limit. Random collisions, 2D and 3D.
#include "core/collision.h"
#include "core/law_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

using namespace granfric;

namespace {

struct Rng {
  std::mt19937_64 gen;
  explicit Rng(unsigned seed) : gen(seed) {}
  double uni(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(gen); }
  double loguni(double lo, double hi) { return std::exp(uni(std::log(lo), std::log(hi))); }
  double gauss() { return std::normal_distribution<double>(0.0, 1.0)(gen); }
  Vec3 gvec(bool dim2) { return {gauss(), gauss(), dim2 ? 0.0 : gauss()}; }
  Vec3 unit(bool dim2)
  {
    Vec3 u = gvec(dim2);
    return (1.0 / norm(u)) * u;
  }
  Vec3 spin(bool dim2) { return dim2 ? Vec3(0.0, 0.0, gauss()) : gvec(false); }
};

Body random_body(Rng &rng, bool dim2)
{
  Body b;
  b.m = rng.loguni(0.1, 10.0);
  b.a = rng.loguni(0.1, 3.0);
  b.q = rng.uni(0.1, 1.0);
  b.v = rng.gvec(dim2);
  b.w = (1.0 / b.a) * rng.spin(dim2);
  return b;
}

// random admissible coefficients of a law, made through the table of laws (which checks them)
LawParams random_law(Rng &rng, LawKind kind)
{
  const double r = rng.uni(0.0, 1.0);
  const double rt = rng.uni(-1.0, 1.0);
  const double mu = rng.uni(0.0, 1.0) < 0.1 ? INF : rng.loguni(1e-3, 1e3);
  const double ks = rng.loguni(1e-3, 1e2);
  const double kd = rng.uni(0.0, 1.0) < 0.5 ? ks : rng.loguni(1e-3, ks);
  double c[4] = {r, rt};
  if (kind == LawKind::WALTON) c[1] = mu, c[2] = rt;
  if (kind == LawKind::JZ) c[0] = 0.5 * (1.0 - r), c[1] = 0.5 * (1.0 - rt), c[2] = ks, c[3] = kd;
  const LawSpec &s = law_spec(kind);
  EXPECT_EQ(first_bad_coeff(s, c), -1);
  return s.make(c);
}

Vec3 contact_velocity(const Body &b1, const Body &b2, const Vec3 &n)
{
  return b1.v - b2.v - cross(b1.a * b1.w + b2.a * b2.w, n);
}

// angular momentum about the contact point c: body 1 at c + a1 n, body 2 at c - a2 n
Vec3 angular_momentum(const Body &b1, const Body &b2, const Vec3 &n)
{
  return b1.m * cross(b1.a * n, b1.v) + (b1.q * b1.m * b1.a * b1.a) * b1.w +
      b2.m * cross(-b2.a * n, b2.v) + (b2.q * b2.m * b2.a * b2.a) * b2.w;
}

Body after(const Body &b, const Vec3 &v, const Vec3 &w)
{
  Body o = b;
  o.v = v;
  o.w = w;
  return o;
}

void expect_vec_near(const Vec3 &a, const Vec3 &b, double tol, const char *what)
{
  EXPECT_NEAR(a.x, b.x, tol) << what;
  EXPECT_NEAR(a.y, b.y, tol) << what;
  EXPECT_NEAR(a.z, b.z, tol) << what;
}

constexpr int NRANDOM = 40000;    // per law and dimension: 3 laws x 2 dims x 40000 = 2.4e5

class RandomCollisions : public ::testing::TestWithParam<std::tuple<LawKind, bool>> {};

std::string law_dim_name(const ::testing::TestParamInfo<std::tuple<LawKind, bool>> &info)
{
  static const char *law[] = {"rough", "walton", "jz"};
  return std::string(law[int(std::get<0>(info.param))]) + (std::get<1>(info.param) ? "_2d" : "_3d");
}

TEST_P(RandomCollisions, ConservationRestitutionEnergy)
{
  const LawKind kind = std::get<0>(GetParam());
  const bool dim2 = std::get<1>(GetParam());
  Rng rng(1234 + 17 * int(kind) + (dim2 ? 1 : 0));
  int nslide = 0, nstick = 0;
  for (int k = 0; k < NRANDOM; ++k) {
    const LawParams law = random_law(rng, kind);
    Body b1 = random_body(rng, dim2), b2 = random_body(rng, dim2);
    Vec3 n = rng.unit(dim2);
    if (dot(contact_velocity(b1, b2, n), n) > 0.0) n = -n;

    const Collision c = collide(law, b1, b2, n);
    const Body a1 = after(b1, c.v1, c.w1), a2 = after(b2, c.v2, c.w2);

    const double pscale = b1.m * norm(b1.v) + b2.m * norm(b2.v) + 1.0;
    expect_vec_near(b1.m * a1.v + b2.m * a2.v, b1.m * b1.v + b2.m * b2.v, 1e-12 * pscale,
                    "linear momentum");
    const double lscale = pscale * (b1.a + b2.a) + 1.0;
    expect_vec_near(angular_momentum(a1, a2, n), angular_momentum(b1, b2, n), 1e-12 * lscale,
                    "angular momentum about the contact point");

    const Vec3 g = contact_velocity(b1, b2, n), gp = contact_velocity(a1, a2, n);
    const double gn = dot(g, n);
    const Vec3 gt = g - gn * n, gtp = gp - dot(gp, n) * n;
    const double gscale = norm(g) + 1.0;
    ASSERT_LT(gn, 0.0);
    EXPECT_NEAR(c.gn, gn, 1e-12 * gscale);
    EXPECT_NEAR(dot(gp, n), -law.r * gn, 1e-12 * gscale) << "g_n' = -r g_n";
    expect_vec_near(gtp, -c.rt * gt, 1e-11 * gscale, "g_t' = -rt g_t");

    const double e0 = kinetic_energy(b1) + kinetic_energy(b2);
    const double e1 = kinetic_energy(a1) + kinetic_energy(a2);
    EXPECT_NEAR(c.dE, e1 - e0, 1e-11 * (e0 + 1.0)) << "closed-form dE";
    const bool may_create = kind == LawKind::JZ && law.mu_d > law.mu_s;
    if (!may_create) {
      EXPECT_LE(c.dE, 1e-12 * (e0 + 1.0));
      EXPECT_FALSE(c.energy_created && c.dE > 1e-12 * (e0 + 1.0));
      EXPECT_GE(c.rt, -1.0 - 1e-12);
      EXPECT_LE(c.rt, law.rt_max + 1e-12);
    }

    const double dPn = std::fabs(dot(c.dP, n));
    const double dPt = norm(c.dP - dot(c.dP, n) * n);
    if (c.sliding) {
      ++nslide;
      EXPECT_NEAR(dPt, law.mu_d * dPn, 1e-10 * (dPn * law.mu_d + 1e-300) + 1e-14)
          << "|dP_t| = mu |dP_n| when sliding";
    } else {
      ++nstick;
      if (law.mu_s != INF) EXPECT_LE(dPt, law.mu_s * dPn * (1.0 + 1e-12) + 1e-14);
      EXPECT_DOUBLE_EQ(c.rt, law.rt_max);
    }
    EXPECT_GT(c.cos_gamma, -1.0 - 1e-15);
    EXPECT_LE(c.cos_gamma, 0.0);

    if (dim2) {
      EXPECT_EQ(c.v1.z, 0.0);
      EXPECT_EQ(c.v2.z, 0.0);
      EXPECT_EQ(c.w1.x, 0.0);
      EXPECT_EQ(c.w1.y, 0.0);
      EXPECT_EQ(c.w2.x, 0.0);
      EXPECT_EQ(c.w2.y, 0.0);
    }
  }
  if (kind == LawKind::ROUGH) {
    EXPECT_EQ(nslide, 0);
  } else {
    // the parameter ranges are wide enough that both regimes must occur often
    EXPECT_GT(nslide, NRANDOM / 20);
    EXPECT_GT(nstick, NRANDOM / 20);
  }
}

INSTANTIATE_TEST_SUITE_P(Laws, RandomCollisions,
                         ::testing::Combine(::testing::Values(LawKind::ROUGH, LawKind::WALTON,
                                                              LawKind::JZ),
                                            ::testing::Bool()),
                         law_dim_name);

void expect_same(const Collision &a, const Collision &b, double tol)
{
  expect_vec_near(a.v1, b.v1, tol, "v1");
  expect_vec_near(a.v2, b.v2, tol, "v2");
  expect_vec_near(a.w1, b.w1, tol, "w1");
  expect_vec_near(a.w2, b.w2, tol, "w2");
  EXPECT_NEAR(a.dE, b.dE, tol);
}

TEST(CollisionLimits, WaltonInfiniteFrictionIsRough)
{
  Rng rng(7);
  for (int k = 0; k < 20000; ++k) {
    const bool dim2 = k % 2;
    const double r = rng.uni(0, 1), beta = rng.uni(-1, 1);
    Body b1 = random_body(rng, dim2), b2 = random_body(rng, dim2);
    Vec3 n = rng.unit(dim2);
    if (dot(contact_velocity(b1, b2, n), n) > 0.0) n = -n;
    const Collision rough = collide(LawParams::rough(r, beta), b1, b2, n);
    expect_same(collide(LawParams::walton(r, INF, beta), b1, b2, n), rough, 1e-14);
    // a very large finite mu converges to the same map
    const Collision big = collide(LawParams::walton(r, 1e12, beta), b1, b2, n);
    if (std::fabs(rough.gn) > 1e-6 * rough.gt) expect_same(big, rough, 1e-12);
  }
}

TEST(CollisionLimits, WaltonZeroFrictionIsSmooth)
{
  Rng rng(8);
  for (int k = 0; k < 5000; ++k) {
    Body b1 = random_body(rng, false), b2 = random_body(rng, false);
    Vec3 n = rng.unit(false);
    if (dot(contact_velocity(b1, b2, n), n) > 0.0) n = -n;
    const double r = rng.uni(0, 1);
    const Collision smooth = collide(LawParams::rough(r, -1.0), b1, b2, n);
    expect_same(collide(LawParams::walton(r, 0.0, rng.uni(-1, 1)), b1, b2, n), smooth, 1e-13);
    expect_vec_near(smooth.w1, b1.w, 1e-14, "spin unchanged without friction");
  }
}

// A smooth law (rough with beta = -1) skips the tangential arithmetic: it gives the numbers of
// the full map with rt = -1 (Walton with rt_max = -1 and a finite mu never reaches the Coulomb
// limit), equal as doubles (== : a zero may differ in sign), and leaves the spins as they were
TEST(CollisionLimits, SmoothShortcutIsTheFullMap)
{
  Rng rng(18);
  auto same = [](const Vec3 &a, const Vec3 &b) { return a.x == b.x && a.y == b.y && a.z == b.z; };
  for (int k = 0; k < 20000; ++k) {
    const bool dim2 = k % 2;
    Body b1 = random_body(rng, dim2), b2 = k % 7 == 0 ? Body::wall(rng.gvec(dim2)) : random_body(rng, dim2);
    Vec3 n = rng.unit(dim2);
    if (dot(contact_velocity(b1, b2, n), n) > 0.0) n = -n;
    const double r = rng.uni(0, 1);
    const Collision cut = collide(LawParams::rough(r, -1.0), b1, b2, n);
    const Collision full = collide(LawParams::walton(r, rng.loguni(1e-3, 1e3), -1.0), b1, b2, n);
    ASSERT_FALSE(full.sliding);
    EXPECT_TRUE(same(cut.v1, full.v1) && same(cut.v2, full.v2) && same(cut.dP, full.dP)) << k;
    EXPECT_TRUE(same(cut.w1, full.w1) && same(cut.w2, full.w2)) << k;
    EXPECT_TRUE(cut.dE == full.dE && cut.gn == full.gn && cut.gt == full.gt && cut.rt == full.rt) << k;
    EXPECT_TRUE(cut.cos_gamma == full.cos_gamma && cut.energy_created == full.energy_created) << k;
    EXPECT_TRUE(same(cut.w1, b1.w) && (b2.is_wall() || same(cut.w2, b2.w))) << k;
  }
}

TEST(CollisionLimits, JenkinsZhangEqualsWaltonForEqualFriction)
{
  Rng rng(9);
  for (int k = 0; k < 20000; ++k) {
    const bool dim2 = k % 2;
    Body b1 = random_body(rng, dim2), b2 = random_body(rng, dim2);
    b1.q = b2.q = 0.5;
    Vec3 n = rng.unit(dim2);
    if (dot(contact_velocity(b1, b2, n), n) > 0.0) n = -n;
    const double qn = rng.uni(0, 0.5), qt = rng.uni(0, 1), mu = rng.loguni(1e-3, 1e2);
    const Collision jz = collide(LawParams::jz(qn, qt, mu, mu), b1, b2, n);
    const Collision wa = collide(LawParams::walton(1 - 2 * qn, mu, 1 - 2 * qt), b1, b2, n);
    expect_same(jz, wa, 1e-12);
    EXPECT_EQ(jz.sliding, wa.sliding);
  }
}

TEST(CollisionLimits, RissoEquations6And7ForEqualDiscs)
{
  Rng rng(10);
  int nslide = 0, nstick = 0;
  for (int k = 0; k < 20000; ++k) {
    const double m = rng.loguni(0.5, 2.0), a = rng.loguni(0.2, 2.0);
    Body b1 = random_body(rng, true), b2 = random_body(rng, true);
    b1.m = b2.m = m;
    b1.a = b2.a = a;
    b1.q = b2.q = 0.5;
    Vec3 n = rng.unit(true);
    if (dot(contact_velocity(b1, b2, n), n) > 0.0) n = -n;
    const double qn = rng.uni(0, 0.5), qt = rng.uni(0, 1), kappa = rng.loguni(1e-3, 10.0);
    const Collision c = collide(LawParams::jz(qn, qt, kappa, kappa), b1, b2, n);
    const double vn = std::fabs(c.gn), vt = c.gt;
    double dE;
    if (c.sliding) {
      ++nslide;
      dE = -(1 - qn) * ((qn - 3 * (1 - qn) * kappa * kappa) * m * vn * vn + kappa * m * vt * vn);
      // Risso's sticking criterion: |v_t| < 3 (1 - q_n) kappa_s v_n / (1 - q_t)
      EXPECT_GE(vt * (1 - qt), 3 * (1 - qn) * kappa * vn * (1 - 1e-12));
    } else {
      ++nstick;
      dE = -qn * (1 - qn) * m * vn * vn - qt * (1 - qt) * m * vt * vt / 3.0;    // corrected eq 6
    }
    EXPECT_NEAR(c.dE, dE, 1e-12 * (m * (vn * vn + vt * vt) + 1.0));
  }
  EXPECT_GT(nslide, 1000);
  EXPECT_GT(nstick, 1000);
}

TEST(CollisionLimits, JenkinsZhangDynamicAboveStaticCanCreateEnergy)
{
  // kappa_d > kappa_s: a contact just past the sticking threshold slides with a tangential
  // impulse larger than the sticking one; with q_t = 0 that overshoots and creates energy
  Body b1, b2;
  b1.m = b2.m = 1.0;
  b1.a = b2.a = 0.5;
  b1.q = b2.q = 0.5;
  b1.v = {-1.0, 1.0, 0.0};
  const Vec3 n(-1.0, 0.0, 0.0);    // body 1 moves toward -x onto body 2 (n from 2 to 1)
  const Collision c = collide(LawParams::jz(0.0, 0.0, 0.1, 0.9), b1, b2, n);
  EXPECT_TRUE(c.sliding);
  EXPECT_GT(c.rt, 1.0);
  EXPECT_TRUE(c.energy_created);
  EXPECT_GT(c.dE, 0.0);
  const double de = kinetic_energy(after(b1, c.v1, c.w1)) + kinetic_energy(after(b2, c.v2, c.w2)) -
      kinetic_energy(b1) - kinetic_energy(b2);
  EXPECT_NEAR(c.dE, de, 1e-12);
}

// A disc spinning very fast (omega up to 1e160) hit head-on at speed 1: Coulomb's limit binds,
// |dP_t| = mu |dP_n| (here mu (1+r) m_n |g_n| = 0.475 with m_n = 1/2), the spins and the energy
// change stay finite, and the energy change is the kinetic energies' difference where that is
// still a number. (s = 1 + rt is below the rounding of 1 there: the map must not form rt.)
TEST(CollisionLimits, WaltonAtExtremeSpinKeepsCoulombsLimit)
{
  const LawParams law = LawParams::walton(0.9, 0.5, 0.4);
  for (double w : {1e3, 1e17, 1e100, 1e160}) {
    Body b1, b2;
    b1.q = b2.q = 0.5;
    b1.v = {-1.0, 0.0, 0.0};
    b2.w = {0.0, 0.0, w};
    const Vec3 n(1.0, 0.0, 0.0);    // body 1 comes from +x onto body 2 at rest (n from 2 to 1)
    const Collision c = collide(law, b1, b2, n);
    EXPECT_TRUE(c.sliding) << w;
    const double dPn = std::fabs(dot(c.dP, n)), dPt = norm(c.dP - dot(c.dP, n) * n);
    EXPECT_NEAR(dPn, 0.5 * 1.9, 1e-12) << w;
    EXPECT_NEAR(dPt, 0.5 * dPn, 1e-12 * dPn) << w;
    EXPECT_TRUE(std::isfinite(c.dE) && std::isfinite(c.w2.z) && std::isfinite(c.rt)) << w;
    EXPECT_LT(c.dE, 0.0) << w;
    if (w < 1e100) {
      const double de = kinetic_energy(after(b1, c.v1, c.w1)) + kinetic_energy(after(b2, c.v2, c.w2)) -
          kinetic_energy(b1) - kinetic_energy(b2);
      EXPECT_NEAR(c.dE, de, 1e-12 * kinetic_energy(b2)) << w;
    }
  }
}

TEST(CollisionLimits, WallIsHeavyLargePartner)
{
  Rng rng(11);
  for (int k = 0; k < 20000; ++k) {
    const bool dim2 = k % 2;
    const LawKind kind = LawKind(k % 3);
    const LawParams law = random_law(rng, kind);
    Body b1 = random_body(rng, dim2);
    const Vec3 vw = 0.5 * rng.gvec(dim2);
    Vec3 n = rng.unit(dim2);
    Body big;
    big.m = 1e13;
    big.a = 1e7;
    big.q = rng.uni(0.1, 1.0);
    big.v = vw;
    if (dot(contact_velocity(b1, big, n), n) > 0.0) n = -n;
    const Collision wall = collide(law, b1, Body::wall(vw), n);
    const Collision heavy = collide(law, b1, big, n);
    if (wall.sliding != heavy.sliding) continue;    // exactly at the stick/slide border
    const double tol = 1e-5 * (norm(b1.v) + norm(vw) + b1.a * norm(b1.w) + 1.0);
    expect_vec_near(wall.v1, heavy.v1, tol, "v1 against wall");
    expect_vec_near(b1.a * wall.w1, b1.a * heavy.w1, tol, "a w1 against wall");
    expect_vec_near(wall.v2, vw, 0.0, "wall velocity unchanged");
    EXPECT_NEAR(wall.dE, heavy.dE, 1e-5 * (kinetic_energy(b1) + 1.0));
    // with m_n = m1 and m_t = m1 q1/(1+q1)
    double m_n, m_t;
    effective_masses(b1, Body::wall(vw), m_n, m_t);
    EXPECT_DOUBLE_EQ(m_n, b1.m);
    EXPECT_NEAR(m_t, b1.m * b1.q / (1.0 + b1.q), 1e-14 * b1.m);
    // the particle's own energy in the wall frame changes by exactly dE
    Body rel = b1, relp = after(b1, wall.v1, wall.w1);
    rel.v = b1.v - vw;
    relp.v = wall.v1 - vw;
    EXPECT_NEAR(kinetic_energy(relp) - kinetic_energy(rel), wall.dE,
                1e-11 * (kinetic_energy(rel) + 1.0));
  }
}

// the table of laws: names, coefficient counts, ranges (each bound in and just out), inf only
// where allowed, NaN never, and the joint condition of jz
TEST(CollisionLimits, ParameterChecks)
{
  auto bad = [](const char *law, std::vector<double> c) {
    const LawSpec *s = find_law(law);
    EXPECT_NE(s, nullptr);
    EXPECT_EQ((int) c.size(), s->ncoeff);
    return first_bad_coeff(*s, c.data());
  };
  EXPECT_EQ(find_law("soft"), nullptr);
  for (int k = 0; k < NLAWS; k++) EXPECT_EQ(find_law(law_spec(k).name), &law_spec(k));
  EXPECT_EQ(bad("rough", {0.9, 0.3}), -1);
  EXPECT_EQ(bad("rough", {1.0, -1.0}), -1);
  EXPECT_EQ(bad("rough", {1.1, 0.3}), 0);
  EXPECT_EQ(bad("rough", {-0.1, 0.3}), 0);
  EXPECT_EQ(bad("rough", {0.9, 1.3}), 1);
  EXPECT_EQ(bad("rough", {0.9, INF}), 1);
  EXPECT_EQ(bad("walton", {0.9, -1.0, 0.3}), 1);
  EXPECT_EQ(bad("walton", {0.9, INF, 0.3}), -1);
  EXPECT_EQ(bad("walton", {NAN, 1.0, 0.3}), 0);
  EXPECT_EQ(bad("walton", {0.9, 1.0, -1.01}), 2);
  EXPECT_EQ(bad("jz", {0.0, 1.0, 0.2, 0.3}), -1);
  EXPECT_EQ(bad("jz", {0.5, 0.0, INF, INF}), -1);
  EXPECT_EQ(bad("jz", {0.6, 0.0, 0.2, 0.3}), 0);
  EXPECT_EQ(bad("jz", {0.1, 1.1, 0.2, 0.3}), 1);
  EXPECT_EQ(bad("jz", {0.1, 0.5, 0.2, INF}), 4);    // (the joint condition)
  // the table's map: jz's coefficients become Walton's form
  const LawParams p = law_spec(LawKind::JZ).make(std::vector<double>{0.1, 0.2, 0.3, 0.4}.data());
  EXPECT_EQ(p.kind, LawKind::JZ);
  EXPECT_DOUBLE_EQ(p.r, 0.8);
  EXPECT_DOUBLE_EQ(p.rt_max, 0.6);
  EXPECT_EQ(p.mu_s, 0.3);
  EXPECT_EQ(p.mu_d, 0.4);
}

TEST(CollisionLimits, ElasticVersionConservesEnergy)
{
  Rng rng(12);
  for (int k = 0; k < 2000; ++k) {
    const LawParams law = random_law(rng, LawKind(k % 3)).elastic();
    Body b1 = random_body(rng, false), b2 = random_body(rng, false);
    Vec3 n = rng.unit(false);
    if (dot(contact_velocity(b1, b2, n), n) > 0.0) n = -n;
    const Collision c = collide(law, b1, b2, n);
    EXPECT_EQ(c.dE, 0.0);
    EXPECT_NEAR(kinetic_energy(after(b1, c.v1, c.w1)) + kinetic_energy(after(b2, c.v2, c.w2)),
                kinetic_energy(b1) + kinetic_energy(b2), 1e-12 * (kinetic_energy(b1) + kinetic_energy(b2)));
  }
}

}    // namespace
