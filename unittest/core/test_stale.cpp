// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// Core tests of how stale predictions are recognised: each change of a trajectory advances one
// 32-bit clock, and a prediction is stale once its partner changed after it was made. When the
// clock nears its end it starts again from 1 with every prediction as stale or fresh as it was
// (EDCore::retick). Restarting it every few dozen changes must leave every trajectory the
// same bits as never restarting it, with cells and lists, walls and gravity, kicks (which mark every
// prediction stale) and the TC model, in 2d and 3d.
#include "ed_fixture.h"

#include <gtest/gtest.h>


using namespace granfric;
using namespace granfric_test;

TEST(StalePredictions, SameBitsWhenTheClockStartsAgain)
{
  struct C {
    int dim, law, n;
    double phi;
    int neighbours;
    bool walls;
  };
  const C cases[] = {{3, 0, 600, 0.05, EDOptions::CELLS, false}, {3, 1, 400, 0.25, EDOptions::CELLS, true},
                     {3, 0, 300, 0.45, EDOptions::LISTS, false}, {2, 2, 500, 0.30, EDOptions::CELLS, true}};
  for (const C &c : cases) {
    SystemSpec s = spec_of(c.n, c.dim, c.phi, 900 + 10 * c.law + c.dim);
    s.lattice = c.phi >= 0.3;
    s.polydisperse = !s.lattice;
    Reference ref = make_system(s, law_of(c.law));
    if (c.walls) {    // walls in y, half a diameter outside the particles' range, and gravity
      ref.periodic[1] = false;
      ref.gravity = Vec3(0.0, -0.4, 0.0);
      ref.walls.push_back({1, -1, ref.lo.y - 0.6, law_of((c.law + 1) % 3)});
      ref.walls.push_back({1, +1, ref.lo.y + ref.L.y + 0.6, law_of(c.law)});
    }
    const double mft = mean_free_time(ref);
    ref.tc = 1e-3 * mft;
    SCOPED_TRACE("dim " + std::to_string(c.dim) + " phi " + std::to_string(c.phi));
    // (windows of two mft, every velocity turned in the middle of each; the clock restarting
    // never, and every 37 changes)
    const long pb = EDOptions().prefetch_bytes;
    CoreRun never(ref, 1000000, c.neighbours, 0.0, true, pb, EDOptions().tick_last);
    CoreRun often(ref, 1000000, c.neighbours, 0.0, true, pb, 37);
    never.run_turning(16.0 * mft, 2.0 * mft);
    often.run_turning(16.0 * mft, 2.0 * mft);
    ASSERT_GE(never.total.collisions, 4L * c.n);
    EXPECT_EQ(often.total.collisions, never.total.collisions);
    EXPECT_EQ(often.total.crossings, never.total.crossings);
    EXPECT_EQ(states_differing(often, never), 0) << "particles whose state differs in some bit";
  }
}
