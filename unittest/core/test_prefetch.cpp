// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// Core tests of the event loop's prefetching (EDOptions::prefetch_bytes): asking the memory ahead
// for the records of events to come reads the queue's bucket lists, schedules and cell lists
// but changes nothing, so small systems run with it from their first particle follow the
// trajectory they follow without it, bit for bit, with cells and lists, in 2d and 3d, across
// windows and kicks (which rebuild the queue).
#include "ed_fixture.h"

#include <gtest/gtest.h>


using namespace granfric;
using namespace granfric_test;

TEST(Prefetch, SameBitsAsWithout)
{
  struct C {
    int dim, law, n;
    double phi;
    int neighbours;
  };
  const C cases[] = {{3, 0, 3000, 0.05, EDOptions::CELLS}, {3, 1, 400, 0.25, EDOptions::CELLS},
                     {3, 0, 300, 0.45, EDOptions::LISTS}, {2, 2, 800, 0.30, EDOptions::CELLS}};
  for (const C &c : cases) {
    SystemSpec s = spec_of(c.n, c.dim, c.phi, 700 + 10 * c.law + c.dim);
    s.lattice = c.phi >= 0.3;
    s.polydisperse = !s.lattice;
    Reference ref = make_system(s, law_of(c.law));
    const double mft = mean_free_time(ref);
    ref.tc = 1e-3 * mft;
    SCOPED_TRACE("dim " + std::to_string(c.dim) + " phi " + std::to_string(c.phi));
    // (windows of two mft, every velocity turned in the middle of each; prefetching from no
    // system and from every one)
    CoreRun without(ref, 1000000, c.neighbours, 0.0, true, 1L << 40), with(ref, 1000000, c.neighbours, 0.0, true, 0);
    without.run_turning(12.0 * mft, 2.0 * mft);
    with.run_turning(12.0 * mft, 2.0 * mft);
    ASSERT_GE(without.total.collisions, 4L * c.n);
    EXPECT_EQ(with.total.collisions, without.total.collisions);
    EXPECT_EQ(with.total.crossings, without.total.crossings);
    EXPECT_EQ(states_differing(with, without), 0) << "particles whose state differs in some bit";
  }
}
