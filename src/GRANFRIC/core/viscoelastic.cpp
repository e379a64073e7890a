// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the normal restitution of viscoelastic spheres (see viscoelastic.h).
#include "viscoelastic.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace granfric {

namespace {

  // x'' = -x^(3/2) - delta x^(1/2) x' as a first-order system (x may dip below 0 by rounding
  // inside a step near the end of a weakly damped collision: the force is 0 there)
  struct State {
    double x, v;
  };
  inline State rate(const State &y, double delta)
  {
    const double r = std::sqrt(std::max(y.x, 0.0));
    return {y.v, -r * (y.x + delta * y.v)};
  }
  // the force, scaled: it vanishes (from above) where the collision ends
  inline double force(const State &y, double delta) { return y.x + delta * y.v; }

  // one Dormand-Prince 5(4) step of length h from y: the fifth-order result, and the difference
  // from the fourth-order one in err
  State dp_step(const State &y, double h, double delta, double &err)
  {
    auto at = [&](double c1, const State &k1, double c2 = 0, const State &k2 = {0, 0}, double c3 = 0,
                  const State &k3 = {0, 0}, double c4 = 0, const State &k4 = {0, 0}, double c5 = 0,
                  const State &k5 = {0, 0}, double c6 = 0, const State &k6 = {0, 0}) {
      return State{y.x + h * (c1 * k1.x + c2 * k2.x + c3 * k3.x + c4 * k4.x + c5 * k5.x + c6 * k6.x),
                   y.v + h * (c1 * k1.v + c2 * k2.v + c3 * k3.v + c4 * k4.v + c5 * k5.v + c6 * k6.v)};
    };
    const State k1 = rate(y, delta);
    const State k2 = rate(at(1.0 / 5, k1), delta);
    const State k3 = rate(at(3.0 / 40, k1, 9.0 / 40, k2), delta);
    const State k4 = rate(at(44.0 / 45, k1, -56.0 / 15, k2, 32.0 / 9, k3), delta);
    const State k5 = rate(at(19372.0 / 6561, k1, -25360.0 / 2187, k2, 64448.0 / 6561, k3, -212.0 / 729, k4), delta);
    const State k6 = rate(at(9017.0 / 3168, k1, -355.0 / 33, k2, 46732.0 / 5247, k3, 49.0 / 176, k4,
                             -5103.0 / 18656, k5), delta);
    const State y5 = at(35.0 / 384, k1, 0.0, k2, 500.0 / 1113, k3, 125.0 / 192, k4, -2187.0 / 6784, k5,
                        11.0 / 84, k6);
    const State k7 = rate(y5, delta);
    // fifth minus fourth order weights
    const double e1 = 35.0 / 384 - 5179.0 / 57600, e3 = 500.0 / 1113 - 7571.0 / 16695,
                 e4 = 125.0 / 192 - 393.0 / 640, e5 = -2187.0 / 6784 + 92097.0 / 339200,
                 e6 = 11.0 / 84 - 187.0 / 2100, e7 = -1.0 / 40;
    const double ex = h * (e1 * k1.x + e3 * k3.x + e4 * k4.x + e5 * k5.x + e6 * k6.x + e7 * k7.x);
    const double ev = h * (e1 * k1.v + e3 * k3.v + e4 * k4.v + e5 * k5.v + e6 * k6.v + e7 * k7.v);
    err = std::max(std::fabs(ex), std::fabs(ev));
    return y5;
  }

