// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// Test-only brute-force O(N^2) event-driven reference: at every step it scans all pairs and
// their periodic images for the globally earliest collision. It shares only the collision law
// and the pair contact-time formula with the core; its bookkeeping (no cells, no queue, no
// invalidation) is independent. Each particle keeps its own time stamp so that positions do not
// accumulate round-off from drifting everybody at every event.
#ifndef GRANFRIC_TEST_REFERENCE_ED_H
#define GRANFRIC_TEST_REFERENCE_ED_H

#include "core/collision.h"
#include "core/prediction.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <vector>

namespace granfric_test {

using namespace granfric;

struct RefParticle {
  Vec3 x, v, w;    // at time t
  double t = 0.0;
  double a = 0.5, m = 1.0, q = 0.4;
  int type = 1;
  double t_last = -INF;
  int last_partner = -1;
  int last_off[3] = {0, 0, 0};
};

struct RefWall {
  int dim = 1, side = -1;
  double pos = 0.0;
  LawParams law;
  double A = 0.0, omega = 0.0;    // vibrating wall (any side): piecewise-parabolic sinusoid mimic
  bool sine = false;              //   or the sinusoid itself
  Vec3 slide;                     // velocity within the wall's plane
  int shake_dim = -1;             // and an oscillation within it: displacement
  double shake_A = 0.0, shake_omega = 0.0;    //   shake_A sin(shake_omega s) along shake_dim
  Vec3 surface(double s) const
  {
    Vec3 u = slide;
    if (shake_dim >= 0) u[shake_dim] += shake_A * shake_omega * std::cos(shake_omega * s);
    return u;
  }
  // the motion, written here independently of the core: on half period k (length pi/omega) the
  // wall rises and falls back (k even) or dips and comes back (k odd) with constant |acceleration|
  // 8 A omega^2 / pi^2, reaching pos +- A at mid-period
  double height(double s) const
  {
    if (A == 0.0) return pos;
    if (sine) return pos + A * std::sin(omega * s);
    const double H = M_PI / omega, acc = 8 * A * omega * omega / (M_PI * M_PI);
    const double k = std::floor(s / H), u = s - k * H;
    const double up = ((long long) k % 2 == 0) ? 1.0 : -1.0;
    return pos + up * 0.5 * acc * u * (H - u);
  }
  double speed(double s) const
  {
    if (A == 0.0) return 0.0;
    if (sine) return A * omega * std::cos(omega * s);
    const double H = M_PI / omega, acc = 8 * A * omega * omega / (M_PI * M_PI);
    const double k = std::floor(s / H), u = s - k * H;
    const double up = ((long long) k % 2 == 0) ? 1.0 : -1.0;
    return up * acc * (0.5 * H - u);
  }
};

struct Reference {
  int dim = 3;
  bool periodic[3] = {true, true, true};
  std::vector<RefWall> walls;
  long wall_collisions = 0;
  Vec3 lo, L;
  Vec3 gravity;
  double tc = 0.0;
  // Lees-Edwards: the image one period up in y lies shift(t) further in x and moves shear_rate
  // faster in x
  bool shear = false;
  double shear_rate = 0.0, shift0 = 0.0;
  double shift(double t) const { return shift0 + shear_rate * t; }
  int ntypes = 1;
  std::vector<LawParams> laws;    // (ntypes+1)^2
  std::vector<RefParticle> p;
  double time = 0.0;
  long collisions = 0;
  double dE = 0.0;
  // collision virial: sum of r_a dP_b (xx, yy, zz, xy, xz, yz), dP = m (v' - v) on the particle
  // whose centre r points to (from its partner's centre, or from the wall's contact point)
  double virial[6] = {0, 0, 0, 0, 0, 0};
  void tally_virial(const Vec3 &r, const Vec3 &dP)
  {
    const double w[6] = {r.x * dP.x, r.y * dP.y, r.z * dP.z, r.x * dP.y, r.x * dP.z, r.y * dP.z};
    for (int k = 0; k < 6; k++) virial[k] += w[k];
  }
  // instant global events (kicks) at absolute times, applied to all particles at once
  std::vector<double> kick_times;
  std::function<void(std::vector<RefParticle> &, int)> kick;
  size_t next_kick = 0;

