// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// Core tests of neighbour lists (EDOptions::LISTS): trajectories equal to the brute-force
// reference, as with cells, for every law in 2D and 3D, with kicks, walls, a list overflow and an
// image shift beyond a list entry's range;
// the automatic choice. (Changes between windows: test_event_driven.cpp.)
#include "ed_fixture.h"

#include <gtest/gtest.h>

using namespace granfric;
using namespace granfric_test;

namespace {

// a core run of the reference's system with the given neighbour structure, in windows of dt
// (queue kept, as fix hardsphere/ed runs) up to nwin dt
CoreRun run_windows(const Reference &ref, int neighbours, double skin, double dt, int nwin)
{
  CoreRun run(ref, 1000000, neighbours, skin);
  run.ed.start();
  for (int w = 0; w < nwin; w++) {
    run.total.add(run.ed.advance_to(dt));
    run.ed.rebase(dt);
  }
  return run;
}

void expect_reference_state(const Reference &ref, const CoreRun &run, double tol)
{
  for (size_t i = 0; i < ref.p.size(); i++) {
    EXPECT_LT(norm(run.ed.position((int) i, 0.0) - ref.p[i].x), tol) << "particle " << i;
    EXPECT_LT(norm(run.ed.velocity((int) i, 0.0) - ref.p[i].v), tol) << "particle " << i;
    EXPECT_LT(ref.p[i].a * norm(run.ed.particle((int) i).w - ref.p[i].w), tol) << "particle " << i;
  }
}

}    // namespace

// every law, 2D and 3D, dilute to dense, polydisperse, skins from tight to wide: the lists give
// the reference trajectory, and the particles rebuild their lists (the events happen)
TEST(NeighbourLists, EqualReference)
{
  struct C {
    int law, dim, n;
    double phi, skin, dt_mft, T_mft;
  };
  const C cases[] = {{0, 3, 200, 0.35, 0.5, 1.0, 4}, {1, 3, 200, 0.45, 0.2, 0.3, 4},
                     {2, 3, 150, 0.2, 1.0, 5.0, 4},  {0, 2, 200, 0.4, 0.5, 2.0, 4},
                     {1, 2, 150, 0.1, 0.3, 0.5, 3},  {2, 3, 60, 0.3, 0.05, 1.0, 4},
                     {1, 3, 40, 0.2, 1.0, 1.0, 6}};
  for (const C &c : cases) {
    SystemSpec s = spec_of(c.n, c.dim, c.phi, 700 + 10 * c.law + c.dim);
    s.q = c.dim == 2 ? 0.5 : 0.4;
    s.lattice = c.phi >= 0.3;    // (dense: equal spheres from a lattice)
    s.polydisperse = !s.lattice;
    Reference ref = make_system(s, law_of(c.law));
    const double mft = mean_free_time(ref);
    const double dt = c.dt_mft * mft;
    const int nwin = (int) std::ceil(c.T_mft / c.dt_mft);
    SCOPED_TRACE("law " + std::to_string(c.law) + " dim " + std::to_string(c.dim) + " phi " +
                 std::to_string(c.phi) + " skin " + std::to_string(c.skin));
    CoreRun run = run_windows(ref, EDOptions::LISTS, c.skin, dt, nwin);
    ref.run_until(nwin * dt);
    EXPECT_TRUE(run.ed.uses_lists());
    EXPECT_GT(run.total.crossings, 0) << "no list was rebuilt";
    ASSERT_GE(ref.collisions, (long) c.n);
    EXPECT_EQ(run.total.collisions, ref.collisions);
    EXPECT_NEAR(run.total.dE, ref.dE, 1e-9 * std::fabs(ref.dE));
    expect_reference_state(ref, run, 1e-9);
  }
}

// kicks (global events re-predict every particle from the kept lists) and walls (predicted per
// particle, as with cells), 3D
TEST(NeighbourLists, KicksAndWallsEqualReference)
{
  SystemSpec s = spec_of(150, 3, 0.25, 811);
  Reference ref = make_system(s, LawParams::walton(0.8, 0.3, 0.4));
  ref.periodic[1] = false;
  ref.walls.push_back({1, -1, ref.lo.y - 0.6, LawParams::rough(0.9, 0.2)});
  ref.walls.push_back({1, +1, ref.lo.y + ref.L.y + 0.6, LawParams::walton(0.7, 0.5, 0.3)});
  const double mft = mean_free_time(ref);
  const double period = 0.31 * mft, dt = 0.57 * mft;
  const int nwin = 8;
  auto dv = [](int e, int k) {
    std::mt19937_64 g(1000003ULL * (unsigned) e + 7919ULL * (unsigned) k + 17);
    std::normal_distribution<double> n(0.0, 0.3);
    return Vec3(n(g), n(g), n(g));
  };
  for (int k = 1; k * period < nwin * dt; k++) ref.kick_times.push_back(k * period);
  ref.kick = [&](std::vector<RefParticle> &ps, int k) {
    for (size_t e = 0; e < ps.size(); e++) ps[e].v += dv((int) e, k);
  };
  CoreRun run(ref, 1000000, EDOptions::LISTS, 0.4);
  EventDriven &ed = run.ed;
  ed.start();
  double t0 = 0.0;
  for (int w = 0; w < nwin; w++) {
    window_kicks(ed, ref, t0, dt, dv);
    run.total.add(ed.advance_to(dt));
    ed.rebase(dt);
    t0 += dt;
  }
  ref.run_until(nwin * dt);
  EXPECT_TRUE(ed.uses_lists());
  EXPECT_GT(run.total.global_events, 10);
  EXPECT_GT(run.total.wall_collisions, 10);
  EXPECT_EQ(run.total.wall_collisions, ref.wall_collisions);
  EXPECT_EQ(run.total.collisions, ref.collisions);
  expect_reference_state(ref, run, 1e-9);
}

