// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the response at a wall (see event_driven.h): a wall collision through the
// particle's law, or re-emission by a thermal wall.
#include "event_driven.h"

#include "counter_rng.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

namespace granfric {

Collision EDCore::thermal_reemission(const EDWall &w, int i, const Vec3 &n, double t, const Vec3 &u)
{
  const EDParticleView p = view(i);
  uint64_t tbits;
  std::memcpy(&tbits, &t, sizeof(tbits));
  CounterStream rng{mix64(mix64(w.seed) ^ (uint64_t) loop_key(i)) ^ tbits};
  auto uniform = [&rng]() { return rng.uniform(); };
  auto gauss = [&]() { return gauss_radius(uniform()) * std::cos(2.0 * M_PI * uniform()); };
  const double sv = std::sqrt(w.T / p.m), sw = std::sqrt(w.T / (p.q * p.m * p.a * p.a));
  Collision c;
  Vec3 v;
  for (int d = 0; d < 3; d++)
    if (d != w.dim && d < opt.dim) v[d] = sv * gauss();
  v[w.dim] = n[w.dim] * sv * gauss_radius(uniform());    // flux: v_n exp(-v_n^2/2)
  v += u;                                                 // (the wall's frame)
  Vec3 wv;
  if (opt.dim == 2)
    wv.z = sw * gauss();
  else
    wv = sw * Vec3(gauss(), gauss(), gauss());
  c.v1 = v;
  c.w1 = wv;
  c.dE = 0.5 * p.m * (norm2(v) - norm2(p.v)) + 0.5 * p.q * p.m * p.a * p.a * (norm2(wv) - norm2(p.w));
  c.gn = dot(p.v, n);
  return c;
}

void EDCore::collide_wall(int i)
{
  Flight &h = flights[i];
  Collider &p = colliders[i];
  Schedule &s = schedules[i];
  const double t = wall_times[i];
  advance(i, t);
  const EDWall &w = opt.walls[s.wall];
  Vec3 n;
  n[w.dim] = w.side < 0 ? 1.0 : -1.0;
  LawParams law = w.laws[s.type];
  const bool tc_elastic = tc_recent(i, t);
  if (tc_elastic) law = law.elastic();
  const double q = qt[s.type];
  Body b{h.v, p.w, p.m, h.a, q};
  Collision c;    // (its dE is set below for moving walls)
  const Vec3 u = w.surface_velocity(clock + t);    // (within the plane)
  if (w.T >= 0.0) {
    c = thermal_reemission(w, i, n, t, u);
  } else {
    double ww, vw, aw;
    w.motion(clock + t, ww, vw, aw);
    Vec3 vwall = u;
    vwall[w.dim] = vw;
    c = collide(law, b, Body::wall(vwall), n);
  }
  // kinetic energy change in the lab frame: a moving wall does work on the particle, so this is
  // not the law's dissipation (equal to it for a wall at rest)
  const double dE_tr = 0.5 * p.m * (norm2(c.v1) - norm2(h.v));
  const double dE_rot = 0.5 * q * p.m * h.a * h.a * (norm2(c.w1) - norm2(p.w));
  const double dE = dE_tr + dE_rot;
  c.dE = w.moving() ? dE : c.dE;
  const Vec3 dP = p.m * (c.v1 - h.v);    // (a thermal wall's too)
  h.v = c.v1;
  p.w = c.w1;
  if (!last_collision.empty()) last_collision[i] = t;
  if (tracking_fast()) note_speed(i, h.v);
  turned(i);
  p.last_partner = -1;
  const long ni = ++s.ncollisions;
  record_wall(i, s.wall, t, n, dP, c, dE_tr, dE_rot, tc_elastic, ni);
  if (ni > opt.max_collisions) {
    std::ostringstream s;
    s << "particle " << ext[i] << " collided " << ni << " times within one window (cap "
      << opt.max_collisions << "), the last time with a wall: inelastic collapse; use the TC "
      << "model (tc) or a larger cap";
    throw EventCapError(s.str(), ext[i], -1 - (int) schedules[i].wall, t, ni);
  }
  predict(i);
  reschedule(i);
}

}    // namespace granfric
