// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// Core tests of the candidate scan in AVX2 lanes (EDOptions::simd): the same trajectory, bit for
// bit, as one candidate at a time, with cells and with lists, at the grid's edges and with
// image shifts, for every law.
#include "ed_fixture.h"

#include <gtest/gtest.h>


using namespace granfric;
using namespace granfric_test;

namespace {

// the reference's system run in windows of dt up to T, one candidate at a time or in lanes
CoreRun run_lanes(const Reference &ref, int neighbours, bool simd, double dt, double T)
{
  CoreRun run(ref, 1000000, neighbours, 0.0, simd);
  run.run(T, dt);
  return run;
}

}    // namespace

// 3d systems from dilute to dense, with cells and with lists, run long enough that particles
// cross the box (image shifts of every sign): every particle's state has the same bits
TEST(Lanes, SameBitsAsOneAtATime)
{
  if (!EventDriven::have_lanes()) GTEST_SKIP() << "this processor has no AVX2";
  struct C {
    int law, n;
    double phi;
    int neighbours;
    double dt_mft, T_mft;
  };
  const C cases[] = {{0, 300, 0.05, EDOptions::CELLS, 5.0, 60}, {1, 300, 0.25, EDOptions::CELLS, 1.0, 20},
                     {0, 200, 0.40, EDOptions::CELLS, 2.0, 30}, {0, 200, 0.45, EDOptions::LISTS, 1.0, 30},
                     {1, 200, 0.30, EDOptions::LISTS, 0.5, 25}, {2, 150, 0.35, EDOptions::LISTS, 2.0, 40},
                     {0, 27, 0.20, EDOptions::CELLS, 3.0, 40}};
  for (const C &c : cases) {
    SystemSpec s = spec_of(c.n, 3, c.phi, 900 + 10 * c.law + c.neighbours);
    s.lattice = c.phi >= 0.3;
    s.polydisperse = !s.lattice;
    Reference ref = make_system(s, law_of(c.law));
    const double mft = mean_free_time(ref);
    ref.tc = 1e-3 * mft;    // (the TC model: no inelastic collapse in the long runs)
    SCOPED_TRACE("law " + std::to_string(c.law) + " phi " + std::to_string(c.phi) + " neighbours " +
                 std::to_string(c.neighbours));
    const CoreRun one = run_lanes(ref, c.neighbours, false, c.dt_mft * mft, c.T_mft * mft);
    const CoreRun four = run_lanes(ref, c.neighbours, true, c.dt_mft * mft, c.T_mft * mft);
    ASSERT_GE(one.total.collisions, 5L * c.n);
    EXPECT_EQ(four.total.collisions, one.total.collisions);
    EXPECT_EQ(four.total.crossings, one.total.crossings);
    EXPECT_EQ(states_differing(four, one), 0) << "particles whose state differs in some bit";
  }
}

// The same in a sheared box (Lees-Edwards): the lanes take the shift and the shear rate of the
// image above or below, as contact_at() does; shear of either sign, slow and fast
TEST(Lanes, ShearedSameBitsAsOneAtATime)
{
  if (!EventDriven::have_lanes()) GTEST_SKIP() << "this processor has no AVX2";
  const double rates[] = {0.3, -2.0};
  for (double rate : rates) {
    SystemSpec s = spec_of(300, 3, 0.25, 950 + (rate > 0));
    s.polydisperse = true;
    Reference ref = make_system(s, law_of(1));
    const double mft = mean_free_time(ref);
    double v2 = 0.0;
    for (const auto &a : ref.p) v2 += norm2(a.v);
    ref.shear = true;
    ref.shear_rate = rate * std::sqrt(v2 / ref.p.size()) * ref.L.y;
    ref.shift0 = 0.61 * ref.L.x;
    ref.tc = 1e-3 * mft;
    SCOPED_TRACE("rate " + std::to_string(rate));
    const CoreRun one = run_lanes(ref, EDOptions::CELLS, false, mft, 15 * mft);
    const CoreRun four = run_lanes(ref, EDOptions::CELLS, true, mft, 15 * mft);
    ASSERT_GE(one.total.collisions, 5L * 300);
    EXPECT_EQ(four.total.collisions, one.total.collisions);
    EXPECT_EQ(four.total.crossings, one.total.crossings);
    EXPECT_EQ(states_differing(four, one), 0) << "particles whose state differs in some bit";
  }
}
