// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: wall motion and contact times (see event_driven.h): static, vibrating
// (piecewise parabolic) and sinusoidal walls on any face, and the first contact of a particle
// with each.
#include "event_driven.h"

#include <algorithm>
#include <cmath>

namespace granfric {

// next contact of the particle's surface with a wall, moving toward it
void EDWall::motion(double s, double &w, double &vw, double &aw) const
{
  if (!vibrating()) {
    w = pos;
    vw = aw = 0.0;
    return;
  }
  if (sine) {
    const double ph = omega * s;
    w = pos + A * std::sin(ph);
    vw = A * omega * std::cos(ph);
    aw = -A * omega * omega * std::sin(ph);
    return;
  }
  const double H = M_PI / omega, a = 8.0 * A * omega * omega / (M_PI * M_PI), v0 = 0.5 * a * H;
  const double k = std::floor(s / H), u = s - k * H;
  const bool up = std::fmod(k, 2.0) == 0.0 || std::fmod(k, 2.0) == -0.0;
  const double sg = up ? 1.0 : -1.0;
  w = pos + sg * (v0 * u - 0.5 * a * u * u);
  vw = sg * (v0 - a * u);
  aw = -sg * a;
}

// A vibrating wall seen from the side of its particles: for a lower wall the coordinates as they
// are, for an upper wall mirrored (x -> -x along its normal), so that the contact searches below
// solve one case only, a surface that oscillates about P between P - A and P + A below the
// particle. m = -side: multiplying by 1 changes no bit, mirroring by -1 is exact.
struct Facing {
  const EDWall &w;
  double m;
  explicit Facing(const EDWall &wall) : w(wall), m(wall.side < 0 ? 1.0 : -1.0) {}
  double top() const { return m * w.pos + w.A; }       // the surface's highest point
  double bottom() const { return m * w.pos - w.A; }    //   and its lowest
  void motion(double s, double &ww, double &vw, double &aw) const
  {
    w.motion(s, ww, vw, aw);
    ww *= m;
    vw *= m;
    aw *= m;
  }
};

// Time (from now) during which a particle cannot touch a vibrating wall (as it faces it) because
// its surface stays above the wall's highest point P + A: until its downward crossing of that
// level (NEVER if it never comes down), 0 if it is at or below the level now. Searching for a
// contact only from there on keeps the cost independent of how long the flight is.
static double time_above_wall(const Facing &f, double x, double v, double g, double a)
{
  const double top = f.top() + a;
  if (x <= top) return 0.0;
  return crossing_time(x, v, g, top, -1);
}

// First contact, at window time >= now, with a sinusoidally vibrating wall (as it faces it). The gap
// f(t) = x(t) - a - w(t) has |f''| <= M = |g| + A omega^2, so on [t0, t0 + h] it stays above
// f(t0) + f'(t0) s - M s^2 / 2: where that bound is positive there is no contact, elsewhere the
// interval is halved; a sign change is refined by bisection. Grazing contacts (f touching 0
// within round-off without changing sign) are not collisions. Several contacts in one step are
// found one after the other, each from the state after the previous one.
static double sine_contact(const Facing &f, double clock, double now, double x, double v, double g,
                           double a)
{
  const double M = std::fabs(g) + f.w.A * f.w.omega * f.w.omega;
  auto gap = [&](double t, double &df) {
    const double dt = t - now;
    double ww, vw, aw;
    f.motion(clock + t, ww, vw, aw);
    df = v + g * dt - vw;
    return x + v * dt + 0.5 * g * dt * dt - a - ww;
  };
  // the last time a contact is possible: the particle falls for ever below the lowest wall point
  // (it hits before), or flies for ever above the highest
  double horizon;
  if (g < 0.0) {
    horizon = crossing_time(x, v, g, f.bottom() + a, -1);
  } else {
    if (v >= f.w.A * f.w.omega && x - a > f.top()) return NEVER;
    horizon = crossing_time(x, v, g, f.top() + a, +1);
    if (horizon == NEVER && v < 0.0) horizon = crossing_time(x, v, g, f.bottom() + a, -1);
  }
  const double tmax = horizon == NEVER ? NEVER : now + horizon + 1e-9 * (1.0 + horizon);
  const double start = now + time_above_wall(f, x, v, g, a);
  if (start >= NEVER) return NEVER;
  double df0;
  double f0 = gap(start, df0);
  if (f0 <= 0.0 && df0 < 0.0) return start;    // overlapping and approaching: now
  const double hmax = 0.25 * 2.0 * M_PI / f.w.omega;
  double t0 = start, h = hmax;
  const double tiny = 1e-13 * (1.0 + std::fabs(now));
  long guard = 0;
  while (t0 < tmax && ++guard < 100000000L) {
    double t1 = t0 + h;
    const double xt = x + (v + 0.5 * g * (t0 - now)) * (t0 - now);
    if (xt - a > f.top()) {
      // above the wall's highest point until the downward crossing of it: no contact before,
      // so a long flight costs no steps of a quarter period
      const double down = crossing_time(xt, v + g * (t0 - now), g, f.top() + a, -1);
      if (down >= NEVER) return NEVER;
      if (down > hmax) {
        t0 += down;
        f0 = gap(t0, df0);
        h = hmax;
        continue;
      }
    }
    if (f0 <= 0.0) {
      // at (or a hair inside) the wall, as after a contact: approaching means a contact now;
      // moving away, f' >= f'(t0) - M s stays >= 0 for s <= f'(t0)/M, so no downward crossing
      // can happen before that (the wall may catch up right after: checked from there)
      if (df0 < 0.0) return t0;
      t1 = t0 + std::min(h, std::max(tiny, df0 / M));
      if (tmax < NEVER && t1 > tmax) t1 = tmax;
      t0 = t1;
      f0 = gap(t1, df0);
      continue;
    }
    if (tmax < NEVER && t1 > tmax) t1 = tmax;
    double df1;
    const double f1 = gap(t1, df1);
    if (f0 > 0.0 && f1 <= 0.0) {
      // a downward zero in (t0, t1]: bisect
      double lo = t0, hi = t1;
      for (int it = 0; it < 200 && hi - lo > 1e-15 * (1.0 + std::fabs(hi)); it++) {
        const double mid = 0.5 * (lo + hi);
        double dm;
        (gap(mid, dm) > 0.0 ? lo : hi) = mid;
      }
      return hi;
    }
    // no sign change: f >= f0 + f'(t0) s - M s^2 / 2 (concave, least at the ends), so a dip
    // below zero inside is impossible when that bound is positive at s = t1 - t0
    const double s = t1 - t0;
    const double bound = f0 + df0 * s - 0.5 * M * s * s;
    if (bound > 0.0 || s < tiny) {
      t0 = t1;    // safe (or a graze within round-off): advance
      f0 = f1;
      df0 = df1;
      h = std::min(hmax, 2.0 * h);
    } else {
      h = 0.5 * s;    // inconclusive: look closer
    }
  }
  return NEVER;
}

// first contact, at window time >= now, of a particle (state x, v now, as it faces the wall)
// with a vibrating wall: on each half period the relative motion is a parabola, solved exactly
static double vibrating_contact(const Facing &f, double clock, double now, double x, double v,
                                double g, double a)
{
  const double H = M_PI / f.w.omega, vmax = 0.5 * 8.0 * f.w.A * f.w.omega * f.w.omega / (M_PI * M_PI) * H;
  // past this time no contact is possible: the particle is for ever above the wall's highest
  // point (upward flight without gravity) or has gone below its lowest (then it hit before)
  double horizon;
  if (g < 0.0) {
    horizon = crossing_time(x, v, g, f.bottom() + a, -1);
  } else {
    if (v >= vmax && x - a > f.top()) return NEVER;
    horizon = crossing_time(x, v, g, f.top() + a, +1);
    if (horizon == NEVER && v < 0.0) horizon = crossing_time(x, v, g, f.bottom() + a, -1);
  }
  double t = now + time_above_wall(f, x, v, g, a);
  const double top = f.top() + a;
  for (long iter = 0; t < NEVER && iter < 100000000L; iter++) {
    const double s = clock + t;
    const double k = std::floor(s / H);
    const double tend = (k + 1.0) * H - clock;
    double ww, vw, aw;
    f.motion(s, ww, vw, aw);
    const double dt = t - now;
    const double xp = x + v * dt + 0.5 * g * dt * dt, vp = v + g * dt;
    if (xp > top) {
      // above the wall's highest point until the downward crossing of it: no contact before;
      // go on from the half period in which that crossing falls, as the loop reaches it (the
      // same numbers), not through every half period of a long flight
      const double down = crossing_time(xp, vp, g, top, -1);
      if (down >= NEVER) return NEVER;
      const double kc = std::floor((clock + t + down) / H);
      if (kc > k + 1.0) {
        t = kc * H - clock;
        continue;
      }
    }
    const double tau = crossing_time(xp - a - ww, vp - vw, g - aw, 0.0, -1);
    if (tau < NEVER && t + tau <= tend) return t + tau;
    if (horizon < NEVER && tend > now + horizon + H) return NEVER;
    t = tend > t ? tend : std::nextafter(t, NEVER);
  }
  return NEVER;
}

// the first contact of particle i with each wall, from its stored state (x, v at its own
// time): the same number whenever it is predicted; not before now
void EDCore::predict_walls(int i)
{
  Schedule &p = schedules[i];
  const Flight &h = flights[i];
  const double a = h.a, tb = h.t;
  for (int k = 0; k < (int) opt.walls.size(); k++) {
    const EDWall &w = opt.walls[k];
    const int d = w.dim;
    const double x = h.x[d], v = h.v[d], g = opt.gravity[d];
    double t;
    if (w.vibrating()) {
      const Facing f(w);    // (the motion along the normal, as seen from the particle's side)
      t = w.sine ? sine_contact(f, clock, tb, f.m * x, f.m * v, f.m * g, a)
                 : vibrating_contact(f, clock, tb, f.m * x, f.m * v, f.m * g, a);
    } else
      t = tb + (w.side < 0 ? crossing_time(x, v, g, w.pos + a, -1) : crossing_time(x, v, g, w.pos - a, +1));
    if (t < now) t = now;
    if (t < wall_times[i]) {
      wall_times[i] = t;
      p.wall = (int8_t) k;
    }
  }
}

}    // namespace granfric
