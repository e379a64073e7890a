// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// Core tests of the event-driven loop: whole trajectories equal to the brute-force reference
// for every law, 2D and 3D, N = 2..500 and windows from 0.01 to 10 mean free times; conservation;
// no overlaps; gravity; the TC model against inelastic collapse and the event cap without it.
#include "ed_fixture.h"
#include "core/law_table.h"

#include "core/id_map.h"
#include "core/kicks.h"

#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <random>
#include <type_traits>
#include <unordered_map>

using namespace granfric;
using namespace granfric_test;

namespace {

// Largest deviation from the reference: positions absolute (unit diameter scale), velocities and
// contact-point spin speeds a w relative to the rms speed.
// Trajectories of hard-sphere gases are chaotic, so differences in the last bit (the reference
// drifts all particles every event, the core updates lazily) grow by a factor of order
// mean free path / diameter per collision; 1e-9 relative after several collision times is
// what exactness means here. The dilute case (area fraction 0.05, mean free path ~ 10
// diameters) amplifies most (a factor ~20 per collision, measured): there 2 mean free times are
// the horizon at which 1e-9 still holds; two particles in a small periodic box (mean free path
// ~4 diameters) amplify by ~6 per collision and hold 1e-9 for about 12 collisions.
void expect_same_state(const Reference &ref, const CoreRun &run, double tol)
{
  double vrms = 0;
  for (const auto &a : ref.p) vrms += norm2(a.v);
  vrms = std::sqrt(vrms / ref.p.size()) + 1e-300;
  double dx = 0, dv = 0, dw = 0;
  for (size_t i = 0; i < ref.p.size(); i++) {
    const auto &a = ref.p[i];
    const auto &b = run.ed.particle((int) i);
    dx = std::max(dx, norm(a.x - b.x));
    dv = std::max(dv, norm(a.v - b.v) / vrms);
    dw = std::max(dw, a.a * norm(a.w - b.w) / vrms);
  }
  EXPECT_LT(dx, tol) << "positions deviate from the brute-force reference";
  EXPECT_LT(dv, tol) << "velocities deviate from the brute-force reference";
  EXPECT_LT(dw, tol) << "spins deviate from the brute-force reference";
}

// the collision virial equals the reference's sum over its collisions (pairs and walls), to
// rounding against the size of its diagonal, and the diagonal is positive (collisions repel)
void expect_same_virial(const Reference &ref, const EDStats &st)
{
  const double scale = std::fabs(ref.virial[0]) + std::fabs(ref.virial[1]) + std::fabs(ref.virial[2]);
  EXPECT_GT(ref.virial[0] + ref.virial[1] + ref.virial[2], 0.0);
  for (int k = 0; k < 6; k++) EXPECT_NEAR(st.virial[k], ref.virial[k], 1e-9 * scale) << "component " << k;
}

struct Case {
  int law, dim, n;
  double phi, dt_mft, T_mft;
};

class Trajectory : public ::testing::TestWithParam<Case> {};

std::string case_name(const ::testing::TestParamInfo<Case> &info)
{
  static const char *law[] = {"rough", "walton", "jz"};
  auto num = [](double x) {
    std::string s = std::to_string(x);
    s.erase(s.find_last_not_of('0') + 1);
    if (s.back() == '.') s.pop_back();
    for (auto &ch : s)
      if (ch == '.') ch = 'p';
    return s;
  };
  const Case &c = info.param;
  return std::string(law[c.law]) + "_" + std::to_string(c.dim) + "d_n" + std::to_string(c.n) +
      "_phi" + num(c.phi) + "_dt" + num(c.dt_mft) + "mft";
}

TEST_P(Trajectory, EqualsBruteForceReference)
{
  const Case c = GetParam();
  SystemSpec s;
  s.n = c.n;
  s.dim = c.dim;
  s.phi = c.phi;
  s.q = c.dim == 2 ? 0.5 : 0.4;
  s.seed = 100 + c.law * 10 + c.dim + c.n;
  Reference ref = make_system(s, law_of(c.law));
  const double mft = mean_free_time(ref);
  const double T = c.T_mft * mft;
  CoreRun run(ref);
  run.run(T, c.dt_mft * mft);
  ref.run_until(T);
  ASSERT_GE(ref.collisions, std::max(4, c.n));    // several collisions per particle happened
  EXPECT_EQ(run.total.collisions, ref.collisions);
  EXPECT_NEAR(run.total.dE, ref.dE, 1e-9 * std::fabs(ref.dE));
  expect_same_virial(ref, run.total);
  expect_same_state(ref, run, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(
    Core, Trajectory,
    ::testing::Values(Case{0, 2, 2, 0.2, 0.3, 8}, Case{1, 3, 2, 0.1, 3.0, 8},
                      Case{0, 2, 20, 0.3, 0.01, 4}, Case{1, 2, 20, 0.3, 1.0, 6},
                      Case{2, 2, 20, 0.3, 10.0, 6}, Case{0, 3, 20, 0.2, 0.3, 6},
                      Case{1, 3, 20, 0.2, 10.0, 6}, Case{2, 3, 20, 0.2, 0.05, 4},
                      Case{0, 2, 200, 0.4, 2.0, 4}, Case{1, 2, 200, 0.05, 0.5, 2},
                      Case{2, 2, 200, 0.25, 10.0, 4}, Case{1, 3, 200, 0.3, 1.0, 3},
                      Case{2, 3, 200, 0.1, 10.0, 3}, Case{0, 3, 200, 0.2, 0.1, 3},
                      Case{1, 2, 500, 0.3, 3.0, 3}, Case{0, 3, 500, 0.25, 10.0, 2}),
    case_name);

TEST(EventDriven, GravityEqualsReference)
{
  for (int dim = 2; dim <= 3; dim++) {
    SystemSpec s;
    s.n = 60;
    s.dim = dim;
    s.phi = 0.2;
    s.seed = 77 + dim;
    Reference ref = make_system(s, LawParams::walton(0.8, 0.4, 0.3));
    ref.gravity = dim == 2 ? Vec3(0.3, -2.0, 0.0) : Vec3(0.2, -0.5, -1.5);
    const double mft = mean_free_time(ref);
    CoreRun run(ref);
    run.run(8 * mft, 0.7 * mft);
    ref.run_until(8 * mft);
    EXPECT_EQ(run.total.collisions, ref.collisions);
    expect_same_state(ref, run, 1e-9);
  }
}

// viscoelastic normal restitution (each collision's r from its normal speed), between particles
// and at walls: event by event equal to the reference
TEST(EventDriven, ViscoelasticEqualsReference)
{
  for (int dim = 2; dim <= 3; dim++) {
    const SystemSpec s = spec_of(60, dim, 0.2, 91 + dim);
    LawParams law = LawParams::walton(0.6, 0.4, 0.3);
    const double vref = 0.5;
    ASSERT_EQ(find_restitution("viscoelastic")->apply(law, &vref), nullptr);
    Reference ref = make_system(s, law);
    ref.periodic[1] = false;
    ref.walls.push_back({1, -1, ref.lo.y - 0.6, law});
    ref.walls.push_back({1, +1, ref.lo.y + ref.L.y + 0.6, law});
    const double mft = mean_free_time(ref);
    CoreRun run(ref);
    run.run(8 * mft, 0.7 * mft);
    ref.run_until(8 * mft);
    EXPECT_GT(ref.wall_collisions, 5);
    EXPECT_EQ(run.total.collisions, ref.collisions);
    EXPECT_EQ(run.total.wall_collisions, ref.wall_collisions);
    expect_same_state(ref, run, 1e-9);
  }
}

TEST(EventDriven, QueueKeptAcrossWindowsEqualsReference)
{
  // start / advance_to / rebase, the way fix hardsphere/ed runs (no re-prediction between
  // windows), against the brute-force reference
  for (int dim = 2; dim <= 3; dim++) {
    SystemSpec s;
    s.n = 150;
    s.dim = dim;
    s.phi = 0.25;
    s.seed = 91 + dim;
    Reference ref = make_system(s, LawParams::walton(0.85, 0.3, 0.5));
    ref.gravity = dim == 2 ? Vec3(0.2, -0.7, 0.0) : Vec3(0.1, -0.3, -0.6);
    ref.tc = 0.005;
    CoreRun run(ref);
    kept_queue_equals_reference(ref, run, 0.37 * mean_free_time(ref), 12);
  }
}

// a deterministic Gaussian-like kick of particle e at kick k (test only)
Vec3 test_kick(int e, int k, double s)
{
  std::mt19937_64 g(1000003ULL * (unsigned) e + 7919ULL * (unsigned) k + 17);
  std::normal_distribution<double> n(0.0, s);
  return Vec3(n(g), n(g), n(g));
}

// Changes from outside between windows with the queue kept (changed(), remove(): how domain
// windows refresh the copies of other ranks' atoms): velocities of a changing subset are
// altered at every window boundary, other particles are taken out and put back unchanged;
// the trajectory equals the brute-force reference with the same changes as instant events.
// (2D and 3D with cells under gravity; 3D with neighbour lists, which take no gravity and no
// nudges: the changed particles re-enter the lists around their new centres)
TEST(EventDriven, ChangesBetweenWindowsEqualReference)
{
  for (int config = 0; config < 3; config++) {
    const int dim = config == 0 ? 2 : 3;
    const bool lists = config == 2;
    const SystemSpec s = spec_of(140, dim, 0.25, 311 + dim);
    Reference ref = make_system(s, LawParams::walton(0.85, 0.3, 0.5));
    if (!lists) ref.gravity = dim == 2 ? Vec3(0.2, -0.7, 0.0) : Vec3(0.1, -0.3, -0.6);
    ref.tc = 0.005;
    const double mft = mean_free_time(ref);
    const double dt = 0.43 * mft;
    const int nwin = 12;
    auto dv = [dim](int e, int k) {
      Vec3 d = test_kick(e, k, 0.4);
      if (dim == 2) d.z = 0.0;
      return d;
    };
    auto kicked = [](int e, int w) { return (e + w) % 9 == 0; };
    for (int w = 1; w < nwin; w++) ref.kick_times.push_back(w * dt);
    ref.kick = [&](std::vector<RefParticle> &ps, int k) {
      for (size_t e = 0; e < ps.size(); e++)
        if (kicked((int) e, k + 1)) ps[e].v += dv((int) e, k + 1);
    };
    CoreRun run(ref, 1000000, lists ? EDOptions::LISTS : EDOptions::CELLS);
    EventDriven &ed = run.ed;
    ed.start();
    EXPECT_EQ(ed.uses_lists(), lists);
    long changed = 0;
    for (int w = 0; w < nwin; w++) {
      if (w > 0) {
        for (int e = 0; e < ed.size(); e++) {
          const bool k = kicked(e, w), out = (e + 2 * w) % 11 == 0;
          if (!k && !out) continue;
          auto p = ed.particle(e);
          const Vec3 x = ed.position(e, 0.0), v = ed.velocity(e, 0.0);
          if (out) ed.remove(e);
          EXPECT_EQ(ed.present(e), !out);
          const double xs[3] = {x.x, x.y, x.z}, vs[3] = {v.x, v.y, v.z}, ws[3] = {0, 0, 0};
          if (lists) EXPECT_FALSE(ed.nudge(e, xs, vs, ws)) << "lists take no nudges";
          p.x = x;
          p.v = k ? v + dv(e, w) : v;
          ed.changed(e);
          changed++;
        }
      }
      run.total.add(ed.advance_to(dt));
      ed.rebase(dt);
    }
    ref.run_until(nwin * dt);
    EXPECT_GT(changed, 200);
    EXPECT_EQ(run.total.collisions, ref.collisions);
    for (size_t i = 0; i < ref.p.size(); i++) {
      EXPECT_LT(norm(ed.position((int) i, 0.0) - ref.p[i].x), 1e-9);
      EXPECT_LT(norm(ed.velocity((int) i, 0.0) - ref.p[i].v), 1e-9);
      EXPECT_LT(ref.p[i].a * norm(ed.particle((int) i).w - ref.p[i].w), 1e-9);
    }
  }
}

// Empty slots: a system with slots left empty at start(), particles taken out for good and
// new ones put into empty slots between windows continues exactly as a fresh start() of the
// changed system would (the fresh core sees only the present particles); an empty slot has no
// events and is never a partner.
// nudge(): states re-rounded between windows (as a copy arrives from the rank that owns it,
// computed on another cell grid) replace the particles' own and their predictions stand; the
// trajectory stays the brute-force reference's. A nudge into another cell is refused and
// changes nothing; an empty slot is refused too.
TEST(EventDriven, NudgedStatesKeepTrajectory)
{
  for (int dim = 2; dim <= 3; dim++) {
    const SystemSpec s = spec_of(140, dim, 0.25, 521 + dim);
    Reference ref = make_system(s, LawParams::walton(0.85, 0.3, 0.5));
    ref.gravity = dim == 2 ? Vec3(0.2, -0.7, 0.0) : Vec3(0.1, -0.3, -0.6);
    const double dt = 0.6 * mean_free_time(ref);
    const int nwin = 10;
    CoreRun run(ref);
    EventDriven &ed = run.ed;
    ed.remove(s.n - 1);    // (an empty slot)
    ref.p.pop_back();
    {
      double x[3], v[3], om[3];
      ref.p[0].x.to(x);
      ref.p[0].v.to(v);
      ref.p[0].w.to(om);
      EXPECT_THROW(ed.nudge(0, x, v, om), std::logic_error);
    }
    ed.start();
    long nudged = 0, refused = 0;
    // a value off by a few units in its last place, as other rounding leaves it
    auto reround = [](double x, int k) { return x == 0.0 ? 0.0 : x * (1.0 + (k % 7 - 3) * 0x1p-52); };
    for (int w = 0; w < nwin; w++) {
      if (w > 0) {
        for (int e = 0; e < s.n - 1; e++) {
          if ((e + w) % 3 != 0) continue;
          double x[3], v[3], om[3];
          ed.state(e, 0.0, x, v, om);
          for (int d = 0; d < 3; d++) {
            x[d] = reround(x[d], e + d + w);
            v[d] = reround(v[d], 2 * e + d + w);
            om[d] = reround(om[d], 3 * e + d + w);
          }
          if (ed.nudge(e, x, v, om)) {
            nudged++;
            double x2[3], v2[3], w2[3];
            ed.state(e, 0.0, x2, v2, w2);
            for (int d = 0; d < dim; d++) {
              EXPECT_EQ(x2[d], x[d]);
              EXPECT_EQ(v2[d], v[d]);
            }
          } else {
            refused++;
          }
        }
        // a position in another cell: refused, nothing changes
        double x[3], v[3], om[3], x2[3], v2[3], w2[3];
        ed.state(w, 0.0, x, v, om);
        const double x0 = x[0];
        x[0] += 0.37 * ref.L[0];
        EXPECT_FALSE(ed.nudge(w, x, v, om));
        ed.state(w, 0.0, x2, v2, w2);
        EXPECT_EQ(x2[0], x0);
        EXPECT_FALSE(ed.nudge(s.n - 1, x, v, om));
        EXPECT_FALSE(ed.present(s.n - 1));
      }
      run.total.add(ed.advance_to(dt));
      ed.rebase(dt);
    }
    ref.run_until(nwin * dt);
    EXPECT_GT(nudged, 300);
    EXPECT_LT(refused, nudged / 10);    // (only particles within rounding of a cell border)
    EXPECT_EQ(run.total.collisions, ref.collisions);
    for (size_t i = 0; i < ref.p.size(); i++) {
      EXPECT_LT(norm(ed.position((int) i, 0.0) - ref.p[i].x), 1e-9);
      EXPECT_LT(norm(ed.velocity((int) i, 0.0) - ref.p[i].v), 1e-9);
      EXPECT_LT(ref.p[i].a * norm(ed.particle((int) i).w - ref.p[i].w), 1e-9);
    }
  }
}

TEST(EventDriven, EmptySlotsFilledAndEmptiedEqualFreshStart)
{
  for (int dim = 2; dim <= 3; dim++) {
    const SystemSpec s = spec_of(260, dim, 0.12, 733 + dim);
    Reference ref = make_system(s, LawParams::rough(0.9, 0.2));
    const double mft = mean_free_time(ref);
    const double dt = mft;
    // slots 0..239 are present from the start, 240..259 empty (their states wait in ref)
    CoreRun run(ref);
    EventDriven &ed = run.ed;
    const int n0 = 240;
    for (int e = n0; e < s.n; e++) ed.remove(e);
    ed.start();
    std::vector<char> present(s.n, 0);
    for (int e = 0; e < n0; e++) present[e] = 1;
    long overlaps_before = 0;
    for (int w = 0; w < 4; w++) {
      run.total.add(ed.advance_to(dt));
      ed.rebase(dt);
    }
    // take out every 7th present particle; fill empty slots at spots clear of everyone
    for (int e = 0; e < n0; e += 7) {
      ed.remove(e);
      present[e] = 0;
    }
    int filled = 0;
    for (int e = n0; e < s.n; e++) {
      auto p = ed.particle(e);
      const RefParticle &r = ref.p[e];
      bool clear = true;
      for (int j = 0; j < s.n && clear; j++) {
        if (!present[j]) continue;
        clear = norm(ref.min_image(ed.position(j, 0.0) - r.x)) > 1.05 * (r.a + ed.particle(j).a);
      }
      if (!clear) continue;
      p.x = r.x;
      p.v = r.v;
      p.w = r.w;
      ed.changed(e);
      present[e] = 1;
      filled++;
    }
    EXPECT_GT(filled, 5);
    // the fresh system: the present particles at this moment
    EventDriven fresh;
    fresh.configure(ed.options(), ref.ntypes, ref.laws);
    std::vector<int> which;
    for (int e = 0; e < s.n; e++)
      if (present[e]) which.push_back(e);
    fresh.resize((int) which.size());
    for (size_t k = 0; k < which.size(); k++) {
      auto p = fresh.particle((int) k);
      p = ed.particle(which[k]);
      p.x = ed.position(which[k], 0.0);
      p.v = ed.velocity(which[k], 0.0);
    }
    fresh.start();
    long ki, kj;
    double depth;
    overlaps_before = ed.overlaps(1e-9, ki, kj, depth);
    EXPECT_EQ(overlaps_before, fresh.overlaps(1e-9, ki, kj, depth));
    EDStats a, b;
    for (int w = 0; w < 6; w++) {
      a.add(ed.advance_to(dt));
      ed.rebase(dt);
      b.add(fresh.advance_to(dt));
      fresh.rebase(dt);
    }
    EXPECT_GT(a.collisions, 200);
    EXPECT_EQ(a.collisions, b.collisions);
    for (size_t k = 0; k < which.size(); k++) {
      const int e = which[k];
      EXPECT_LT(norm(ed.position(e, 0.0) - fresh.position((int) k, 0.0)), 1e-9);
      EXPECT_LT(norm(ed.velocity(e, 0.0) - fresh.velocity((int) k, 0.0)), 1e-9);
      EXPECT_LT(norm(ed.particle(e).w - fresh.particle((int) k).w), 1e-9);
    }
    for (int e = 0; e < s.n; e++) EXPECT_EQ(ed.present(e), (bool) present[e]);
  }
}

// two particles overlapping across a periodic boundary are found in boxes of any number of
// cells (with fewer than 3 cells a dimension's neighbour cells repeat at other image shifts),
// with cells and with neighbour lists
TEST(EventDriven, OverlapsAcrossPeriodicBoundaries)
{
  for (int neighbours : {EDOptions::CELLS, EDOptions::LISTS})
    for (int dim = 2; dim <= 3; dim++)
      for (double side : {3.0, 4.0, 10.0}) {
        EventDriven ed;
        EDOptions o;
        o.dim = dim;
        o.neighbours = neighbours;
        for (int d = 0; d < 3; d++) o.hi[d] = d < dim ? side : 1.0;
        ed.configure(o, 1, std::vector<LawParams>(4, LawParams::rough(1.0, -1.0)));
        ed.resize(2);
        auto a = ed.particle(0), b = ed.particle(1);
        a.x = Vec3(0.3, 0.5 * side, dim == 3 ? 0.5 * side : 0.5);
        b.x = Vec3(side - 0.3, 0.5 * side, dim == 3 ? 0.5 * side : 0.5);    // 0.6 apart across x = 0
        a.a = b.a = 0.5;
        ed.start();
        ASSERT_EQ(ed.uses_lists(), neighbours == EDOptions::LISTS);
        long ki, kj;
        double depth;
        EXPECT_EQ(ed.overlaps(1e-9, ki, kj, depth), 1) << dim << "D, box " << side;
        EXPECT_NEAR(depth, 0.4, 1e-12);
      }
}

// a dense gas placed at random (many pairs overlap, polydisperse): lists and cells find the same
// overlapping pairs, the same deepest one and depth
TEST(EventDriven, OverlapsSameWithListsAndCells)
{
  for (int dim = 2; dim <= 3; dim++) {
    long n[2], ki[2], kj[2];
    double depth[2];
    for (int l = 0; l < 2; l++) {
      EventDriven ed;
      EDOptions o;
      o.dim = dim;
      o.neighbours = l ? EDOptions::LISTS : EDOptions::CELLS;
      const double side = dim == 3 ? 7.0 : 14.0;
      for (int d = 0; d < 3; d++) o.hi[d] = d < dim ? side : 1.0;
      ed.configure(o, 1, std::vector<LawParams>(4, LawParams::rough(1.0, -1.0)));
      const int np = dim == 3 ? 300 : 220;
      ed.resize(np);
      std::mt19937_64 rng(77 + dim);
      std::uniform_real_distribution<double> u(0.0, 1.0);
      for (int i = 0; i < np; i++) {
        auto p = ed.particle(i);
        p.x = Vec3(side * u(rng), side * u(rng), dim == 3 ? side * u(rng) : 0.5);
        p.v = Vec3(u(rng) - 0.5, u(rng) - 0.5, dim == 3 ? u(rng) - 0.5 : 0.0);
        p.a = 0.4 + 0.1 * u(rng);
      }
      ed.start();
      ASSERT_EQ(ed.uses_lists(), l == 1);
      n[l] = ed.overlaps(1e-9, ki[l], kj[l], depth[l]);
    }
    EXPECT_GT(n[0], 10) << dim << "D";
    EXPECT_EQ(n[0], n[1]) << dim << "D";
    EXPECT_EQ(depth[0], depth[1]) << dim << "D";
    EXPECT_EQ(ki[0], ki[1]) << dim << "D";
    EXPECT_EQ(kj[0], kj[1]) << dim << "D";
  }
}

TEST(EventDriven, GlobalKicksEqualReference)
{
  for (int dim = 2; dim <= 3; dim++) {
    SystemSpec s;
    s.n = 120;
    s.dim = dim;
    s.phi = 0.25;
    s.seed = 57 + dim;
    Reference ref = make_system(s, LawParams::walton(0.8, 0.3, 0.4));
    const double mft = mean_free_time(ref);
    const double period = 0.23 * mft;
    auto dv = [dim](int e, int k) {
      Vec3 d = test_kick(e, k, 0.3);
      if (dim == 2) d.z = 0.0;
      return d;
    };
    for (int k = 1; k * period < 6 * mft; k++) ref.kick_times.push_back(k * period);
    ref.kick = [&](std::vector<RefParticle> &ps, int k) {
      for (size_t e = 0; e < ps.size(); e++) ps[e].v += dv((int) e, k);
    };
    CoreRun run(ref);
    run.ed.start();
    const double dt = 0.61 * mft;
    double t0 = 0.0, injected = 0.0;
    const int nwin = (int) std::floor(6 * mft / dt);
    for (int w = 0; w < nwin; w++) {
      window_kicks(run.ed, ref, t0, dt, dv);
      const EDStats st = run.ed.advance_to(dt);
      run.total.add(st);
      injected += st.injected;
      run.ed.rebase(dt);
      t0 += dt;
    }
    ref.run_until(nwin * dt);
    EXPECT_GT(run.total.global_events, 10);
    EXPECT_EQ(run.total.collisions, ref.collisions);
    double e0 = 0, e1 = 0;
    for (size_t i = 0; i < ref.p.size(); i++) {
      EXPECT_LT(norm(run.ed.position((int) i, 0.0) - ref.p[i].x), 1e-9);
      EXPECT_LT(norm(run.ed.velocity((int) i, 0.0) - ref.p[i].v), 1e-9);
      EXPECT_LT(ref.p[i].a * norm(run.ed.particle((int) i).w - ref.p[i].w), 1e-9);
    }
    // energy books: injected + collision energy changes = change of kinetic energy
    Reference start = make_system(s, LawParams::walton(0.8, 0.3, 0.4));
    for (const auto &p : start.p) e0 += 0.5 * p.m * (norm2(p.v) + p.q * p.a * p.a * norm2(p.w));
    for (const auto &p : ref.p) e1 += 0.5 * p.m * (norm2(p.v) + p.q * p.a * p.a * norm2(p.w));
    EXPECT_NEAR(injected + run.total.dE, e1 - e0, 1e-10 * e0);
  }
}

// The kick schedule follows the simulation time: a run that continues where windows of the last
// one left keeps its shift (whatever the rounding of the window ends), a time moved back or
// forward makes the next kick the first on the grid k / f_dr at or after it; the kick indices
// (the random numbers) go on without repeating
TEST(Kicks, ScheduleFollowsTheTime)
{
  for (double fdr : {5.0, 3.0, 0.7}) {
    Kicks law;
    law.fdr = fdr;
    long next = 0, shift = law.shift_at(0.0, 0, 0);
    EXPECT_EQ(shift, 0);
    const double dt = 0.31;    // (no kick at the end of the last window: no tie to round)
    double t0 = 0.0;
    std::vector<double> times;
    std::vector<long> index;
    for (int w = 0; w < 30; w++, t0 += dt) law.kicks_in(t0, t0 + dt, next, times, index, shift);
    const long done = next;
    EXPECT_EQ(done, (long) std::ceil(30 * dt * fdr - 1e-9)) << fdr;
    // continued: the end of the last window, summed or multiplied, keeps the shift
    EXPECT_EQ(law.shift_at(t0, done, 0), 0) << fdr;
    EXPECT_EQ(law.shift_at(30 * dt, done, 0), 0) << fdr;
    // a counter one kick off does not fit the time: the next kick is the first at or after it
    EXPECT_EQ(law.shift_at(t0, done + 1, 0), 1) << fdr;
    EXPECT_EQ(law.shift_at(t0, done - 1, 0), -1) << fdr;
    // moved back to 0: kick `done` comes at 0; forward to 500: at the first grid time >= 500
    EXPECT_EQ(law.shift_at(0.0, done, 0), done) << fdr;
    shift = law.shift_at(500.0, done, 0);
    EXPECT_LT((done - 1 - shift) / fdr, 500.0) << fdr;
    EXPECT_GE((done - shift) / fdr, 500.0) << fdr;
    times.clear();
    index.clear();
    next = done;
    law.kicks_in(500.0, 510.0, next, times, index, shift);
    ASSERT_EQ((long) times.size(), (long) std::ceil(510.0 * fdr) - (long) std::ceil(500.0 * fdr)) << fdr;
    EXPECT_EQ(index.front(), done) << fdr;
    EXPECT_NEAR(times.front(), std::ceil(500.0 * fdr) / fdr, 1e-9) << fdr;
  }
}

// A gas of 80 particles under law `law` between a floor and a lid (y), each half a diameter
// beyond the particles' range, periodic in x (and z); walls with the laws lo_law and hi_law
Reference walled_system(int law, int dim, unsigned seed, int lo_law, int hi_law)
{
  SystemSpec s;
  s.n = 80;
  s.dim = dim;
  s.phi = 0.2;
  s.seed = seed;
  Reference ref = make_system(s, law_of(law));
  ref.periodic[1] = false;
  ref.walls.push_back({1, -1, ref.lo.y - 0.6, law_of(lo_law)});
  ref.walls.push_back({1, +1, ref.lo.y + ref.L.y + 0.6, law_of(hi_law)});
  return ref;
}

// nwin windows of length dt (after each, check() if given), then the reference to the same
// time: the same collisions, the same states to 1e-9 and the same virial
void windows_equal_reference(Reference &ref, CoreRun &run, double dt, int nwin,
                             const std::function<void()> &check = nullptr)
{
  for (int w = 0; w < nwin; w++) {
    run.total.add(run.ed.advance_to(dt));
    run.ed.rebase(dt);
    if (check) check();
  }
  ref.run_until(nwin * dt);
  EXPECT_GT(run.total.wall_collisions, 10);
  EXPECT_EQ(run.total.wall_collisions, ref.wall_collisions);
  EXPECT_EQ(run.total.collisions, ref.collisions);
  expect_same_virial(ref, run.total);
  for (size_t i = 0; i < ref.p.size(); i++) {
    EXPECT_LT(norm(run.ed.position((int) i, 0.0) - ref.p[i].x), 1e-9);
    EXPECT_LT(norm(run.ed.velocity((int) i, 0.0) - ref.p[i].v), 1e-9);
  }
}

// the particles' momentum and kinetic energy (translation and rotation) at window time 0
void momentum_and_energy(const EventDriven &ed, Vec3 &p, double &e)
{
  p = Vec3();
  e = 0.0;
  for (int i = 0; i < ed.size(); i++) {
    const auto q = ed.particle(i);
    const Vec3 v = ed.velocity(i, 0.0);
    p += q.m * v;
    e += 0.5 * q.m * norm2(v) + 0.5 * q.q * q.m * q.a * q.a * norm2(q.w);
  }
}

// a box with walls below and above (y), periodic in x (and z), under gravity toward the floor;
// every law, 2D and 3D, against the reference; nobody crosses a wall
TEST(EventDriven, WallsEqualReferenceAndHold)
{
  for (int law = 0; law < 3; law++)
    for (int dim = 2; dim <= 3; dim++) {
      Reference ref = walled_system(law, dim, 31 + law * 2 + dim, (law + 1) % 3, law);
      ref.gravity = dim == 2 ? Vec3(0.1, -0.4, 0.0) : Vec3(0.0, -0.4, 0.1);
      const double mft = mean_free_time(ref);
      CoreRun run(ref);
      run.ed.start();
      // ~5 collisions per particle: longer horizons lose 1e-9 to chaos, not to errors
      windows_equal_reference(ref, run, 0.55 * mft, 9, [&]() {
        for (int i = 0; i < run.ed.size(); i++) {
          const double y = run.ed.position(i, 0.0).y, a = run.ed.particle(i).a;
          ASSERT_GE(y - a, ref.walls[0].pos - 1e-9) << "through the floor";
          ASSERT_LE(y + a, ref.walls[1].pos + 1e-9) << "through the ceiling";
        }
      });
      EXPECT_LT(run.total.collisions, 8 * 80);
    }
}

// Walls sliding within their planes in opposite directions (a Couette cell) under each law:
// event by event equal to the reference, and the momentum books close: what the particles
// gained along the walls is what the walls lost (the walls' impulses), and the energy the
// walls gave is the gas's kinetic energy change less the pair collisions' dissipation
TEST(EventDriven, SlidingWallsEqualReferenceAndBalance)
{
  for (int law = 0; law < 3; law++)
    for (int dim = 2; dim <= 3; dim++) {
      Reference ref = walled_system(law, dim, 41 + law * 2 + dim, law, law);
      ref.walls[0].slide = dim == 2 ? Vec3(-0.7, 0.0, 0.0) : Vec3(-0.7, 0.0, 0.3);
      ref.walls[1].slide = Vec3(0.7, 0.0, 0.0);
      const double mft = mean_free_time(ref);
      CoreRun run(ref);
      run.ed.start();
      Vec3 p0, p1;
      double e0, e1;
      momentum_and_energy(run.ed, p0, e0);
      windows_equal_reference(ref, run, 0.55 * mft, 9);
      momentum_and_energy(run.ed, p1, e1);
      // (no gravity: the particles' momentum changes by the walls' impulses only)
      const std::vector<double> &J = run.total.wall_impulse;
      for (int d = 0; d < 3; d++) EXPECT_NEAR(p1[d] - p0[d], -(J[d] + J[3 + d]), 1e-9) << "momentum " << d;
      EXPECT_NE(J[0], 0.0);    // (the walls drag the gas along x)
      const double work = run.total.wall_work[0] + run.total.wall_work[1];
      EXPECT_NEAR(e1 - e0, work + run.total.dE, 1e-9 * (1.0 + e0));
      EXPECT_NEAR(run.total.dE_wall, work, 1e-9 * (1.0 + e0));
    }
}

// A floor shaken within its plane (along x, and along z in 3d) and a lid shaken along x at
// another frequency, under gravity: equal to the reference (whose surface velocity is written
// apart), and the energy the walls give is the gas's energy change (kinetic and potential)
// less the pair collisions' dissipation
TEST(EventDriven, ShakenFloorEqualsReference)
{
  for (int law = 0; law < 3; law++)
    for (int dim = 2; dim <= 3; dim++) {
      Reference ref = walled_system(law, dim, 53 + law * 2 + dim, law, law);
      ref.gravity = Vec3(0.0, -0.5, 0.0);
      ref.walls[0].shake_dim = dim == 2 ? 0 : 2;
      ref.walls[0].shake_A = 0.2;
      ref.walls[0].shake_omega = 3.0;
      ref.walls[1].shake_dim = 0;
      ref.walls[1].shake_A = 0.1;
      ref.walls[1].shake_omega = 7.0;
      const double mft = mean_free_time(ref);
      CoreRun run(ref);
      run.ed.start();
      Vec3 p0, p1;
      double e0, e1;
      momentum_and_energy(run.ed, p0, e0);
      double u0 = 0.0, u1 = 0.0;
      for (int i = 0; i < run.ed.size(); i++) u0 += 0.5 * run.ed.particle(i).m * run.ed.position(i, 0.0).y;
      windows_equal_reference(ref, run, 0.55 * mft, 9);
      momentum_and_energy(run.ed, p1, e1);
      for (int i = 0; i < run.ed.size(); i++) u1 += 0.5 * run.ed.particle(i).m * run.ed.position(i, 0.0).y;
      const double work = run.total.wall_work[0] + run.total.wall_work[1];
      EXPECT_NEAR(e1 + u1 - e0 - u0, work + run.total.dE, 1e-9 * (1.0 + e0));
      EXPECT_GT(std::fabs(run.total.wall_impulse[ref.walls[0].shake_dim]), 0.0);
    }
}

// Two thermal walls at one temperature sliding at the same velocity carry an elastic gas
// along: it takes their velocity as its mean and their temperature about it
TEST(EventDriven, SlidingThermalWallsCarryTheGas)
{
  for (int dim = 2; dim <= 3; dim++) {
    SystemSpec s;
    s.n = dim == 2 ? 300 : 400;
    s.dim = dim;
    s.phi = 0.1;
    s.seed = 7 + dim;
    Reference ref = make_system(s, LawParams::rough(1.0, -1.0));
    ref.periodic[1] = false;
    ref.walls.push_back({1, -1, ref.lo.y - 0.6, LawParams::rough(1.0, -1.0)});
    ref.walls.push_back({1, +1, ref.lo.y + ref.L.y + 0.6, LawParams::rough(1.0, -1.0)});
    CoreRun run(ref);
    EDOptions o = run.ed.options();
    const Vec3 u(1.5, 0.0, dim == 2 ? 0.0 : -0.5);
    for (int k = 0; k < 2; k++) {
      o.walls[k].T = 1.0;
      o.walls[k].seed = 17 + k;
      o.walls[k].slide = u;
    }
    run.ed.configure(o, ref.ntypes, ref.laws);
    run.ed.start();
    Vec3 mean;
    double temp = 0.0;
    int nsample = 0;
    // (the gas starts at rest: it heats up as the walls accelerate it, and the walls take the
    // heat back over some hundred windows; sampled after 1000, as ThermalWallEquilibratesTheGas)
    for (int w = 0; w < 2000; w++) {
      run.total.add(run.ed.advance_to(1.0));
      run.ed.rebase(1.0);
      if (w < 1000) continue;
      // (the particles' masses differ: the mean velocity is the momentum per mass)
      Vec3 m;
      double mass = 0.0;
      for (int i = 0; i < run.ed.size(); i++) {
        m += run.ed.particle(i).m * run.ed.velocity(i, 0.0);
        mass += run.ed.particle(i).m;
      }
      m = (1.0 / mass) * m;
      double t = 0.0;
      for (int i = 0; i < run.ed.size(); i++)
        t += run.ed.particle(i).m * norm2(run.ed.velocity(i, 0.0) - m) / (dim * s.n);
      mean += m;
      temp += t;
      nsample++;
    }
    mean = (1.0 / nsample) * mean;
    EXPECT_GT(run.total.wall_collisions, 1000);
    EXPECT_NEAR(mean.x, u.x, 0.05) << dim << "D";
    EXPECT_NEAR(mean.z, u.z, 0.05) << dim << "D";
    EXPECT_NEAR(temp / nsample, 1.0, 0.05) << dim << "D";
  }
}

// a sliding velocity with a component along the wall's normal, or along z in 2d: refused
TEST(EventDriven, SlidingOutOfThePlaneRefused)
{
  SystemSpec s;
  s.n = 20;
  s.dim = 2;
  s.phi = 0.2;
  Reference ref = make_system(s, LawParams::rough(0.9, 0.0));
  ref.periodic[1] = false;
  ref.walls.push_back({1, -1, ref.lo.y - 0.6, LawParams::rough(0.9, 0.0)});
  CoreRun run(ref);
  EDOptions o = run.ed.options();
  o.walls[0].slide = Vec3(0.0, 1.0, 0.0);
  EXPECT_THROW(run.ed.configure(o, ref.ntypes, ref.laws), std::invalid_argument);
  o.walls[0].slide = Vec3(1.0, 0.0, 1.0);
  EXPECT_THROW(run.ed.configure(o, ref.ntypes, ref.laws), std::invalid_argument);
  o.walls[0].slide = Vec3(1.0, 0.0, 0.0);
  EXPECT_NO_THROW(run.ed.configure(o, ref.ntypes, ref.laws));
}

// a bed on a vibrating base (piecewise-parabolic motion) under gravity: event by event equal to
// the reference (which finds wall contacts by brute-force marching and bisection), the base
// injects energy, nobody goes through it
TEST(EventDriven, VibratingBaseEqualsReference)
{
  for (int motion = 0; motion < 2; motion++)
  for (int dim = 2; dim <= 3; dim++) {
    SystemSpec s;
    s.n = 60;
    s.dim = dim;
    s.phi = 0.15;
    s.seed = 13 + dim;
    Reference ref = make_system(s, LawParams::walton(0.9, 0.3, 0.4));
    ref.periodic[1] = false;
    ref.gravity = dim == 2 ? Vec3(0.0, -1.0, 0.0) : Vec3(0.0, -1.0, 0.0);
    RefWall base{1, -1, ref.lo.y - 0.8, LawParams::walton(0.8, 0.5, 0.2), 0.3, 6.0, motion == 1};
    ref.tc = 1e-3;    // a grain carried up by the accelerating base collides ever faster (collapse)
    ref.walls.push_back(base);
    ref.walls.push_back({1, +1, ref.lo.y + ref.L.y + 0.8, law_of(0)});
    CoreRun run(ref);
    run.ed.start();
    const double dt = 0.13;
    const int nwin = 15;
    for (int w = 0; w < nwin; w++) {
      run.total.add(run.ed.advance_to(dt));
      run.ed.rebase(dt);
      for (int i = 0; i < run.ed.size(); i++) {
        const double y = run.ed.position(i, 0.0).y, a = run.ed.particle(i).a;
        ASSERT_GE(y - a, base.height(run.ed.get_clock()) - 1e-9) << "through the vibrating base";
      }
    }
    ref.run_until(nwin * dt);
    EXPECT_GT(run.total.wall_collisions, 8);    // the base is hit (11-14 times measured)
    EXPECT_EQ(run.total.wall_collisions, ref.wall_collisions);
    EXPECT_EQ(run.total.collisions, ref.collisions);
    for (size_t i = 0; i < ref.p.size(); i++) {
      EXPECT_LT(norm(run.ed.position((int) i, 0.0) - ref.p[i].x), 1e-9);
      EXPECT_LT(norm(run.ed.velocity((int) i, 0.0) - ref.p[i].v), 1e-9);
    }
  }
}

// Walls vibrate on every face: a bed that gravity holds against a vibrating upper wall (yhi, the
// scene above upside down), and a gas in a box shaken as a whole (lower and upper walls of y, and
// of x in a box closed in x too, moving together), piecewise parabolic and sinusoidal, 2d and 3d:
// event by event equal to the reference, nobody goes through a wall
TEST(EventDriven, VibratingUpperAndSideWallsEqualReference)
{
  for (int scene = 0; scene < 2; scene++)
    for (int motion = 0; motion < 2; motion++)
      for (int dim = 2; dim <= 3; dim++) {
        SCOPED_TRACE(std::string(scene == 0 ? "upside-down bed" : "shaken box") + (motion ? ", sine, " : ", parabolic, ") +
                     std::to_string(dim) + "D");
        SystemSpec s;
        s.n = 60;
        s.dim = dim;
        s.phi = 0.15;
        s.seed = 41 + dim + 2 * motion;
        Reference ref = make_system(s, LawParams::walton(0.9, 0.3, 0.4));
        ref.periodic[1] = false;
        const bool sine = motion == 1;
        const LawParams wl = LawParams::walton(0.8, 0.5, 0.2);
        const double ylo = ref.lo.y - 0.8, yhi = ref.lo.y + ref.L.y + 0.8;
        if (scene == 0) {
          ref.gravity = Vec3(0.0, 1.0, 0.0);
          ref.tc = 1e-3;
          ref.walls.push_back({1, -1, ylo, law_of(0)});
          ref.walls.push_back({1, +1, yhi, wl, 0.3, 6.0, sine});
        } else {
          ref.periodic[0] = false;
          ref.walls.push_back({1, -1, ylo, wl, 0.3, 6.0, sine});
          ref.walls.push_back({1, +1, yhi, wl, 0.3, 6.0, sine});
          ref.walls.push_back({0, -1, ref.lo.x - 0.8, wl, 0.2, 9.0, sine});
          ref.walls.push_back({0, +1, ref.lo.x + ref.L.x + 0.8, wl, 0.2, 9.0, sine});
        }
        const Reference start = ref;
        CoreRun run(ref);
        run.ed.start();
        const double dt = 0.13;
        const int nwin = 15;
        for (int w = 0; w < nwin; w++) {
          run.total.add(run.ed.advance_to(dt));
          run.ed.rebase(dt);
          for (const RefWall &wall : ref.walls)
            for (int i = 0; i < run.ed.size(); i++) {
              const double x = run.ed.position(i, 0.0)[wall.dim], a = run.ed.particle(i).a;
              const double gap = wall.side < 0 ? x - a - wall.height(run.ed.get_clock())
                                               : wall.height(run.ed.get_clock()) - x - a;
              ASSERT_GE(gap, -1e-9) << "through wall " << wall.dim << " " << wall.side;
            }
        }
        ref.run_until(nwin * dt);
        EXPECT_GT(run.total.wall_collisions, 5);
        EXPECT_EQ(run.total.wall_collisions, ref.wall_collisions);
        EXPECT_EQ(run.total.collisions, ref.collisions);
        double dev = 0.0;
        for (size_t i = 0; i < ref.p.size(); i++)
          dev = std::max({dev, norm(run.ed.position((int) i, 0.0) - ref.p[i].x),
                          norm(run.ed.velocity((int) i, 0.0) - ref.p[i].v)});
        if (dev < 1e-9) continue;
        // A grain the wall carries chatters on it at relative speeds near 0 (upside-down bed,
        // parabolic, 2d: 74 contacts within a window, |g_n| down to 0.003), where contact times
        // depend on the last bits: the reference run again from velocities one rounding away
        // measures how far the trajectory itself is determined (7e-10 there)
        Reference nudged = start;
        for (RefParticle &p : nudged.p) p.v.y = std::nextafter(p.v.y, 1e300);
        nudged.run_until(nwin * dt);
        double spread = 0.0;
        for (size_t i = 0; i < ref.p.size(); i++)
          spread = std::max({spread, norm(nudged.p[i].x - ref.p[i].x), norm(nudged.p[i].v - ref.p[i].v)});
        EXPECT_LT(dev, 100.0 * spread);
      }
}

// A grain leaves a base that vibrates very fast (omega = 1e7, amplitude 1e-6) faster than the
// base can follow and comes back after a flight of about 200 time units, 6e8 half periods: its
// contact is found where it comes down to the band of the base's motion, as a brute-force march
// over the last periods finds it. The flight above the band is skipped, not walked through half
// period by half period (piecewise parabolic and sinusoidal motion).
TEST(EventDriven, FastVibratingBaseAfterALongFlight)
{
  for (bool sine : {false, true}) {
    Reference ref;
    ref.dim = 2;
    ref.lo = Vec3(0.0, 0.0, -0.5);
    ref.L = Vec3(10.0, 10000.0, 1.0);
    ref.periodic[1] = false;
    ref.gravity = Vec3(0.0, -1.0, 0.0);
    ref.laws.assign(4, LawParams::rough(0.8, -1.0));
    RefWall base{1, -1, 1.0, LawParams::rough(0.8, -1.0), 1e-6, 1e7, sine};
    ref.walls.push_back(base);
    ref.walls.push_back({1, +1, 9999.0, LawParams::rough(0.8, -1.0)});
    RefParticle g;
    g.x = Vec3(5.0, base.pos + 0.9e-6 + 0.5, 0.0);    // inside the band of the base's motion
    g.v = Vec3(0.0, 100.0, 0.0);                       // faster than the base (12.7 at most)
    g.q = 0.5;
    ref.p.push_back(g);
    // the brute-force contact: the grain comes down to the band's top at t_top; march from
    // two periods before it in steps of 1/20000 period, then bisect
    const double top = base.pos + base.A + g.a;
    const double t_top = crossing_time(g.x.y, g.v.y, -1.0, top, -1);
    auto gap = [&](double t) { return g.x.y + g.v.y * t - 0.5 * t * t - g.a - base.height(t); };
    const double h = 2.0 * M_PI / base.omega / 20000.0;
    double t0 = t_top - 40000.0 * h, tc = -1.0;
    for (double f0 = gap(t0); tc < 0.0 && t0 < t_top + 1.0; t0 += h) {
      const double f1 = gap(t0 + h);
      if (f0 > 0.0 && f1 <= 0.0) {
        double lo = t0, hi = t0 + h;
        for (int it = 0; it < 200; it++) (gap(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
        tc = hi;
      }
      f0 = f1;
    }
    ASSERT_GT(tc, 199.0) << sine;
    CoreRun early(ref), late(ref);
    early.ed.start();
    late.ed.start();
    EXPECT_EQ(early.ed.advance_to(tc - 1e-7).wall_collisions, 0) << sine;
    EXPECT_EQ(late.ed.advance_to(tc + 1e-7).wall_collisions, 1) << sine;
    EXPECT_GT(late.ed.velocity(0, tc + 1e-7).y, 0.0) << sine;    // thrown up again
  }
}

// The cell width changes only which candidates are tested: the trajectory is the brute-force
// reference's for the automatic width (wider than the contact distance in a dilute 2d gas) and
// for any requested width, down to a single cell across the box (periodic images at two shifts).
TEST(EventDriven, CellWidthLeavesTheTrajectory)
{
  for (int dim = 2; dim <= 3; dim++)
    for (double w : {0.0, 1.0, 2.5, 6.0, 20.0}) {    // diameters; 0: the automatic width
      SystemSpec s;
      s.n = 200;
      s.dim = dim;
      s.phi = dim == 2 ? 0.05 : 0.1;
      s.q = dim == 2 ? 0.5 : 0.4;
      s.seed = 31 + dim;
      Reference ref = make_system(s, law_of(1));
      // (two mean free times in 2d: in so dilute a gas chaos lifts rounding differences above
      // 1e-9 soon after, as in the trajectory cases above; three in 3d, for N collisions)
      const double mft = mean_free_time(ref), T = (dim == 2 ? 2.0 : 3.0) * mft;
      CoreRun run(ref);
      EDOptions o = run.ed.options();
      o.cell_width = w;
      run.ed.configure(o, ref.ntypes, ref.laws);
      run.run(T, 0.5 * mft);
      ref.run_until(T);
      SCOPED_TRACE(std::to_string(dim) + "D, requested width " + std::to_string(w) + ", cells " +
                   std::to_string(run.ed.cell_size()) + " wide");
      double amax = 0.0;    // (polydisperse: sigma is the largest contact distance)
      for (const RefParticle &p : ref.p) amax = std::max(amax, p.a);
      const double want = w > 0.0 ? w : EventDriven::auto_cell_width(dim, 2.0 * amax, s.n / ref.L.x / ref.L.y);
      EXPECT_GE(run.ed.cell_size(), std::min(want, ref.L.x) * (1.0 - 1e-12));
      ASSERT_GE(ref.collisions, s.n);
      EXPECT_EQ(run.total.collisions, ref.collisions);
      expect_same_state(ref, run, 1e-9);
    }
}

// The automatic width: the contact distance from area fraction 0.3 up and in 3d, wider below
// (bench/cell_width.sh measured the optimum; doc/fix_hardsphere_ed.rst states the rule)
TEST(EventDriven, AutomaticCellWidth)
{
  auto n2 = [](double phi) { return phi / (M_PI / 4.0); };    // unit diameter
  EXPECT_EQ(EventDriven::auto_cell_width(2, 1.0, n2(0.3)), 1.0);
  EXPECT_EQ(EventDriven::auto_cell_width(2, 1.0, n2(0.6)), 1.0);
  EXPECT_NEAR(EventDriven::auto_cell_width(2, 1.0, n2(0.2)), 1.30, 0.01);
  EXPECT_NEAR(EventDriven::auto_cell_width(2, 1.0, n2(0.1)), 2.06, 0.01);
  EXPECT_NEAR(EventDriven::auto_cell_width(2, 1.0, n2(0.05)), 3.26, 0.01);
  EXPECT_NEAR(EventDriven::auto_cell_width(2, 2.0, n2(0.05) / 4.0), 6.52, 0.02);    // scales with sigma
  EXPECT_EQ(EventDriven::auto_cell_width(3, 1.0, 0.0955), 1.0);
  EXPECT_EQ(EventDriven::auto_cell_width(2, 1.0, 0.0), 1.0);    // (no particles)
}

// a thermal wall brings an elastic rough gas to its temperature, translational and rotational
// (detailed balance of the flux Maxwellian); the opposite wall is elastic
TEST(EventDriven, ThermalWallEquilibratesTheGas)
{
  for (int dim = 2; dim <= 3; dim++) {
    SystemSpec s;
    s.n = dim == 2 ? 300 : 400;
    s.dim = dim;
    s.phi = 0.1;
    s.seed = 5 + dim;
    s.q = dim == 2 ? 0.5 : 0.4;
    Reference ref = make_system(s, LawParams::rough(1.0, 1.0));
    ref.periodic[1] = false;
    ref.walls.push_back({1, -1, ref.lo.y - 0.6, LawParams::rough(1.0, 1.0)});
    ref.walls.push_back({1, +1, ref.lo.y + ref.L.y + 0.6, LawParams::rough(1.0, -1.0)});
    CoreRun run(ref);
    EDOptions o = run.ed.options();
    o.walls[0].T = 2.0;
    o.walls[0].seed = 99;
    run.ed.configure(o, ref.ntypes, ref.laws);
    run.ed.start();
    const double Tw = 2.0;
    double sum_tr = 0, sum_rot = 0;
    int nsample = 0;
    // The gas starts at T = 1 and takes the wall's temperature through one wall only, with a
    // relaxation time of about 120 windows in 2D: after 200 windows it still lacked ~4 % (mean
    // of 32 runs 0.96, as an exponential approach with that time gives), so it is sampled after
    // 1000 (then, over 12 seeds, 0.997 with a spread of 2 % in 2D, 0.995 and 0.5 % in 3D).
    for (int w = 0; w < 2000; w++) {
      run.total.add(run.ed.advance_to(1.0));
      run.ed.rebase(1.0);
      if (w < 1000) continue;
      double etr = 0, erot = 0;
      for (int i = 0; i < run.ed.size(); i++) {
        const auto p = run.ed.particle(i);
        const Vec3 v = run.ed.velocity(i, 0.0);
        etr += 0.5 * p.m * norm2(v);
        erot += 0.5 * p.q * p.m * p.a * p.a * norm2(p.w);
      }
      const int drot = dim == 2 ? 1 : 3;
      sum_tr += 2.0 * etr / (dim * s.n);
      sum_rot += 2.0 * erot / (drot * s.n);
      nsample++;
    }
    EXPECT_GT(run.total.wall_collisions, 1000);
    EXPECT_NEAR(sum_tr / nsample / Tw, 1.0, 0.05) << "T_tr in " << dim << "D";
    EXPECT_NEAR(sum_rot / nsample / Tw, 1.0, 0.05) << "T_rot in " << dim << "D";
  }
}

TEST(EventDriven, ElasticSmoothGasConservesEnergy)
{
  SystemSpec s;
  s.n = 1000;
  s.dim = 2;
  s.phi = 0.3;
  s.polydisperse = true;
  Reference ref = make_system(s, LawParams::rough(1.0, -1.0));
  auto energy = [](const EventDriven &ed) {
    double e = 0;
    for (int i = 0; i < ed.size(); i++) {
      const auto p = ed.particle(i);
      e += 0.5 * p.m * norm2(p.v) + 0.5 * p.q * p.m * p.a * p.a * norm2(p.w);
    }
    return e;
  };
  CoreRun run(ref);
  const double e0 = energy(run.ed);
  while (run.total.collisions < 1000000) run.window(5.0);
  EXPECT_NEAR(energy(run.ed), e0, 1e-10 * e0);
  EXPECT_EQ(run.total.dE, 0.0);
}

TEST(EventDriven, MomentumConservedNoOverlapNoLoss)
{
  for (int law = 0; law < 3; law++)
    for (int dim = 2; dim <= 3; dim++) {
      SystemSpec s;
      s.n = 400;
      s.dim = dim;
      s.phi = dim == 2 ? 0.5 : 0.35;
      s.lattice = true;
      s.polydisperse = false;
      s.seed = 5 + law;
      Reference ref = make_system(s, law_of(law));
      CoreRun run(ref);
      auto momentum = [&]() {
        Vec3 P;
        for (int i = 0; i < run.ed.size(); i++) P += run.ed.particle(i).m * run.ed.particle(i).v;
        return P;
      };
      const Vec3 P0 = momentum();
      for (int w = 0; w < 20; w++) {
        run.window(0.2);
        // no overlap (minimum image, all pairs) and no particle lost (all finite)
        const EventDriven &ed = run.ed;
        double worst = 0;
        for (int i = 0; i < ed.size(); i++) {
          const auto pi = ed.particle(i);
          ASSERT_TRUE(std::isfinite(pi.x.x + pi.x.y + pi.x.z));
          for (int j = i + 1; j < ed.size(); j++) {
            const auto pj = ed.particle(j);
            const double d = norm(ref.min_image(pi.x - pj.x));
            worst = std::max(worst, (pi.a + pj.a - d) / (pi.a + pj.a));
          }
        }
        EXPECT_LT(worst, 1e-12) << "overlap";
      }
      EXPECT_GT(run.total.collisions, 1000);
      const Vec3 P = momentum();
      EXPECT_LT(norm(P - P0), 1e-11 * s.n) << "law " << law << " dim " << dim;
    }
}

// a dense, strongly inelastic system: r = 0.5 at area fraction 0.6, N = 2500, no net momentum.
// Without the TC model it collapses within ~20 time units (measured: at N = 400 the same
// system only cools; collapse needs long enough chains, and N = 2500 has them).
Reference collapsing_system()
{
  SystemSpec s;
  s.n = 2500;
  s.dim = 2;
  s.phi = 0.6;
  s.lattice = true;
  s.polydisperse = false;
  s.q = 0.5;
  s.seed = 3;
  Reference ref = make_system(s, LawParams::rough(0.5, -1.0));
  Vec3 P;
  for (const auto &p : ref.p) P += p.v;
  for (auto &p : ref.p) p.v -= (1.0 / ref.p.size()) * P;
  return ref;
}

TEST(EventDriven, CollapseStopsAtEventCapWithoutTC)
{
  Reference ref = collapsing_system();
  CoreRun run(ref, 100000);
  const auto start = std::chrono::steady_clock::now();
  bool thrown = false;
  try {
    for (int w = 0; w < 100; w++) run.window(1.0);
  } catch (const EventCapError &e) {
    thrown = true;
    EXPECT_GT(e.n, 100000);
    EXPECT_NE(e.i, e.j);
    EXPECT_NE(std::string(e.what()).find("inelastic collapse"), std::string::npos);
  }
  EXPECT_TRUE(thrown) << "r = 0.5 at area fraction 0.6 must collapse without tc";
  const double secs =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(secs, 120.0) << "the cap must stop a collapse in bounded time";
}

// A particle far faster than the system's scale crosses cells without end: the cap on cell
// crossings (max_crossings times the particles, an option of its own: every collision is
// allowed here) stops the window at the first crossing beyond and names it and its speed
TEST(EventDriven, CrossingCapStopsAFastParticle)
{
  SystemSpec s;
  s.n = 8;
  s.dim = 2;
  s.phi = 0.01;
  Reference ref = make_system(s, LawParams::rough(1.0, -1.0));
  CoreRun run(ref);
  EDOptions o = run.ed.options();
  ASSERT_EQ(o.max_collisions, 1000000);
  o.max_crossings = 10;
  run.ed.configure(o, ref.ntypes, ref.laws);
  run.ed.particle(3).v = Vec3(1e8, 3e7, 0.0);
  run.ed.start();
  bool thrown = false;
  try {
    run.window(1.0);
  } catch (const EventCapError &e) {
    thrown = true;
    EXPECT_EQ(e.kind, EventCapError::CROSSINGS);
    EXPECT_EQ(e.n, 10 * 8 + 1);
    // (the fast particle, or one it struck)
    EXPECT_GT(e.speed, 1e7);
    EXPECT_GT(norm(run.ed.velocity(e.i, e.t)), 1e7);
  }
  EXPECT_TRUE(thrown);
}

TEST(EventDriven, TCModelPreventsCollapse)
{
  Reference ref = collapsing_system();
  ref.tc = 1e-4;
  CoreRun run(ref, 100000);
  double e0 = 0;
  for (int i = 0; i < run.ed.size(); i++) e0 += 0.5 * run.ed.particle(i).m * norm2(run.ed.particle(i).v);
  EXPECT_NO_THROW(for (int w = 0; w < 100; w++) run.window(1.0));
  EXPECT_GT(run.total.tc_elastic, 0);
  EXPECT_LT(-run.total.dE, e0 * 1.5);
  EXPECT_LT(run.total.max_collisions_one_particle, 100000);
}

TEST(EventDriven, TCModelEqualsReference)
{
  Reference ref = collapsing_system();
  ref.p.resize(400);
  ref.L = Vec3(ref.L.x * 0.4, ref.L.y * 0.4, 1.0);
  for (auto &p : ref.p) p.x = ref.lo + Vec3(std::fmod(p.x.x - ref.lo.x, ref.L.x), std::fmod(p.x.y - ref.lo.y, ref.L.y), 0.0);
  // drop overlapping particles created by folding the lattice
  std::vector<RefParticle> keep;
  for (auto &p : ref.p) {
    bool ok = true;
    for (auto &q : keep) ok = ok && norm(ref.min_image(p.x - q.x)) > p.a + q.a;
    if (ok) keep.push_back(p);
  }
  ref.p = keep;
  ref.tc = 0.02;
  CoreRun run(ref);
  run.run(3.0, 0.37);
  ref.run_until(3.0);
  EXPECT_GT(run.total.tc_elastic, 0);
  EXPECT_EQ(run.total.collisions, ref.collisions);
  expect_same_state(ref, run, 1e-9);
}

// The last collision times (kept only with the TC model) follow every particle through the
// core's renumbering in cell order and through the time shifts between windows: each equals the
// time of the particle's last collision in the recorded histories. Without tc they read -inf.
TEST(EventDriven, LastCollisionTimesFollowReorderAndRebase)
{
  for (double tc : {1e-6, 0.0}) {
    Reference ref = make_system(spec_of(300, 2, 0.3, 17), LawParams::rough(0.9, 0.2));
    ref.tc = tc;
    const double dt = 0.5 * mean_free_time(ref);
    CoreRun run(ref);
    run.ed.start();
    std::vector<EDEvent> h;
    run.ed.record_events(&h);
    std::vector<double> last(ref.p.size(), -INF);    // absolute times
    const int nwin = 200;
    for (int w = 0; w < nwin; w++) {
      h.clear();
      run.total.add(run.ed.advance_to(dt));
      for (const EDEvent &e : h) {
        last[e.i] = w * dt + e.t;
        if (e.j >= 0) last[e.j] = w * dt + e.t;
      }
      run.ed.rebase(dt);
    }
    // the core renumbers its particles after 4 N cell crossings: several times here
    ASSERT_GT(run.total.crossings, 16L * (long) ref.p.size());
    long collided = 0;
    for (int e = 0; e < run.ed.size(); e++) {
      const double tl = run.ed.particle(e).t_last;
      if (tc == 0.0) {
        EXPECT_EQ(tl, -INF) << "no last collision times without the TC model";
        continue;
      }
      if (last[e] == -INF) {
        EXPECT_EQ(tl, -INF);
        continue;
      }
      collided++;
      EXPECT_NEAR(tl + nwin * dt, last[e], 1e-9) << "particle " << e;
    }
    if (tc > 0.0) EXPECT_GT(collided, 290);
  }
}

// Recording only the events of flagged particles (as the MPI windows do for copies and sent
// atoms) gives exactly the events of the full record that involve a flagged particle, in the
// same order, and the same trajectory; pair collisions and wall collisions alike.
TEST(EventDriven, RecordsOnlyFlaggedParticlesEvents)
{
  SystemSpec s = spec_of(400, 2, 0.3, 23);
  Reference ref = make_system(s, LawParams::rough(0.9, 0.2));
  ref.periodic[1] = false;
  ref.walls.push_back({1, -1, ref.lo.y - 0.6, LawParams::rough(0.8, -1.0)});
  ref.walls.push_back({1, +1, ref.lo.y + ref.L.y + 0.6, LawParams::rough(0.8, -1.0)});
  const double dt = 3.0 * mean_free_time(ref);
  std::vector<uint8_t> flag(ref.p.size(), 0);
  for (size_t e = 0; e < flag.size(); e += 7) flag[e] = 1;
  CoreRun all(ref), some(ref);
  all.ed.start();
  some.ed.start();
  std::vector<EDEvent> ha, hs;
  all.ed.record_events(&ha);
  some.ed.record_events(&hs, flag.data());
  all.total.add(all.ed.advance_to(dt));
  some.total.add(some.ed.advance_to(dt));
  std::vector<EDEvent> expected;
  for (const EDEvent &e : ha)
    if (flag[e.i] || (e.j >= 0 && flag[e.j])) expected.push_back(e);
  ASSERT_GT(all.total.wall_collisions, 0);
  ASSERT_GT(expected.size(), 50u);
  ASSERT_LT(expected.size(), ha.size() / 2) << "the flags select a minority of the events";
  ASSERT_EQ(hs.size(), expected.size());
  bool walls = false;
  for (size_t k = 0; k < hs.size(); k++) {
    EXPECT_EQ(hs[k].t, expected[k].t);
    EXPECT_EQ(hs[k].i, expected[k].i);
    EXPECT_EQ(hs[k].j, expected[k].j);
    EXPECT_EQ(norm(hs[k].vi - expected[k].vi), 0.0);
    walls = walls || hs[k].j < 0;
  }
  EXPECT_TRUE(walls) << "some recorded events are wall collisions";
  EXPECT_EQ(some.total.collisions, all.total.collisions);
  for (int e = 0; e < all.ed.size(); e++)
    EXPECT_EQ(norm(all.ed.position(e, dt) - some.ed.position(e, dt)), 0.0);
}

// track_fast(): the fast list holds exactly the velocity changes (pair and wall collisions,
// kicks) that leave a particle at or above the threshold, in time order; so every particle
// not listed stays within path_bound() of its start (checked against its positions at many
// times of the window); off by default and after track_fast(INF).
TEST(EventDriven, FastListBoundsPaths)
{
  SystemSpec s = spec_of(400, 2, 0.3, 29);
  Reference ref = make_system(s, LawParams::rough(0.9, 0.2));
  ref.periodic[1] = false;
  ref.gravity = Vec3(0.0, -0.4, 0.0);
  ref.walls.push_back({1, -1, ref.lo.y - 0.6, LawParams::rough(0.8, -1.0)});
  ref.walls.push_back({1, +1, ref.lo.y + ref.L.y + 0.6, LawParams::rough(0.8, -1.0)});
  const double dt = 3.0 * mean_free_time(ref);
  const int n = (int) ref.p.size(), pieces = 40;
  CoreRun run(ref);
  EventDriven &ed = run.ed;
  ed.start();
  EXPECT_TRUE(ed.fast_list().empty());
  // threshold: the squared speed that 1 particle in 10 exceeds at the start
  std::vector<double> s0(n);
  for (int e = 0; e < n; e++) s0[e] = norm2(ed.velocity(e, 0.0));
  std::vector<double> sorted = s0;
  std::sort(sorted.begin(), sorted.end());
  const double s2 = sorted[n * 9 / 10];
  const double tk = 16 * dt / pieces;    // a kick of every particle, at a piece boundary
  auto dv = [](int e) { return Vec3(test_kick(e, 1, 0.3).x, test_kick(e, 1, 0.3).y, 0.0); };
  std::vector<EDEvent> h;
  ed.record_events(&h);
  ed.track_fast(s2);
  // positions at many times of the window (advance_to in pieces keeps the trajectory)
  std::vector<Vec3> x0(n);
  for (int e = 0; e < n; e++) x0[e] = ed.position(e, 0.0);
  std::vector<double> far(n, 0.0), kicked2(n);
  for (int k = 1; k <= pieces; k++) {
    run.total.add(ed.advance_to(k * dt / pieces));
    for (int e = 0; e < n; e++) far[e] = std::max(far[e], norm(ed.position(e, k * dt / pieces) - x0[e]));
    if (k == 16) {    // (the next advance_to kicks at tk)
      for (int e = 0; e < n; e++) kicked2[e] = norm2(ed.velocity(e, tk) + dv(e));
      ed.set_global_events({tk}, [&](int) {
        for (int e = 0; e < n; e++) ed.particle(e).v += dv(e);
      });
    }
  }
  ASSERT_GT(run.total.wall_collisions, 0);
  ASSERT_EQ(run.total.global_events, 1);
  // the list: the collisions before the kick, the kick, the collisions after it
  std::vector<std::pair<int, double>> before, after;
  for (const EDEvent &e : h) {
    auto &to = e.t < tk ? before : after;
    if (norm2(e.vi) >= s2) to.push_back({e.i, norm2(e.vi)});
    if (e.j >= 0 && norm2(e.vj) >= s2) to.push_back({e.j, norm2(e.vj)});
  }
  const auto &fl = ed.fast_list();
  ASSERT_GT(before.size(), 10u);
  ASSERT_GT(after.size(), 10u);
  ASSERT_GE(fl.size(), before.size() + after.size());
  for (size_t k = 0; k < before.size(); k++) EXPECT_EQ(fl[k], before[k]);
  const size_t na = fl.size() - after.size();
  for (size_t k = 0; k < after.size(); k++) EXPECT_EQ(fl[na + k], after[k]);
  std::vector<int> listed(n, 0), by_kick(n, 0);
  for (const auto &f : fl) listed[f.first] = 1;
  for (size_t k = before.size(); k < na; k++) {
    EXPECT_EQ(by_kick[fl[k].first]++, 0) << "the kick lists a particle once";
    EXPECT_NEAR(fl[k].second, kicked2[fl[k].first], 1e-12 * s2);
  }
  long nkick = 0;
  for (int e = 0; e < n; e++) {
    if (kicked2[e] > s2 * (1 + 1e-9)) EXPECT_EQ(by_kick[e], 1) << "particle " << e;
    if (kicked2[e] < s2 * (1 - 1e-9)) EXPECT_EQ(by_kick[e], 0) << "particle " << e;
    nkick += by_kick[e];
  }
  EXPECT_GT(nkick, 10);
  // a particle never listed stays within the bound from max(its start, the threshold)
  long unlisted = 0;
  for (int e = 0; e < n; e++) {
    if (listed[e]) continue;
    unlisted++;
    const double bound = dt * (std::sqrt(std::max(s0[e], s2)) + 0.5 * dt * norm(ref.gravity));
    EXPECT_DOUBLE_EQ(ed.path_bound(std::max(s0[e], s2), dt), bound);
    EXPECT_LE(far[e], bound) << "particle " << e;
  }
  EXPECT_GT(unlisted, n / 2);
  ed.track_fast(INF);
  EXPECT_TRUE(ed.fast_list().empty());
}

TEST(Prediction, PairContactTime)
{
  // head-on: distance 3 along x, closing at speed 2, contact at sigma = 1 after 1
  EXPECT_DOUBLE_EQ(pair_contact_time(Vec3(3, 0, 0), Vec3(-2, 0, 0), 1.0), 1.0);
  EXPECT_EQ(pair_contact_time(Vec3(3, 0, 0), Vec3(2, 0, 0), 1.0), NEVER);    // separating
  EXPECT_EQ(pair_contact_time(Vec3(3, 2, 0), Vec3(-2, 0, 0), 1.0), NEVER);   // misses
  EXPECT_EQ(pair_contact_time(Vec3(0.9, 0, 0), Vec3(-1, 0, 0), 1.0), 0.0);   // overlap, approaching
  // grazing within tolerance
  const double tau = pair_contact_time(Vec3(3, 0.999999, 0), Vec3(-1, 0, 0), 1.0);
  EXPECT_GT(tau, 2.0);
  EXPECT_LT(tau, 3.0);
}

// With a horizon a contact time is either the one without (bit for bit) or NEVER, and NEVER only
// where the contact without a horizon comes at or after the horizon: horizons around the
// contact time itself (0.1 ... 1e-15 of it away, across the test's margin of 1e-6), 3d and 2d;
// head-on pairs near touching, grazing pairs (impact parameter within 1e-4 ... 1e-14 of sigma,
// where the square root cancels most) and others
TEST(Prediction, PairContactTimeHorizonOnlyDropsLaterContacts)
{
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> pick(0, 7);
  long pruned = 0, kept = 0, tight = 0, grazing = 0;
  for (int k = 0; k < 300000; k++) {
    const double sigma = 1.0 + 0.5 * u(rng);
    Vec3 r, v;
    const int kind = k % 3;
    if (kind < 2) {
      // from 4 sigma apart down to near touching; nearly head-on (kind 0) or anything
      const double d = sigma * (1.0 + 4.0 * std::pow(10.0, -pick(rng)) * std::fabs(u(rng)));
      const double spread = kind == 0 ? 0.01 : 1.0;
      r = Vec3(d, spread * u(rng) * d, spread * u(rng) * d);
      v = Vec3(-std::fabs(u(rng)) - 1e-3, spread * u(rng), spread * u(rng));
    } else {
      // grazing: moving along -x at an impact parameter just below sigma, offset in y and z
      const double s = sigma * (1.0 - std::pow(10.0, -4 - 10.0 * std::fabs(u(rng))));
      const double phi = 3.14159 * u(rng);
      r = Vec3(sigma * (1.5 + std::fabs(u(rng))), s * std::cos(phi), s * std::sin(phi));
      v = Vec3(-(0.1 + std::fabs(u(rng))), 0.0, 0.0);
    }
    const double z = kind == 2 ? r.z : 0.3 * sigma * u(rng);    // (2d: a constant z distance)
    const double f3 = pair_contact_time<3>(r.x, r.y, r.z, v.x, v.y, v.z, sigma);
    const double f2 = pair_contact_time<2>(r.x, r.y, z, v.x, v.y, 0.0, sigma);
    for (const double f : {f3, f2}) {
      if (f == NEVER) continue;
      grazing += kind == 2;
      const double scale = std::pow(10.0, -2 * pick(rng) - 1);
      const bool in3 = f == f3;
      const double horizon = f * (1.0 + scale * u(rng));
      const double h = in3 ? pair_contact_time<3>(r.x, r.y, r.z, v.x, v.y, v.z, sigma, horizon)
                           : pair_contact_time<2>(r.x, r.y, z, v.x, v.y, 0.0, sigma, horizon);
      if (h == NEVER) {
        ASSERT_GE(f, horizon) << "k " << k;
        pruned++;
        tight += horizon > f * (1.0 - 1e-4);
      } else {
        ASSERT_EQ(h, f) << "k " << k;
        kept++;
      }
    }
  }
  EXPECT_GT(pruned, 10000);
  EXPECT_GT(kept, 10000);
  EXPECT_GT(tight, 1000);    // dropped within 1e-4 of the horizon
  EXPECT_GT(grazing, 10000);
}

TEST(Prediction, CrossingTime)
{
  EXPECT_DOUBLE_EQ(crossing_time(0.0, 2.0, 0.0, 1.0, +1), 0.5);
  EXPECT_EQ(crossing_time(0.0, 2.0, 0.0, -1.0, -1), NEVER);
  EXPECT_DOUBLE_EQ(crossing_time(0.0, -2.0, 0.0, -1.0, -1), 0.5);
  // thrown up at 2 under g = -1: reaches 1 upward at 2 - sqrt(2), downward at 2 + sqrt(2)
  EXPECT_NEAR(crossing_time(0.0, 2.0, -1.0, 1.0, +1), 2.0 - std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(crossing_time(0.0, 2.0, -1.0, 1.0, -1), 2.0 + std::sqrt(2.0), 1e-14);
  // comes back through its start point at 4
  EXPECT_NEAR(crossing_time(0.0, 2.0, -1.0, 0.0, -1), 4.0, 1e-14);
  EXPECT_EQ(crossing_time(0.0, 2.0, -1.0, 3.0, +1), NEVER);    // apex at 2
  // sitting a hair below B after crossing upward must not cross upward again later
  EXPECT_EQ(crossing_time(1.0 - 1e-16, 1e-3, -1.0, 1.0, +1), 0.0 + crossing_time(1.0 - 1e-16, 1e-3, -1.0, 1.0, +1));
  EXPECT_NEAR(crossing_time(1.0 - 1e-16, 1e-3, -1.0, 1.0, -1), 2e-3, 1e-12);
  // a hair beyond B still moving that way: cross now
  EXPECT_EQ(crossing_time(1.0 + 1e-16, 1.0, 0.0, 1.0, +1), 0.0);
  EXPECT_EQ(crossing_time(1.0 + 1e-16, 1.0, -1.0, 1.0, +1), 0.0);
  // at rest on B (or a hair beyond) and accelerated through it: cross now (a grain that a floor
  // of restitution 0 left at rest under gravity; before, the root was 0/0 or not real, and the
  // grain fell through the floor)
  EXPECT_EQ(crossing_time(1.0, 0.0, -1.0, 1.0, -1), 0.0);
  EXPECT_EQ(crossing_time(1.0 - 1e-16, 0.0, -1.0, 1.0, -1), 0.0);
  EXPECT_EQ(crossing_time(1.0 - 1e-16, -1e-12, -1.0, 1.0, -1), 0.0);
  EXPECT_EQ(crossing_time(1.0, 0.0, 1.0, 1.0, +1), 0.0);
  // ... but not when accelerated back, or at rest with no acceleration
  EXPECT_EQ(crossing_time(1.0, 0.0, 1.0, 1.0, -1), NEVER);
  EXPECT_EQ(crossing_time(1.0, 0.0, 0.0, 1.0, -1), NEVER);
  // a hair beyond B, moving back too slowly to reach it: crosses as it turns
  EXPECT_DOUBLE_EQ(crossing_time(1.0 - 1e-16, 1e-12, -1.0, 1.0, -1), 1e-12);
}

}    // namespace

// the one list of summed statistics: add() sums every field (vectors grow), the maximum is a
// maximum, and flatten/unflatten carry every summed field through flat arrays
TEST(EDStatsFields, AddFlattenUnflatten)
{
  EDStats a, b;
  long n = 1;
  double x = 0.5;
  auto fill = [&](EDStats &s, size_t walls) {
    s.wall_hits.assign(walls, 0);
    s.wall_impulse.assign(3 * walls, 0.0);
    s.wall_work.assign(walls, 0.0);
    s.gamma_hist.assign(4, 0);
    EDStats::each_sum(
        [&](auto &f) {
          using T = std::decay_t<decltype(f)>;
          if constexpr (std::is_same_v<T, long>) f = n++;
          else if constexpr (std::is_same_v<T, double>) f = x += 0.25;
          else for (auto &e : f) e = (typename T::value_type) (n++);
        },
        s);
  };
  fill(a, 1);
  fill(b, 2);
  a.max_collisions_one_particle = 7;
  b.max_collisions_one_particle = 3;
  EDStats sum = a;
  sum.add(b);
  EXPECT_EQ(sum.collisions, a.collisions + b.collisions);
  EXPECT_EQ(sum.virial[5], a.virial[5] + b.virial[5]);
  ASSERT_EQ(sum.wall_hits.size(), 2u);
  EXPECT_EQ(sum.wall_hits[1], b.wall_hits[1]);
  EXPECT_EQ(sum.wall_work[0], a.wall_work[0] + b.wall_work[0]);
  EXPECT_EQ(sum.max_collisions_one_particle, 7);
  std::vector<long> counts;
  std::vector<double> sums;
  sum.flatten(counts, sums);
  EXPECT_EQ(counts.size(), 7u + 2u + 4u);
  EXPECT_EQ(sums.size(), 3u + 6u + 6u + 2u);
  EDStats back;
  back.wall_hits.assign(2, 0);
  back.wall_impulse.assign(6, 0.0);
  back.wall_work.assign(2, 0.0);
  back.gamma_hist.assign(4, 0);
  back.unflatten(counts.data(), sums.data());
  std::vector<long> c2;
  std::vector<double> s2;
  back.flatten(c2, s2);
  EXPECT_EQ(c2, counts);
  EXPECT_EQ(s2, sums);
  EXPECT_EQ(back.dE_wall, sum.dE_wall);
  EXPECT_EQ(back.gamma_hist[3], sum.gamma_hist[3]);
}

// the ID map of domain windows against std::unordered_map: random inserts, overwrites and
// erases (long probe runs included: few distinct homes at the start), growth past its room
TEST(IdMapTable, AgreesWithUnorderedMap)
{
  IdMap m;
  m.reset(8);
  std::unordered_map<long, int> ref;
  std::mt19937_64 rng(5);
  for (int step = 0; step < 200000; step++) {
    const long key = (long) (rng() % (step < 20000 ? 64 : 5000));
    const int op = (int) (rng() % 3);
    if (op == 2) {
      m.erase(key);
      ref.erase(key);
    } else {
      const int v = (int) (rng() % 1000);
      m.set(key, v);
      ref[key] = v;
    }
    if (step % 997 == 0)
      for (long k = 0; k < 5000; k++) {
        const auto it = ref.find(k);
        ASSERT_EQ(m.get(k), it == ref.end() ? -1 : it->second) << "step " << step << " key " << k;
      }
  }
  EXPECT_EQ(m.size(), ref.size());
}

// The cell grid cannot change the rounding: a particle's stored state changes only at its own
// collisions (not at cell crossings) and a pair's contact time is computed from the two stored
// states alone, whoever predicts it and whenever. So systems that differ only in their cell
// width, or that find candidates in cells and in neighbour lists, follow the same trajectory bit
// for bit, over windows that keep one time origin (2D and 3D, dense and dilute, smooth and
// rough inelastic laws).
TEST(CellGridIndependence, SameBitsForAnyCellWidth)
{
  struct Case {
    int dim;
    int n;
    double phi, w1, w2;
    LawParams law;
    bool lists = false;    // the second system finds candidates in neighbour lists
  };
  const Case cases[] = {{2, 600, 0.3, 1.0, 2.5, LawParams::rough(1.0, -1.0)},
                        {2, 600, 0.05, 1.0, 3.0, LawParams::rough(0.9, 0.4)},
                        {3, 500, 0.3, 1.0, 2.0, LawParams::walton(0.9, 0.3, 0.4)},
                        {3, 1000, 0.45, 1.0, 1.0, LawParams::rough(1.0, -1.0), true}};
  for (const Case &c : cases) {
    EventDriven a, b;
    std::mt19937_64 rng(11);
    const double L = std::pow(c.n * (c.dim == 2 ? M_PI * 0.25 : M_PI / 6.0) / c.phi, 1.0 / c.dim);
    auto build = [&](EventDriven &ed, double w, bool lists) {
      EDOptions o;
      o.dim = c.dim;
      o.cell_width = w;
      o.neighbours = lists ? EDOptions::LISTS : EDOptions::CELLS;
      for (int d = 0; d < 3; d++) o.hi[d] = d < c.dim ? L : 1.0;
      ed.configure(o, 1, std::vector<LawParams>(4, c.law));
      ed.resize(c.n);
    };
    build(a, c.w1, false);
    build(b, c.w2, c.lists);
    const int m = (int) std::ceil(std::pow((double) c.n, 1.0 / c.dim) - 1e-9);
    std::normal_distribution<double> G(0, 1);
    for (int i = 0; i < c.n; i++) {
      const int ix = i % m, iy = (i / m) % m, iz = i / (m * m);
      const Vec3 x((ix + 0.5) * L / m, (iy + 0.5) * L / m, c.dim == 3 ? (iz + 0.5) * L / m : 0.5);
      const Vec3 v(G(rng), G(rng), c.dim == 3 ? G(rng) : 0.0), w(G(rng), G(rng), G(rng));
      for (EventDriven *ed : {&a, &b}) {
        auto p = ed->particle(i);
        p.x = x, p.v = v, p.w = w, p.a = 0.5, p.m = 1.0;
      }
    }
    a.start();
    b.start();
    ASSERT_TRUE(a.cell_size() != b.cell_size() || a.uses_lists() != b.uses_lists());
    // (the Enskog mean free time at T = 1; windows of half of it, 60 of them, one time origin)
    const double dens = c.n / std::pow(L, c.dim);
    const double g = c.dim == 2 ? (1 - 7 * c.phi / 16) / ((1 - c.phi) * (1 - c.phi))
                                : (1 - c.phi / 2) / std::pow(1 - c.phi, 3);
    const double mft = 1.0 / ((c.dim == 2 ? 2.0 : 4.0) * dens * g * std::sqrt(M_PI));
    const double end = 30.0 * mft;
    long collisions = 0;
    for (int k = 1; k <= 60; k++) {
      collisions += a.advance_to(end * k / 60.0).collisions;
      b.advance_to(end * k / 60.0);
    }
    // (at least 10 collisions per particle: chaos amplifies any difference long before)
    EXPECT_GT(2 * collisions, 10L * c.n);
    for (int e = 0; e < c.n; e++) {
      double xa[3], va[3], wa[3], xb[3], vb[3], wb[3];
      a.state(e, end, xa, va, wa);
      b.state(e, end, xb, vb, wb);
      for (int d = 0; d < 3; d++) {
        ASSERT_EQ(xa[d], xb[d]) << "dim " << c.dim << " fraction " << c.phi << " particle " << e;
        ASSERT_EQ(va[d], vb[d]);
        ASSERT_EQ(wa[d], wb[d]);
      }
    }
  }
}

// start_at(): a core built afresh (another cell grid) from the stored states of a running one
// (x, v at their own times, w, last partners) continues its trajectory bit for bit, as a
// domain window that rebuilds its grid continues the serial run
TEST(CellGridIndependence, StartAtContinuesStoredStates)
{
  for (int dim : {2, 3}) {
    const int n = dim == 2 ? 600 : 500;
    const double phi = 0.3, L = std::pow(n * (dim == 2 ? M_PI * 0.25 : M_PI / 6.0) / phi, 1.0 / dim);
    const LawParams law = LawParams::walton(0.9, 0.3, 0.4);
    auto options = [&](double w) {
      EDOptions o;
      o.dim = dim;
      o.cell_width = w;
      o.neighbours = EDOptions::CELLS;
      for (int d = 0; d < 3; d++) o.hi[d] = d < dim ? L : 1.0;
      return o;
    };
    EventDriven a, b;
    a.configure(options(1.0), 1, std::vector<LawParams>(4, law));
    a.resize(n);
    std::mt19937_64 rng(5);
    std::normal_distribution<double> G(0, 1);
    const int m = (int) std::ceil(std::pow((double) n, 1.0 / dim) - 1e-9);
    for (int i = 0; i < n; i++) {
      const int ix = i % m, iy = (i / m) % m, iz = i / (m * m);
      auto p = a.particle(i);
      p.x = Vec3((ix + 0.5) * L / m, (iy + 0.5) * L / m, dim == 3 ? (iz + 0.5) * L / m : 0.5);
      p.v = Vec3(G(rng), G(rng), dim == 3 ? G(rng) : 0.0);
      p.w = Vec3(G(rng), G(rng), G(rng));
      p.a = 0.5, p.m = 1.0;
    }
    a.start();
    const double dt = 0.05;
    long collisions = 0;
    for (int k = 1; k <= 40; k++) collisions += a.advance_to(k * dt).collisions;
    // b: a's stored states at window 40, on a grid twice as wide, then both go on
    b.configure(options(2.0), 1, std::vector<LawParams>(4, law));
    b.resize(n);
    for (int e = 0; e < n; e++) {
      auto p = b.particle(e);
      p = std::as_const(a).particle(e);
    }
    for (int e = 0; e < n; e++) b.set_last_partner(e, a.last_partner(e), a.last_offset(e));
    b.start_at(40 * dt);
    for (int k = 41; k <= 240; k++) {
      collisions += a.advance_to(k * dt).collisions;
      b.advance_to(k * dt);
    }
    EXPECT_GT(2 * collisions, 10L * n);
    for (int e = 0; e < n; e++) {
      double xa[3], va[3], wa[3], xb[3], vb[3], wb[3];
      a.state(e, 240 * dt, xa, va, wa);
      b.state(e, 240 * dt, xb, vb, wb);
      for (int d = 0; d < 3; d++) {
        ASSERT_EQ(xa[d], xb[d]) << "dim " << dim << " particle " << e;
        ASSERT_EQ(va[d], vb[d]);
        ASSERT_EQ(wa[d], wb[d]);
      }
    }
  }
}
