// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// Test helpers: random hard-sphere systems, and the core event loop run window by window.
#ifndef GRANFRIC_TEST_ED_FIXTURE_H
#define GRANFRIC_TEST_ED_FIXTURE_H

#include "core/event_driven.h"
#include "reference_ed.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <random>
#include <stdexcept>

namespace granfric_test {

struct SystemSpec {
  int n = 100;
  int dim = 2;
  double phi = 0.1;            // area or volume fraction
  bool polydisperse = true;    // radii in [0.4, 0.6], masses ~ a^dim times a random factor
  double q = 0.4;
  unsigned seed = 1;
  bool lattice = false;        // start on a (triangular / simple cubic) lattice, for dense systems
};

inline SystemSpec spec_of(int n, int dim, double phi, unsigned seed)
{
  SystemSpec s;
  s.n = n;
  s.dim = dim;
  s.phi = phi;
  s.seed = seed;
  return s;
}

// random non-overlapping configuration with Gaussian velocities and spins
inline Reference make_system(const SystemSpec &s, const LawParams &law)
{
  std::mt19937_64 gen(s.seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::normal_distribution<double> G(0.0, 1.0);
  Reference ref;
  ref.dim = s.dim;
  ref.ntypes = 2;
  ref.laws.assign(9, law);
  std::vector<double> radii(s.n);
  double vol = 0;
  for (auto &a : radii) {
    a = s.polydisperse ? 0.4 + 0.2 * U(gen) : 0.5;
    vol += s.dim == 2 ? M_PI * a * a : 4.0 / 3.0 * M_PI * a * a * a;
  }
  const double side = std::pow(vol / s.phi, 1.0 / s.dim);
  ref.L = Vec3(side, side, s.dim == 2 ? 1.0 : side);
  ref.lo = Vec3(-0.3 * side, 0.1, s.dim == 2 ? -0.5 : 0.0);
  ref.p.resize(s.n);
  int m = (int) std::ceil(std::pow((double) s.n, 1.0 / s.dim) - 1e-9);
  for (int i = 0; i < s.n; i++) {
    RefParticle &p = ref.p[i];
    p.a = radii[i];
    p.m = std::pow(2 * p.a, s.dim) * (s.polydisperse ? 0.5 + U(gen) : 1.0);
    p.q = s.q;
    p.type = 1 + (i % 2);
    if (s.lattice) {
      const double h = side / m;
      const int ix = i % m, iy = (i / m) % m, iz = i / (m * m);
      p.x = Vec3(ref.lo.x + (ix + 0.5 + (s.dim == 2 ? 0.5 * (iy % 2) - 0.25 : 0.0)) * h,
                 ref.lo.y + (iy + 0.5) * h, s.dim == 2 ? 0.0 : ref.lo.z + (iz + 0.5) * h);
    } else {
      for (int tries = 0;; tries++) {
        if (tries > 100000) throw std::runtime_error("make_system: cannot place particles");
        p.x = Vec3(ref.lo.x + side * U(gen), ref.lo.y + side * U(gen),
                   s.dim == 2 ? 0.0 : ref.lo.z + side * U(gen));
        bool ok = true;
        for (int j = 0; j < i && ok; j++)
          ok = norm(ref.min_image(p.x - ref.p[j].x)) > p.a + ref.p[j].a;
        if (ok) break;
      }
    }
    p.v = Vec3(G(gen), G(gen), s.dim == 2 ? 0.0 : G(gen));
    p.w = s.dim == 2 ? Vec3(0, 0, G(gen) / p.a) : (1.0 / p.a) * Vec3(G(gen), G(gen), G(gen));
  }
  return ref;
}

// the core, fed from a Reference's particles, run in windows of length dt up to time T
struct CoreRun {
  EventDriven ed;
  EDStats total;
  double time = 0.0;

  // neighbours, skin, simd: how the core finds candidates (EDOptions::neighbours, list_skin,
  // simd); prefetch_bytes, tick_last: EDOptions::prefetch_bytes, tick_last
  explicit CoreRun(const Reference &ref, long cap = 1000000, int neighbours = EDOptions::AUTO,
                   double skin = 0.0, bool simd = true, long prefetch_bytes = EDOptions().prefetch_bytes,
                   uint32_t tick_last = EDOptions().tick_last)
  {
    EDOptions o;
    o.tick_last = tick_last;
    o.neighbours = neighbours;
    o.list_skin = skin;
    o.simd = simd;
    o.prefetch_bytes = prefetch_bytes;
    o.dim = ref.dim;
    for (int d = 0; d < 3; d++) {
      o.lo[d] = ref.lo[d];
      o.hi[d] = ref.lo[d] + ref.L[d];
    }
    o.gravity = ref.gravity;
    o.tc = ref.tc;
    o.max_collisions = cap;
    for (int d = 0; d < 3; d++) o.periodic[d] = ref.periodic[d];
    o.shear = ref.shear;
    o.shear_rate = ref.shear_rate;
    shift = [s0 = ref.shift0, u = ref.shear_rate](double t) { return s0 + u * t; };
    for (const auto &w : ref.walls) {
      EDWall e;
      e.dim = w.dim;
      e.side = w.side;
      e.pos = w.pos;
      e.laws.assign(ref.ntypes + 1, w.law);
      e.A = w.A;
      e.omega = w.omega;
      e.sine = w.sine;
      e.slide = w.slide;
      e.shake_dim = w.shake_dim;
      e.shake_A = w.shake_A;
      e.shake_omega = w.shake_omega;
      o.walls.push_back(e);
    }
    // the core keeps the shape factor per type: the reference's particles give it
    o.shape.assign(ref.ntypes + 1, 0.0);
    for (const RefParticle &r : ref.p) {
      if (o.shape[r.type] != 0.0 && o.shape[r.type] != r.q)
        throw std::invalid_argument("CoreRun: particles of one type with different shape factors");
      o.shape[r.type] = r.q;
    }
    for (auto &q : o.shape) q = q == 0.0 ? 0.4 : q;
    ed.configure(o, ref.ntypes, ref.laws);
    ed.resize((int) ref.p.size());
    for (size_t i = 0; i < ref.p.size(); i++) {
      const RefParticle &r = ref.p[i];
      auto p = ed.particle((int) i);
      p.x = r.x;
      p.v = r.v;
      p.w = r.w;
      p.a = r.a;
      p.m = r.m;
      p.type = r.type;
      p.t_last = r.t_last;
    }
  }

  std::function<double(double)> shift;    // the reference's shear shift at time t
  void window(double dt)
  {
    ed.set_shear_shift(shift(time));
    total.add(ed.run(dt));
    for (int i = 0; i < ed.size(); i++) ed.particle(i).t_last -= dt;    // window times restart at 0
    time += dt;
  }

  void run(double T, double dt)
  {
    while (time < T - 1e-12 * T) window(std::min(dt, T - time));
  }
  // windows of dt up to T, every particle's velocity turned by a right angle about z at the
  // middle of each window (a global event: every prediction goes stale, the temperature stays)
  void run_turning(double T, double dt)
  {
    while (time < T - 1e-12 * T) {
      std::vector<double> turn = {0.5 * dt};
      ed.set_global_events(turn, [this](int) {
        for (int e = 0; e < ed.size(); e++) {
          Vec3 &v = ed.particle(e).v;
          v = Vec3(v.y, -v.x, v.z);
        }
      });
      window(dt);
    }
  }
};

// how many particles of two runs of one system differ in some bit of x, v or w at window time 0
inline int states_differing(const CoreRun &a, const CoreRun &b)
{
  auto same = [](const Vec3 &u, const Vec3 &v) { return std::memcmp(&u, &v, sizeof(Vec3)) == 0; };
  int differ = 0;
  for (int i = 0; i < a.ed.size(); i++)
    differ += !(same(a.ed.position(i, 0.0), b.ed.position(i, 0.0)) &&
                same(a.ed.velocity(i, 0.0), b.ed.velocity(i, 0.0)) && same(a.ed.particle(i).w, b.ed.particle(i).w));
  return differ;
}

// the reference's kicks in the window [t0, t0 + dt) as the core's global events of that window,
// each adding dv(e, k) to the velocity of particle e (k: the kick's index in the reference)
inline void window_kicks(EventDriven &ed, const Reference &ref, double t0, double dt,
                         std::function<Vec3(int, int)> dv)
{
  std::vector<double> times;
  std::vector<int> index;
  for (size_t k = 0; k < ref.kick_times.size(); k++)
    if (ref.kick_times[k] >= t0 && ref.kick_times[k] < t0 + dt) {
      times.push_back(ref.kick_times[k] - t0);
      index.push_back((int) k);
    }
  ed.set_global_events(times, [&ed, index, dv](int g) {
    for (int e = 0; e < ed.size(); e++) ed.particle(e).v += dv(e, index[g]);
  });
}

// one law of each kind, for tests over every law (0 rough, 1 Walton, 2 Jenkins-Zhang)
// nwin windows of dt with the queue kept (start(), then advance_to(dt) and rebase(dt) each, as
// fix hardsphere/ed runs), against the reference run as long: the same collisions, and every
// state to 1e-9 (set the core's options, e.g. the shear shift, before)
inline void kept_queue_equals_reference(Reference &ref, CoreRun &run, double dt, int nwin)
{
  run.ed.start();
  for (int w = 0; w < nwin; w++) {
    run.total.add(run.ed.advance_to(dt));
    run.ed.rebase(dt);
  }
  ref.run_until(nwin * dt);
  EXPECT_EQ(run.total.collisions, ref.collisions);
  for (size_t i = 0; i < ref.p.size(); i++) {
    EXPECT_LT(norm(run.ed.position((int) i, 0.0) - ref.p[i].x), 1e-9);
    EXPECT_LT(norm(run.ed.velocity((int) i, 0.0) - ref.p[i].v), 1e-9);
    EXPECT_LT(ref.p[i].a * norm(run.ed.particle((int) i).w - ref.p[i].w), 1e-9);
  }
}

inline LawParams law_of(int k)
{
  switch (k) {
    case 0: return LawParams::rough(0.9, 0.4);
    case 1: return LawParams::walton(0.85, 0.3, 0.5);
    default: return LawParams::jz(0.05, 0.1, 0.2, 0.2);
  }
}

// mean free time of a system, N T / (2 collisions), from the shortest core run of doubling
// length T with at least max(4, N) collisions (inelastic systems cool, so the estimate must
// come from the first collisions)
inline double mean_free_time(const Reference &ref)
{
  const long need = std::max<long>(4, (long) ref.p.size());
  for (double T = 1e-3;; T *= 2.0) {
    CoreRun probe(ref);
    probe.window(T);
    if (probe.total.collisions >= need || T > 1e6)
      return ref.p.size() * T / (2.0 * std::max<long>(1, probe.total.collisions));
  }
}

}    // namespace granfric_test

#endif
