// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: event prediction under free flight with uniform gravity.
// Uniform gravity cancels in the relative motion of two particles, so pair contact times solve
// |r + v tau| = sigma; a particle against a fixed plane (or cell boundary) moves on a parabola.
#ifndef GRANFRIC_CORE_PREDICTION_H
#define GRANFRIC_CORE_PREDICTION_H

#include "vec3.h"

#include <cmath>
#include <limits>

namespace granfric {

constexpr double NEVER = std::numeric_limits<double>::infinity();

// Earliest tau >= 0 at which |r + v tau| = sigma with the pair approaching (r.v < 0); NEVER if
// none. A pair that already overlaps and approaches gets tau = 0. Components given one by one;
// in 2d (DIM = 2) the relative velocity has no z component and r2 is a constant z distance.
//
// horizon: NEVER is also returned for a contact that certainly comes at tau >= horizon, known
// from a lower bound of the root before the root is taken (the scans ask for contacts earlier
// than the best candidate so far). A contact that is returned is the same number for any
// horizon. The bound: with c = r^2 - sigma^2 > 0 and b = r.v < 0 the root tau = c / (-b +
// sqrt(b^2 - v^2 c)) is at least c / (-2 b), and as computed at least that much less 10 roundings
// (the square root's argument never exceeds b^2 as rounded); the margin 1e-9 covers them and
// the roundings of the horizon and its factor, so a pruned contact would have come out >=
// horizon.
//
// The horizon as the scans carry it: a contact is pruned where c > -b horizon_factor(horizon)
// (c, b as below). The factor holds the bound's 2 and its margin, so that a scan computes it
// once per better candidate, not once per candidate.
inline double horizon_factor(double horizon) { return horizon * (2.0 * (1.0 + 1e-9)); }

// The contact time from b = r.v, c = r^2 - sigma^2 and the relative velocity v (for v^2), with
// the horizon as its factor hf
template <int DIM>
inline double contact_root(double b, double c, double v0, double v1, double v2, double hf)
{
  // Few branches: whether a candidate approaches (b < 0) is a coin toss, which a branch
  // predictor gets wrong about half the time; one branch asks whether it approaches soon enough
  const bool soon = (b < 0.0) & !(c > -b * hf);
  if (!soon) return NEVER;
  const double w2 = DIM == 3 ? v0 * v0 + v1 * v1 + v2 * v2 : v0 * v0 + v1 * v1;
  const double disc = b * b - w2 * c;
  // (the root from a harmless operand where there is none, and the answer selected)
  const bool meet = disc >= 0.0;
  const double tau = c / (-b + std::sqrt(meet ? disc : 1.0));    // stable form of (-b - sqrt(disc))/v2
  return meet ? (tau > 0.0 ? tau : 0.0) : NEVER;
}

template <int DIM>
inline double pair_contact_time(double r0, double r1, double r2, double v0, double v1, double v2,
                                double sigma, double horizon = NEVER)
{
  const double b = DIM == 3 ? r0 * v0 + r1 * v1 + r2 * v2 : r0 * v0 + r1 * v1;
  const double c = (r0 * r0 + r1 * r1 + r2 * r2) - sigma * sigma;
  return contact_root<DIM>(b, c, v0, v1, v2, horizon_factor(horizon));
}

inline double pair_contact_time(const Vec3 &r, const Vec3 &v, double sigma)
{
  return pair_contact_time<3>(r.x, r.y, r.z, v.x, v.y, v.z, sigma);
}

// First tau >= 0 at which x + v tau + g tau^2 / 2 reaches B moving upward (dir = +1: velocity
// > 0 there) or downward (dir = -1); NEVER if it does not. Roots are taken in stable forms and
// selected by the sign of the velocity at the root, so a point that sits on B up to round-off
// is not reported as crossing B again in the direction it just came from.
inline double crossing_time(double x, double v, double g, double B, int dir)
{
  const double a = 0.5 * g, c = x - B;
  if (a == 0.0) {
    if (dir * v <= 0.0) return NEVER;
    const double tau = -c / v;
    return tau > 0.0 ? tau : 0.0;
  }
  const double disc = v * v - 4.0 * a * c;
  if (disc < 0.0) return NEVER;
  const double s = std::sqrt(disc);
  double tau;
  if (dir > 0) {
    // root with derivative 2 a tau + v = +s
    if (v >= 0.0)
      tau = -2.0 * c / (v + s);
    else
      tau = (s - v) / (2.0 * a);
  } else {
    // root with derivative -s
    if (v <= 0.0)
      tau = 2.0 * c / (s - v);
    else
      tau = -(v + s) / (2.0 * a);
  }
  if (!(tau >= 0.0)) {
    // the crossing in this direction lies in the past; if round-off left the point beyond B
    // while it still moves that way, it crosses now
    return (c * dir > 0.0 && v * dir > 0.0) ? 0.0 : NEVER;
  }
  return tau;
}

}    // namespace granfric

#endif
