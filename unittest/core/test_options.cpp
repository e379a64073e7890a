// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// Core tests of the options' one field list (EDOptions::each_field): a change of any field that
// defines the configuration, a wall's or a law's field included, makes another configuration
// (EventDriven::same_configuration), a change of a tuning field does not, and the description
// (EDOptions::describe) names every field and tells every change apart.
#include "event_driven.h"

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

using namespace granfric;

namespace {

// a walled 3d box with two particle types
EDOptions walled_box()
{
  EDOptions o;
  o.periodic[1] = false;
  EDWall w;
  w.laws.assign(3, LawParams::rough(0.9, 0.2));
  o.walls = {w};
  w.side = 1;
  w.pos = 1.0;
  o.walls.push_back(w);
  return o;
}

const std::vector<LawParams> LAWS(9, LawParams::walton(0.8, 0.3, 0.4));

}    // namespace

TEST(Options, EveryDefiningFieldChangesTheConfiguration)
{
  const EDOptions a = walled_box();
  ASSERT_TRUE(EventDriven::same_configuration(a, 2, LAWS, a, 2, LAWS));
  const std::vector<std::function<void(EDOptions &)>> defining = {
      [](EDOptions &o) { o.dim = 2; },
      [](EDOptions &o) { o.lo[2] = -1.0; },
      [](EDOptions &o) { o.hi[0] = 2.0; },
      [](EDOptions &o) { o.periodic[2] = false; },
      [](EDOptions &o) { o.open[1] = true; },
      [](EDOptions &o) { o.period[1] = 3.0; },
      [](EDOptions &o) { o.gravity.y = -1.0; },
      [](EDOptions &o) { o.tc = 1e-4; },
      [](EDOptions &o) { o.max_collisions = 10; },
      [](EDOptions &o) { o.gamma_bins = 8; },
      [](EDOptions &o) { o.walls.pop_back(); },
      [](EDOptions &o) { o.walls[1].dim = 0; },
      [](EDOptions &o) { o.walls[1].side = -1; },
      [](EDOptions &o) { o.walls[0].pos = 0.1; },
      [](EDOptions &o) { o.walls[0].laws[2].r = 0.5; },
      [](EDOptions &o) { o.walls[0].laws[1].kind = LawKind::JZ; },
      [](EDOptions &o) { o.walls[0].laws[1].rt_max = 0.3; },
      [](EDOptions &o) { o.walls[0].laws[1].mu_s = 0.3; },
      [](EDOptions &o) { o.walls[0].laws[1].mu_d = 0.3; },
      [](EDOptions &o) { o.walls[0].T = 1.0; },
      [](EDOptions &o) { o.walls[0].seed = 7; },
      [](EDOptions &o) { o.walls[0].A = 0.01; },
      [](EDOptions &o) { o.walls[0].omega = 3.0; },
      [](EDOptions &o) { o.walls[0].sine = true; },
      [](EDOptions &o) { o.shape = {0.0, 0.4, 0.5}; },
      [](EDOptions &o) { o.cell_width = 1.5; },
      [](EDOptions &o) { o.neighbours = EDOptions::CELLS; },
      [](EDOptions &o) { o.list_skin = 0.2; },
      [](EDOptions &o) { o.shear_band = 4; },
  };
  std::vector<std::string> seen = {a.describe()};
  for (size_t k = 0; k < defining.size(); k++) {
    EDOptions b = a;
    defining[k](b);
    EXPECT_FALSE(EventDriven::same_configuration(a, 2, LAWS, b, 2, LAWS)) << "change " << k;
    EXPECT_FALSE(EventDriven::same_configuration(b, 2, LAWS, a, 2, LAWS)) << "change " << k;
    for (const std::string &d : seen) EXPECT_NE(b.describe(), d) << "change " << k;
    seen.push_back(b.describe());
  }
  // the laws between particles and their number of types are part of the configuration too
  std::vector<LawParams> other = LAWS;
  other[4].mu_d = 0.5;
  EXPECT_FALSE(EventDriven::same_configuration(a, 2, LAWS, a, 2, other));
  EXPECT_FALSE(EventDriven::same_configuration(a, 2, LAWS, a, 1, std::vector<LawParams>(4)));
}

TEST(Options, TuningFieldsAndTheDefaultShapeKeepTheConfiguration)
{
  const EDOptions a = walled_box();
  EDOptions b = a;
  b.simd = !a.simd;
  b.prefetch_bytes = 0;
  b.tick_last = 100;
  EXPECT_TRUE(EventDriven::same_configuration(a, 2, LAWS, b, 2, LAWS));
  EXPECT_NE(a.describe(), b.describe());
  b = a;
  b.shape = {0.4, 0.4, 0.4};    // (what no shape table means)
  EXPECT_TRUE(EventDriven::same_configuration(a, 2, LAWS, b, 2, LAWS));
}

TEST(Options, DescriptionNamesEveryField)
{
  const std::string d = walled_box().describe();
  for (const char *name : {"dim ", "lo (0 0 0)", "hi (1 1 1)", "periodic (true false true)", "open ",
                           "period ", "gravity (0 0 0)", "tc 0", "max_collisions 1000000", "max_crossings 10000",
                           "gamma_bins ", "walls [{dim 1, side -1, pos 0, laws [{kind 0, r 0.90000000000000002",
                           "shape []", "cell_width ", "neighbours 0", "list_skin ", "simd true",
                           "prefetch_bytes ", "tick_last 4294967294", "shear_band 0"})
    EXPECT_NE(d.find(name), std::string::npos) << name << " not in " << d;
}
