// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: event prediction under free flight with uniform gravity.
// Uniform gravity cancels in the relative motion of two particles, so pair contact times solve
// |r + v tau| = sigma; a particle against a fixed plane (or cell boundary) moves on a parabola.
#ifndef GRANFRIC_CORE_PREDICTION_H
#define GRANFRIC_CORE_PREDICTION_H

#include "vec3.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace granfric {

constexpr double NEVER = std::numeric_limits<double>::infinity();

// Earliest tau >= 0 at which |r + v tau| = sigma with the pair approaching (r.v < 0); NEVER if
// none. A pair that already overlaps and approaches gets tau = 0. Components given one by one;
// in 2d (DIM = 2) the relative velocity has no z component and r2 is a constant z distance.
//
// horizon: NEVER is also returned for a contact that certainly comes at tau >= horizon. A
// contact that is returned is the same number for any horizon. The scans ask for contacts
// earlier than their best candidate so far; most candidates are not, and whether one is must
// not cost a mispredicted branch (whether a candidate approaches is a coin toss, which a
// branch predictor gets wrong about half the time). So the test is exact up to a margin and
// decided without branches: with b = r.v, c = r^2 - sigma^2 and w2 = v^2 the contact time is
// the first root of f(tau) = w2 tau^2 + 2 b tau + c (f(0) = c), and it lies at or before h
// iff the pair approaches (b < 0), the roots are real (b^2 - w2 c >= 0) and either f(h) <= 0
// or the vertex -b / w2 lies at or before h. The one branch, on that outcome, is rarely taken.
//
// The margin: h is the horizon widened by 1e-6 of itself and by 1e-15 of the time it ends at
// (horizon_limit), so that no root computed earlier than the horizon is dropped. The root as
// computed lies within about 1e-7 of the first root of the quadratic of the computed b, c and
// w2 (the square root of b^2 - w2 c, whose subtraction cancels for a grazing contact, enters a
// sum of two positive terms), the contact time tr + tau and the horizon before - tr are each
// rounded once, and f(h), evaluated with rounding, keeps its sign where its root lies 1e-6 of h
// away (Prediction.PairContactTimeHorizonOnlyDropsLaterContacts).
inline double horizon_limit(double ahead, double before)
{
  return ahead * (1.0 + 1e-6) + std::fabs(before) * 1e-15;
}

// The contact time from b = r.v, c = r^2 - sigma^2 and the relative velocity v (for v^2), with
// the horizon as its limit h
template <int DIM>
inline double contact_root(double b, double c, double v0, double v1, double v2, double h)
{
  const double w2 = DIM == 3 ? v0 * v0 + v1 * v1 + v2 * v2 : v0 * v0 + v1 * v1;
  const double disc = b * b - w2 * c;
  const double wh = w2 * h;
  // (b <= 0, disc >= 0 and one of f(h) <= 0 and -b - w2 h <= 0: one comparison; b = 0, where
  // the pair does not approach, and NaN are left out after it)
  const double fh = c + (2.0 * b + wh) * h;
  if (!(std::max(b, std::max(-disc, std::min(fh, -b - wh))) <= 0.0)) return NEVER;
  if (!(b < 0.0) || !(disc >= 0.0)) return NEVER;
  const double tau = c / (-b + std::sqrt(disc));    // stable form of (-b - sqrt(disc))/v2
  return tau > 0.0 ? tau : 0.0;
}

template <int DIM>
inline double pair_contact_time(double r0, double r1, double r2, double v0, double v1, double v2,
                                double sigma, double horizon = NEVER)
{
  const double b = DIM == 3 ? r0 * v0 + r1 * v1 + r2 * v2 : r0 * v0 + r1 * v1;
  const double c = (r0 * r0 + r1 * r1 + r2 * r2) - sigma * sigma;
  return contact_root<DIM>(b, c, v0, v1, v2, horizon_limit(horizon, horizon));
}

inline double pair_contact_time(const Vec3 &r, const Vec3 &v, double sigma)
{
  return pair_contact_time<3>(r.x, r.y, r.z, v.x, v.y, v.z, sigma);
}

// First tau >= 0 at which x + v tau + g tau^2 / 2 reaches B moving upward (dir = +1: velocity
// > 0 there) or downward (dir = -1); NEVER if it does not. Roots are taken in stable forms and
// selected by the sign of the velocity at the root, so a point that sits on B up to round-off
// is not reported as crossing B again in the direction it just came from. A point on B or a
// hair beyond it that moves on that way, or is at rest there and accelerated that way (a grain
// left at rest on a floor under gravity), crosses now, and one that moves back from beyond B
// too slowly to reach it crosses when it turns: such roots are 0/0 or not real.
inline double crossing_time(double x, double v, double g, double B, int dir)
{
  const double a = 0.5 * g, c = x - B;
  if (a == 0.0) {
    if (dir * v <= 0.0) return NEVER;
    const double tau = -c / v;
    return tau > 0.0 ? tau : 0.0;
  }
  const double disc = v * v - 4.0 * a * c;
  // (not real: B lies beyond the turning point, or the point beyond B is accelerated on)
  if (disc < 0.0) return c * dir >= 0.0 ? std::max(0.0, -v / g) : NEVER;
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
    // the crossing in this direction lies in the past (or is 0/0); if round-off left the point
    // beyond B while it still moves that way, it crosses now
    const bool onward = v * dir > 0.0 || (v == 0.0 && g * dir > 0.0);
    return (c * dir >= 0.0 && onward) ? 0.0 : NEVER;
  }
  return tau;
}

}    // namespace granfric

#endif
