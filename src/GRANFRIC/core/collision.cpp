// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the collision map (Walton form, see collision.h and doc/conventions.rst).
#include "collision.h"

#include "viscoelastic.h"

#include <algorithm>
#include <cmath>

namespace granfric {

double Collision::gamma() const
{
  return std::acos(std::max(-1.0, std::min(1.0, cos_gamma)));
}

// 1/m and a^2/I of a body; both 0 for a wall
static inline double inverse_mass(const Body &b)
{
  return b.is_wall() ? 0.0 : 1.0 / b.m;
}

static inline double a2_over_I(const Body &b)
{
  return b.is_wall() ? 0.0 : 1.0 / (b.q * b.m);
}

void effective_masses(const Body &b1, const Body &b2, double &m_n, double &m_t)
{
  const double im1 = inverse_mass(b1), im2 = inverse_mass(b2);
  m_n = 1.0 / (im1 + im2);
  m_t = 1.0 / (im1 + im2 + a2_over_I(b1) + a2_over_I(b2));
}

double kinetic_energy(const Body &b)
{
  if (b.is_wall()) return 0.0;
  return 0.5 * b.m * norm2(b.v) + 0.5 * b.q * b.m * b.a * b.a * norm2(b.w);
}

// The tangential part of the map for g_t, the tangential contact-point velocity (gt = |g_t|):
// the restitution rt (Coulomb's limit where it binds), the tangential impulse added
// to c.dP, the spins, and the energy that the tangential motion loses added to c.dE.
// The map is written with s = 1 + rt, the fraction of the sticking impulse: at Coulomb's limit
// s = mu (m_n/m_t)(1+r)|g_n|/|g_t| is far below the rounding of 1 when the contact point moves
// fast (a fast spin), so rt = -1 + s would lose it; the energy takes |g_t| once per factor, so
// it stays finite wherever the impulse is.
static void tangential(const LawParams &law, const Body &b1, const Body &b2, const Vec3 &n, const Vec3 &g_t,
                       double gt, double im1, double im2, double m_n, Collision &c)
{
  const double k1 = a2_over_I(b1), k2 = a2_over_I(b2);
  const double m_t = 1.0 / (im1 + im2 + k1 + k2);
  double s = 1.0 + law.rt_max;
  if (gt > 0.0 && law.mu_s != INF) {
    // s at Coulomb's limit with a friction coefficient of 1
    const double slide_scale = (m_n / m_t) * (1.0 + law.r) * std::fabs(c.gn) / gt;
    if (law.kind == LawKind::JZ) {
      // Jenkins-Zhang: stick iff the sticking impulse is below kappa_s times the normal one,
      // otherwise slide with |dP_t| = kappa_d |dP_n| (discontinuous when kappa_s != kappa_d)
      if (!(s < law.mu_s * slide_scale)) {
        s = law.mu_d * slide_scale;
        c.sliding = true;
      }
    } else if (law.mu_s * slide_scale < s) {
      s = law.mu_s * slide_scale;
      c.sliding = true;
    }
  }
  c.rt = s - 1.0;
  const Vec3 dP_t = -(m_t * s) * g_t;
  c.dP = c.dP + dP_t;
  const Vec3 nxdP = cross(n, dP_t);    // = n x dP; exactly 0 without tangential impulse
  // w' = w - a n x dP / I with a/I = (a^2/I)/a
  c.w1 = b1.is_wall() ? Vec3() : b1.w - (k1 / b1.a) * nxdP;
  c.w2 = b2.is_wall() ? Vec3() : b2.w - (k2 / b2.a) * nxdP;
  // (1 - rt^2) |g_t|^2 = s (2 - s) |g_t|^2
  c.dE = c.dE - 0.5 * (m_t * s * gt) * (2.0 - s) * gt;
}

// the law with the viscoelastic restitution at normal contact velocity gn (collision.h)
LawParams LawParams::at_contact(double gn, const Body &b1, const Body &b2, double m_n) const
{
  LawParams p = *this;
  double scale = visco;
  if (visco_material) {
    const double R = b2.is_wall() ? b1.a : b1.a * b2.a / (b1.a + b2.a);
    scale *= std::pow(R, 0.2) * std::pow(m_n, -0.4);
  }
  p.r = viscoelastic_restitution(scale * std::pow(std::fabs(gn), 0.2));
  return p;
}

// A smooth law (rt = -1 whatever the contact, no Coulomb limit: rough with beta = -1, and the TC
// model's replacement) takes the normal part alone: its tangential impulse, its spin changes and
// the tangential energy loss are exact zeros, so it gives the same numbers (up to the sign of a
// zero) without the tangential arithmetic.
Collision collide(const LawParams &given, const Body &b1, const Body &b2, const Vec3 &n)
{
  const double im1 = inverse_mass(b1), im2 = inverse_mass(b2);
  const double m_n = 1.0 / (im1 + im2);

  // contact-point relative velocity; a wall's contact point moves with the wall
  Vec3 aw = b1.a * b1.w;
  if (!b2.is_wall()) aw += b2.a * b2.w;
  const Vec3 g = b1.v - b2.v - cross(aw, n);
  const double gn = dot(g, n);
  LawParams at_speed;
  if (given.visco > 0.0) at_speed = given.at_contact(gn, b1, b2, m_n);
  const LawParams &law = given.visco > 0.0 ? at_speed : given;
  const Vec3 g_t = g - gn * n;
  const double gt2 = norm2(g_t);
  // (|g_t| without the square where that overflows: a contact point faster than 1e154)
  const double gt = gt2 < INF ? std::sqrt(gt2) : std::hypot(g_t.x, g_t.y, g_t.z);

  Collision c;
  c.gn = gn;
  c.gt = gt;
  const double g2 = gn * gn + gt2;
  c.cos_gamma = g2 > 0.0 ? gn / (g2 < INF ? std::sqrt(g2) : std::hypot(gn, gt)) : -1.0;
  c.dP = (-m_n * (1.0 + law.r) * gn) * n;
  c.dE = -0.5 * m_n * (1.0 - law.r * law.r) * gn * gn;
  if (law.smooth()) {
    c.rt = law.rt_max;
    c.w1 = b1.is_wall() ? Vec3() : b1.w;
    c.w2 = b2.is_wall() ? Vec3() : b2.w;
  } else {
    tangential(law, b1, b2, n, g_t, gt, im1, im2, m_n, c);
  }
  c.v1 = b1.v + im1 * c.dP;
  c.v2 = b2.v - im2 * c.dP;
  c.energy_created = c.dE > 0.0;
  return c;
}

}    // namespace granfric
