// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: instantaneous collision laws for rough hard spheres and discs.
//
// Conventions (doc/conventions.rst): n points from body 2 to body 1, the contact-point
// velocity is g = v1 - v2 - (a1 w1 + a2 w2) x n, the pair approaches iff g.n < 0. The shape factor
// q = I/(m a^2) is per body (2/5 sphere, 1/2 disc). 2D is the same code with z components zero
// (spins along z only stay along z). A wall is a body of infinite mass and radius with its own
// velocity (Body::wall).
#ifndef GRANFRIC_CORE_COLLISION_H
#define GRANFRIC_CORE_COLLISION_H

#include "vec3.h"

#include <limits>

namespace granfric {

constexpr double INF = std::numeric_limits<double>::infinity();

enum class LawKind { ROUGH, WALTON, JZ };

struct Body;

// Coefficients of one collision law (one type pair, or particle-wall), as the table of laws
// (law_table.h) makes them from a user's coefficients.
// All three laws share one map (Walton's with a static and a dynamic friction coefficient):
//   rough : r, rt_max = beta, mu_s = mu_d = inf (constant tangential restitution)
//   walton: r, rt_max, mu_s = mu_d = mu
//   jz    : r = 1 - 2 q_n, rt_max = 1 - 2 q_t, mu_s = kappa_s, mu_d = kappa_d
// Any of them may take a viscoelastic normal restitution instead of the constant r
// (viscoelastic.h): visco > 0 gives r = E(delta) at each collision, with
//   delta = visco |g_n|^(1/5)                                    (visco_material false), or
//   delta = visco R_eff^(1/5) m_eff^(-2/5) |g_n|^(1/5)           (visco_material true),
// R_eff and m_eff the pair's reduced radius and mass (a wall: the particle's own).
struct LawParams {
  LawKind kind = LawKind::ROUGH;
  double r = 1.0;
  double rt_max = -1.0;
  double mu_s = INF;
  double mu_d = INF;
  double visco = 0.0;
  bool visco_material = false;

  static LawParams rough(double r, double beta) { return {LawKind::ROUGH, r, beta, INF, INF}; }
  static LawParams walton(double r, double mu, double rt_max)
  {
    return {LawKind::WALTON, r, rt_max, mu, mu};
  }
  static LawParams jz(double qn, double qt, double kappa_s, double kappa_d)
  {
    return {LawKind::JZ, 1.0 - 2.0 * qn, 1.0 - 2.0 * qt, kappa_s, kappa_d};
  }
  // the TC model's replacement (Luding et al. 1998): elastic and smooth, r = 1 and beta = -1, so
  // neither normal nor tangential motion loses energy and spins are untouched
  LawParams elastic() const { return {kind, 1.0, -1.0, INF, INF}; }

  // can a collision gain energy? (Jenkins-Zhang with kappa_d > kappa_s: a sliding contact then
  // takes a larger tangential impulse than sticking would)
  bool can_create_energy() const { return kind == LawKind::JZ && mu_d > mu_s; }
  // is it smooth? (rt = -1 whatever the contact, no Coulomb limit: no tangential impulse)
  bool smooth() const { return rt_max == -1.0 && mu_s == INF; }
  // does every collision conserve the kinetic energy? (elastic normal motion, and a tangential
  // motion that is either untouched or reversed without a Coulomb limit)
  bool conserves_energy() const
  {
    return r == 1.0 && visco == 0.0 && mu_s == INF && (rt_max == -1.0 || rt_max == 1.0);
  }
  // the law of a collision with normal contact velocity gn between b1 and b2: itself, or with the
  // viscoelastic restitution at that speed as r
  LawParams at_contact(double gn, const Body &b1, const Body &b2, double m_n) const;

  // Every field, in one fixed order: f(name, field of s...) for each, with the fields of every s
  // given by reference (EDOptions::each_field)
  template <class F, class... S>
  static void each_field(F &&f, S &...s)
  {
    f("kind", s.kind...), f("r", s.r...), f("rt_max", s.rt_max...), f("mu_s", s.mu_s...);
    f("mu_d", s.mu_d...), f("visco", s.visco...), f("visco_material", s.visco_material...);
  }
};

struct Body {
  Vec3 v, w;        // velocity, angular velocity
  double m = 1.0;   // mass (INF: wall)
  double a = 0.5;   // radius (ignored for a wall)
  double q = 0.4;   // I / (m a^2) (ignored for a wall)

  static Body wall(const Vec3 &v_wall) { return {v_wall, Vec3(), INF, 0.0, 1.0}; }
  bool is_wall() const { return m == INF; }
};

struct Collision {
  Vec3 v1, w1, v2, w2;     // post-collision state (v2 = wall velocity, w2 = 0 for a wall)
  Vec3 dP;                 // impulse on body 1 (body 2 gets -dP)
  double dE = 0.0;         // kinetic energy change, closed form (<= 0 unless the law creates energy)
  double gn = 0.0;         // pre-collision g.n (< 0 when approaching)
  double gt = 0.0;         // pre-collision |g_t|
  double cos_gamma = -1.0; // cos of the impact angle, g.n/|g| (-1 for a head-on or a g = 0 contact)
  double rt = 0.0;         // tangential restitution that was applied
  bool sliding = false;    // Coulomb limit reached (never for rough)
  bool energy_created = false;
  double gamma() const;    // impact angle in (pi/2, pi]
};

// Apply the law to a contact with unit normal n (from 2 to 1). The caller decides whether the
// pair approaches (gn < 0); the map is applied as given.
Collision collide(const LawParams &law, const Body &b1, const Body &b2, const Vec3 &n);

// Effective masses of the contact (m_n, m_t) as used by the map.
void effective_masses(const Body &b1, const Body &b2, double &m_n, double &m_t);

// Kinetic energy of a body (translational + rotational); 0 for a wall.
double kinetic_energy(const Body &b);

}    // namespace granfric

#endif