  // E(delta) by integration: from a short series start (the equation is singular at x = 0,
  // x ~ t there) to the first zero of the force, located by bisection of the last step
  double integrate(double delta)
  {
    if (!(delta > 0.0)) return 1.0;
    const double t0 = 1e-6;
    // x = t - (4/15) d t^(5/2) - (4/35) t^(7/2) + (1/15) d^2 t^4 + ..., x' its derivative
    const double s0 = std::sqrt(t0);
    State y{t0 - (4.0 / 15) * delta * t0 * t0 * s0 - (4.0 / 35) * t0 * t0 * t0 * s0 +
                (1.0 / 15) * delta * delta * t0 * t0 * t0 * t0,
            1.0 - (2.0 / 3) * delta * t0 * s0 - 0.4 * t0 * t0 * s0 + (4.0 / 15) * delta * delta * t0 * t0 * t0};
    const double tol = 1e-13;
    double h = 1e-4;
    for (int step = 0; step < 1000000; step++) {
      double err;
      const State y1 = dp_step(y, h, delta, err);
      if (err > tol) {
        h *= std::max(0.1, 0.9 * std::pow(tol / err, 0.2));
        continue;
      }
      if (force(y1, delta) <= 0.0) {
        // the collision ends within this step: Newton's method on the step's length (each trial
        // one accurate step; the force's rate is x' + delta x''), kept inside the bracket
        double lo = 0.0, hi = h, f_lo = force(y, delta), f_hi = force(y1, delta);
        double m = h * f_lo / (f_lo - f_hi);
        State end = y1;
        for (int it = 0; it < 100; it++) {
          double e;
          const State ym = dp_step(y, m, delta, e);
          const double f = force(ym, delta);
          (f > 0.0 ? lo : hi) = m;
          (f > 0.0 ? f_lo : f_hi) = f;
          if (f <= 0.0) end = ym;
          const State r = rate(ym, delta);
          const double df = r.x + delta * r.v;
          double next = df < 0.0 ? m - f / df : 0.5 * (lo + hi);
          if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
          if (std::fabs(next - m) <= 1e-16 * h || hi - lo <= 1e-16 * h) {
            end = dp_step(y, next, delta, e);
            break;
          }
          m = next;
        }
        return std::max(0.0, -end.v);
      }
      y = y1;
      h *= std::min(5.0, 0.9 * std::pow(tol / std::max(err, 1e-300), 0.2));
    }
    return std::max(0.0, -y.v);    // (not reached)
  }

  // cubic (4-point Lagrange) interpolation of table e (points 0 .. n, uniform) at u in points
  double lagrange(const std::vector<double> &e, int n, double u)
  {
    const int j0 = std::min(std::max((int) std::floor(u) - 1, 0), n - 3);
    const double p = u - j0;    // in [0, 3]
    const double l0 = -(p - 1) * (p - 2) * (p - 3) / 6.0, l1 = p * (p - 2) * (p - 3) / 2.0;
    const double l2 = -p * (p - 1) * (p - 3) / 2.0, l3 = p * (p - 1) * (p - 2) / 6.0;
    return l0 * e[j0] + l1 * e[j0 + 1] + l2 * e[j0 + 2] + l3 * e[j0 + 3];
  }

  // Two tables: E at s = sqrt(delta) = k SMAX / N (k = 0 .. N), where E is a smooth function
  // of s, and ln E at ln delta from ln(SMAX^2) to ln(DMAX) in NL steps, where ln E is a smooth,
  // nearly straight function of ln delta. Past DMAX, E = E(DMAX) (DMAX/delta)^(5/3): the
  // strongly damped collision's asymptote (E delta^(5/3) = 1.31013, 1.31033, 1.31036 at
  // delta = 1e3, 3e3, 1e4).
  constexpr int N = 4096, NL = 512;
  constexpr double SMAX = 8.0, DMAX = 1e4;
  struct Tables {
    std::vector<double> e, lne;
    double lo, step;    // ln delta at the log table's first point, and its spacing
  };
  const Tables &tables()
  {
    static const Tables t = [] {
      Tables r;
      r.e.resize(N + 1);
      for (int k = 0; k <= N; k++) {
        const double s = k * (SMAX / N);
        r.e[k] = integrate(s * s);
      }
      r.lo = std::log(SMAX * SMAX);
      r.step = (std::log(DMAX) - r.lo) / NL;
      r.lne.resize(NL + 1);
      for (int k = 0; k <= NL; k++) r.lne[k] = std::log(integrate(std::exp(r.lo + k * r.step)));
      return r;
    }();
    return t;
  }

}    // namespace

double viscoelastic_restitution_exact(double delta)
{
  return integrate(delta);
}

double viscoelastic_restitution(double delta)
{
  if (!(delta > 0.0)) return 1.0;
  const Tables &t = tables();
  const double s = std::sqrt(delta);
  if (s < SMAX) return lagrange(t.e, N, s * (N / SMAX));
  if (delta <= DMAX) return std::exp(lagrange(t.lne, NL, (std::log(delta) - t.lo) / t.step));
  return std::exp(t.lne[NL]) * std::pow(DMAX / delta, 5.0 / 3.0);
}

double viscoelastic_delta(double e)
{
  if (!(e < 1.0)) return 0.0;
  // E decreases with delta: bisection on s, past the table as far as needed
  double lo = 0.0, hi = SMAX;
  while (viscoelastic_restitution(hi * hi) > e && hi < 1e6) hi *= 2.0;
  for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; it++) {
    const double mid = 0.5 * (lo + hi);
    (viscoelastic_restitution(mid * mid) > e ? lo : hi) = mid;
  }
  const double s = 0.5 * (lo + hi);
  return s * s;
}

}    // namespace granfric
