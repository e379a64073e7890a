// Test helpers: random hard-sphere systems, and the core event loop run window by window.
#ifndef GRANFRIC_TEST_ED_FIXTURE_H
#define GRANFRIC_TEST_ED_FIXTURE_H

#include "core/event_driven.h"
#include "reference_ed.h"

#include <cmath>
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

  explicit CoreRun(const Reference &ref, long cap = 1000000)
  {
    EDOptions o;
    o.dim = ref.dim;
    for (int d = 0; d < 3; d++) {
      o.lo[d] = ref.lo[d];
      o.hi[d] = ref.lo[d] + ref.L[d];
    }
    o.gravity = ref.gravity;
    o.tc = ref.tc;
    o.max_collisions = cap;
    for (int d = 0; d < 3; d++) o.periodic[d] = ref.periodic[d];
    for (const auto &w : ref.walls) {
      EDWall e;
      e.dim = w.dim;
      e.side = w.side;
      e.pos = w.pos;
      e.laws.assign(ref.ntypes + 1, w.law);
      e.A = w.A;
      e.omega = w.omega;
      e.sine = w.sine;
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

  void window(double dt)
  {
    total.add(ed.run(dt));
    for (int i = 0; i < ed.size(); i++) ed.particle(i).t_last -= dt;    // window times restart at 0
    time += dt;
  }

  void run(double T, double dt)
  {
    while (time < T - 1e-12 * T) window(std::min(dt, T - time));
  }
};

}    // namespace granfric_test

#endif