  Vec3 pos(const RefParticle &q, double t) const
  {
    const double dt = t - q.t;
    return q.x + dt * q.v + (0.5 * dt * dt) * gravity;
  }
  Vec3 vel(const RefParticle &q, double t) const { return q.v + (t - q.t) * gravity; }
  void bring(RefParticle &q, double t) const
  {
    q.x = pos(q, t);
    q.v = vel(q, t);
    q.t = t;
  }

  // minimum-image separation per periodic dimension
  Vec3 min_image(Vec3 r) const
  {
    for (int d = 0; d < dim; d++)
      if (periodic[d]) r[d] -= L[d] * std::round(r[d] / L[d]);
    return r;
  }

  void run_until(double t_end, long max_collisions = 100000000)
  {
    const int n = (int) p.size();
    double amax = 0;
    for (auto &q : p) amax = std::max(amax, q.a);
    while (time < t_end) {
      double vmax = 0;
      for (auto &q : p) vmax = std::max(vmax, norm(vel(q, time)));
      // within H no pair moves by more than 1.5 L - 2 amax relative to its minimum image,
      // so image offsets of -1, 0, +1 around it contain every possible contact
      double H = INF;
      // (with shear an image moves up to the shear rate faster)
      for (int d = 0; d < dim; d++)
        if (periodic[d])
          H = std::min(H, (1.5 * L[d] - 2.0 * amax) / (2.0 * vmax + 2.0 * std::fabs(shear_rate) + 1e-300));
      double best = std::min(H, t_end - time);
      int bi = -1, bj = -1, boff[3] = {0, 0, 0}, bwall = -1;
      for (int i = 0; i < n; i++) {
        const Vec3 xi = pos(p[i], time), vi = vel(p[i], time);
        for (int k = 0; k < (int) walls.size(); k++) {
          const RefWall &w = walls[k];
          const int d = w.dim;
          double tau;
          if (w.A > 0.0) {
            // brute force: march in steps of 1/20000 period up to the best time found so far,
            // then bisect the first downward zero of the gap between surface and wall
            auto gap = [&](double s) {
              const double dt = s;
              const double x = xi[d] + vi[d] * dt + 0.5 * gravity[d] * dt * dt;
              return w.side < 0 ? x - p[i].a - w.height(time + s) : w.height(time + s) - x - p[i].a;
            };
            tau = NEVER;
            const double h = 2 * M_PI / w.omega / 20000;
            double s0 = 0.0, f0 = gap(0.0);
            for (double s1 = h; s0 < best; s1 += h) {
              const double f1 = gap(s1);
              if (f0 > 0.0 && f1 <= 0.0) {
                double lo = s0, hi = s1;
                for (int it = 0; it < 200 && hi - lo > 1e-15 * (1 + hi); it++) {
                  const double mid = 0.5 * (lo + hi);
                  (gap(mid) > 0.0 ? lo : hi) = mid;
                }
                tau = hi;
                break;
              }
              s0 = s1;
              f0 = f1;
            }
          } else {
            tau = w.side < 0 ? crossing_time(xi[d], vi[d], gravity[d], w.pos + p[i].a, -1)
                             : crossing_time(xi[d], vi[d], gravity[d], w.pos - p[i].a, +1);
          }
          if (tau < best) {
            best = tau;
            bi = i;
            bwall = k;
          }
        }
      }
      for (int i = 0; i < n; i++) {
        const Vec3 xi = pos(p[i], time), vi = vel(p[i], time);
        for (int j = i + 1; j < n; j++) {
          const Vec3 r0 = xi - pos(p[j], time), v0 = vi - vel(p[j], time);
          const int kx0 = periodic[0] ? 1 : 0, ky0 = periodic[1] ? 1 : 0;
          const int kz = dim == 3 && periodic[2] ? 1 : 0;
          const int k0y = periodic[1] ? (int) std::lround(r0.y / L.y) : 0;
          for (int ky = -ky0; ky <= ky0; ky++) {
            // (the image o_y periods up: shifted and moving in x with shear)
            const int oy = k0y + ky;
            Vec3 r = r0, v = v0;
            if (shear) {
              r.x -= oy * shift(time);
              v.x -= oy * shear_rate;
            }
            int k0[3] = {0, oy, 0};
            for (int d = 0; d < dim; d++)
              if (periodic[d] && d != 1) k0[d] = (int) std::lround(r[d] / L[d]);
            for (int kx = -kx0; kx <= kx0; kx++)
              for (int k3 = -kz; k3 <= kz; k3++) {
                const int off[3] = {k0[0] + kx, oy, k0[2] + k3};
                if (p[i].last_partner == j && p[j].last_partner == i &&
                    off[0] == p[i].last_off[0] && off[1] == p[i].last_off[1] &&
                    off[2] == p[i].last_off[2])
                  continue;
                const Vec3 s(off[0] * L.x, off[1] * L.y, off[2] * L.z);
                const double tau = pair_contact_time(r - s, v, p[i].a + p[j].a);
                if (tau < best) {
                  best = tau;
                  bi = i;
                  bj = j;
                  bwall = -1;
                  for (int d = 0; d < 3; d++) boff[d] = off[d];
                }
              }
          }
        }
      }
      if (next_kick < kick_times.size() && kick_times[next_kick] <= time + best &&
          kick_times[next_kick] < t_end) {
        time = kick_times[next_kick];
        for (auto &q : p) {
          bring(q, time);
          q.last_partner = -1;
        }
        kick(p, (int) next_kick++);
        continue;
      }
      time += best;
      if (bi < 0) continue;
      if (bwall >= 0) {
        RefParticle &a = p[bi];
        bring(a, time);
        const RefWall &w = walls[bwall];
        Vec3 nn;
        nn[w.dim] = w.side < 0 ? 1.0 : -1.0;
        LawParams law = w.law;
        const double sa = time - a.t_last;
        if (tc > 0 && sa >= 0 && sa < tc) law = law.elastic();
        Vec3 vwall = w.surface(time);
        vwall[w.dim] = w.speed(time);
        const Collision c = collide(law, Body{a.v, a.w, a.m, a.a, a.q}, Body::wall(vwall), nn);
        tally_virial(a.a * nn, a.m * (c.v1 - a.v));
        a.v = c.v1;
        a.w = c.w1;
        a.t_last = time;
        a.last_partner = -1;
        dE += c.dE;
        wall_collisions++;
        continue;
      }
      RefParticle &a = p[bi], &b = p[bj];
      bring(a, time);
      bring(b, time);
      Vec3 r = a.x - b.x - Vec3(boff[0] * L.x, boff[1] * L.y, boff[2] * L.z);
      Vec3 vb = b.v;    // (b's image's velocity)
      if (shear) {
        r.x -= boff[1] * shift(time);
        vb.x += boff[1] * shear_rate;
      }
      const Vec3 nn = (1.0 / norm(r)) * r;
      LawParams law = laws[a.type * (ntypes + 1) + b.type];
      const double sa = time - a.t_last, sb = time - b.t_last;
      if (tc > 0 && ((sa >= 0 && sa < tc) || (sb >= 0 && sb < tc))) law = law.elastic();
      const Collision c =
          collide(law, Body{a.v, a.w, a.m, a.a, a.q}, Body{vb, b.w, b.m, b.a, b.q}, nn);
      tally_virial(r, a.m * (c.v1 - a.v));
      a.v = c.v1;
      a.w = c.w1;
      b.v = c.v2 - (vb - b.v);
      b.w = c.w2;
      a.t_last = b.t_last = time;
      a.last_partner = bj;
      b.last_partner = bi;
      for (int d = 0; d < 3; d++) {
        a.last_off[d] = boff[d];
        b.last_off[d] = -boff[d];
      }
      dE += c.dE;
      if (++collisions > max_collisions) throw std::runtime_error("reference: too many collisions");
    }
    for (auto &q : p) bring(q, t_end);
  }
};

}    // namespace granfric_test

#endif