// a skin so wide that the lists overflow: the core continues with cells at that moment, on the
// same trajectory
TEST(NeighbourLists, OverflowContinuesWithCells)
{
  SystemSpec s = spec_of(300, 3, 0.25, 1011);
  Reference ref = make_system(s, LawParams::rough(0.9, 0.3));
  const double mft = mean_free_time(ref);
  CoreRun run = run_windows(ref, EDOptions::LISTS, 3.0, 0.5 * mft, 6);
  ref.run_until(3.0 * mft);
  EXPECT_FALSE(run.ed.uses_lists()) << "lists of ~5 sigma cannot hold their neighbours";
  EXPECT_EQ(run.total.collisions, ref.collisions);
  expect_reference_state(ref, run, 1e-9);
}

// a particle whose stored position lies 200 periods away: its image shift to its neighbours
// does not fit a list entry, so the core continues with cells from the start, on the trajectory
// cells give, bit for bit
TEST(NeighbourLists, FarImageContinuesWithCells)
{
  SystemSpec s = spec_of(200, 3, 0.4, 1213);
  s.lattice = true;
  s.polydisperse = false;
  Reference ref = make_system(s, LawParams::rough(0.9, 0.3));
  const double mft = mean_free_time(ref);
  CoreRun lists(ref, 1000000, EDOptions::LISTS, 0.4), cells(ref, 1000000, EDOptions::CELLS);
  for (CoreRun *r : {&lists, &cells}) {
    r->ed.particle(7).x.x += 200.0 * ref.L.x;
    r->ed.start();
    for (int w = 0; w < 8; w++) {
      r->total.add(r->ed.advance_to(0.5 * mft));
      r->ed.rebase(0.5 * mft);
    }
  }
  EXPECT_FALSE(lists.ed.uses_lists());
  ASSERT_GT(cells.total.collisions, 200);
  EXPECT_EQ(lists.total.collisions, cells.total.collisions);
  for (int e = 0; e < (int) ref.p.size(); e++) {
    EXPECT_EQ(lists.ed.position(e, 0.0).x, cells.ed.position(e, 0.0).x) << "particle " << e;
    EXPECT_EQ(lists.ed.velocity(e, 0.0).y, cells.ed.velocity(e, 0.0).y) << "particle " << e;
  }
}

// the automatic choice: lists in small dense 3d gases without gravity, cells otherwise; lists
// with gravity are refused
TEST(NeighbourLists, AutomaticChoiceAndLimits)
{
  auto uses_lists = [](int dim, double phi, bool gravity, int n = 300) {
    SystemSpec s = spec_of(n, dim, phi, 5);
    s.polydisperse = false;
    s.lattice = true;
    Reference ref = make_system(s, LawParams::rough(1.0, -1.0));
    if (gravity) ref.gravity = Vec3(0.0, -1.0, 0.0);
    CoreRun run(ref);
    run.ed.start();
    return run.ed.uses_lists();
  };
  EXPECT_TRUE(uses_lists(3, 0.45, false));
  EXPECT_FALSE(uses_lists(3, 0.45, true));
  EXPECT_FALSE(uses_lists(3, 0.1, false));
  EXPECT_FALSE(uses_lists(2, 0.45, false));
  EXPECT_TRUE(uses_lists(3, 0.45, false, 13824));
  EXPECT_FALSE(uses_lists(3, 0.45, false, (int) EventDriven::MAX_LISTS + 1))
      << "lists beyond the cache are slower";
  EventDriven ed;
  EDOptions o;
  o.neighbours = EDOptions::LISTS;
  o.gravity = Vec3(0.0, -1.0, 0.0);
  EXPECT_THROW(ed.configure(o, 1, std::vector<LawParams>(4)), std::invalid_argument);
  o.gravity = Vec3();
  o.neighbours = 3;
  EXPECT_THROW(ed.configure(o, 1, std::vector<LawParams>(4)), std::invalid_argument);
  o.neighbours = EDOptions::LISTS;
  o.list_skin = -0.1;
  EXPECT_THROW(ed.configure(o, 1, std::vector<LawParams>(4)), std::invalid_argument);
}
