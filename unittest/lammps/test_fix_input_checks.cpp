// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// What fix hardsphere/ed and its companions refuse at the start of a run (timestep, overlaps,
// walls, box, kick rates), the consistency of its collision counts with walls, and run_style
// respa giving the verlet trajectory.
#include "lammps_fixture.h"

#include "atom.h"
#include "fix.h"
#include "modify.h"

#include <cmath>
#include <string>

using namespace granfric_test;

namespace {

// two discs of diameter 1 in a periodic 10 x 10 box, atom 2 at x2
std::string pair_of_discs(const std::string &x2)
{
  return "units lj\ndimension 2\natom_style sphere\ncomm_modify vel yes\n"
         "region box block 0 10 0 10 -0.5 0.5\ncreate_box 1 box\n"
         "create_atoms 1 single 2.0 2.0 0.0\ncreate_atoms 1 single " + x2 + " 2.0 0.0\n"
         "create_atoms 1 single 6.0 6.0 0.0\nset type 1 diameter 1.0\nset type 1 mass 1.0\n"
         "pair_style hardsphere/rough inertia disc\npair_coeff * * 1.0 -1.0\n"
         "timestep 0.1\nthermo 0\n";
}

// one disc of diameter 1 at (5, y) in a 10 x 20 box, closed in y (walls still to be defined)
std::string ball(const std::string &y)
{
  return "units lj\ndimension 2\natom_style sphere\nboundary p f p\ncomm_modify vel yes\n"
         "region box block 0 10 0 20 -0.5 0.5\ncreate_box 1 box\ncreate_atoms 1 single 5 " + y +
         " 0\nset type 1 diameter 1.0\nset type 1 mass 1.0\n"
         "pair_style hardsphere/walton inertia disc\npair_coeff * * 0.8 0.1 0.3\n"
         "timestep 0.5\nthermo 0\n";
}

// a fresh instance that runs setup, then fails at the commands last with an error matching re
std::unique_ptr<LAMMPS_NS::LAMMPS> fails_at(const std::string &setup, const std::string &last,
                                            const std::string &re)
{
  auto lmp = make_lammps();
  run(lmp.get(), setup);
  EXPECT_LMP_ERROR(lmp.get(), last, re);
  return lmp;
}

TEST(InputChecks, TimestepMustBePositive)
{
  auto lmp = fails_at(pair_of_discs("3.5") + "fix ed all hardsphere/ed",
                      "timestep 0.0\nrun 1 post no",
                      "^ERROR: Fix hardsphere/ed requires a positive timestep \\(timestep = 0\\)");
  EXPECT_LMP_ERROR(lmp.get(), "timestep -0.1\nrun 1 post no",
                   "requires a positive timestep \\(timestep = -0.1\\)");
  const double x = lmp->atom->x[0][0];
  EXPECT_EQ(error_of(lmp.get(), "timestep 0.1\nvelocity all set 1.0 0.0 0.0\nrun 1 post no"), "");
  EXPECT_NEAR(lmp->atom->x[0][0], x + 0.1, 1e-12) << "a positive step moves atoms forward";
}

// overlapping atoms (and coincident ones) stop the run with the pair, the depth and how to
// remove them; overlap allow turns that into a warning
TEST(InputChecks, OverlapsAreAnErrorUnlessAllowed)
{
  auto lmp = fails_at(pair_of_discs("2.7") + "fix ed all hardsphere/ed", "run 2 post no",
                      "^ERROR: Fix hardsphere/ed: atoms 1 and 2 overlap by 0.3 at the start of "
                      "the run \\(1 overlapping pairs in all\\). Remove them with delete_atoms "
                      "overlap, create atoms with create_atoms ... overlap \\(or fix deposit ... "
                      "near\\), or .* overlap allow");
  EXPECT_EQ(error_of(lmp.get(), "delete_atoms overlap 1.0 all all\nrun 2 post no"), "")
      << "the remedy the error names works";
  lmp.reset();
  fails_at(pair_of_discs("2.0") + "fix ed all hardsphere/ed", "run 2 post no",
           "atoms 1 and 2 overlap by 1 at the start");
  const std::string out = screen_of(pair_of_discs("2.7") + "fix ed all hardsphere/ed overlap allow\n"
                                                           "run 2 post no");
  EXPECT_NE(out.find("WARNING: Fix hardsphere/ed: 1 pairs of atoms overlap at the start of the "
                     "run (deepest: atoms 1 and 2 by 0.3)"),
            std::string::npos)
      << out;
  EXPECT_EQ(out.find("ERROR"), std::string::npos) << out;
  EXPECT_EQ(screen_of(pair_of_discs("3.2") + "fix ed all hardsphere/ed\nrun 2 post no")
                .find("overlap"),
            std::string::npos)
      << "no overlap, no message";
}

// atoms added during a run (fix deposit without near, into a region around an atom) are checked
// for overlaps too, and the message says when they were added
TEST(InputChecks, OverlapsOfAtomsAddedDuringTheRun)
{
  auto lmp = make_lammps();
  run(lmp.get(), "units lj\natom_style sphere\ncomm_modify vel yes\n"
                 "region box block 0 10 0 10 0 10\ncreate_box 1 box\n"
                 "create_atoms 1 single 5 5 5\nset group all diameter 1.0\nset group all mass 1.0\n"
                 "pair_style hardsphere/rough\npair_coeff * * 0.9 0.0\nfix ed all hardsphere/ed\n"
                 "timestep 0.1\nthermo 0\nrun 2 post no\n"
                 "region ins block 4.9 5.1 4.9 5.1 4.9 5.1 units box\n");
  EXPECT_LMP_ERROR(lmp.get(), "fix dep all deposit 1 1 1 4711 region ins\nrun 3 post no",
                   "^ERROR: Fix hardsphere/ed: atoms 1 and 2 overlap by .* after atoms were added at "
                   "step 3 \\(1 overlapping pairs in all\\)");
}

// fixes that act through forces, and pair exclusions, change nothing for hard particles: a
// warning names each (fix enforce2d, which keeps discs in the plane, is not warned about);
// without them, no warning
TEST(InputChecks, ForceFixesAndExclusionsWarned)
{
  const std::string out = screen_of(pair_of_discs("3.5") + "fix ed all hardsphere/ed\n"
                                    "fix v all viscous 0.5\nfix a all addforce 1.0 0.0 0.0\n"
                                    "fix e all enforce2d\nneigh_modify exclude type 1 1\nrun 1 post no");
  EXPECT_NE(out.find("WARNING: Fix v (viscous) acts through forces, which the hard particles of fix "
                     "hardsphere/ed ed do not feel"), std::string::npos) << out;
  EXPECT_NE(out.find("WARNING: Fix a (addforce) acts through forces"), std::string::npos) << out;
  EXPECT_EQ(out.find("Fix e (enforce2d)"), std::string::npos) << out;
  EXPECT_NE(out.find("WARNING: neigh_modify exclude has no effect on fix hardsphere/ed ed"),
            std::string::npos) << out;
  EXPECT_EQ(screen_of(pair_of_discs("3.5") + "fix ed all hardsphere/ed\nrun 1 post no").find("WARNING"),
            std::string::npos);
}

// atoms that cross a tenth of maxcross cells each in a step are warned about, once in a run
// (their speeds could be running away; the cap would stop the run); slower ones not (100 discs
// at fraction 0.3, cells about a diameter wide, steps of 0.1: at T = 1e4 a disc crosses about
// 13 cells per step, at T = 1 about 0.1)
TEST(InputChecks, FastAtomsWarned)
{
  const std::string warning = "WARNING: Fix hardsphere/ed ed: in step ";
  auto gas = [](const std::string &T) {
    return "units lj\ndimension 2\natom_style sphere\ncomm_modify vel yes\nlattice sq 0.3\n"
           "region box block 0 10 0 10 -0.5 0.5\ncreate_box 1 box\ncreate_atoms 1 box\n"
           "set type 1 diameter 1.0\nset type 1 mass 1.0\npair_style hardsphere/rough inertia disc\n"
           "pair_coeff * * 1.0 -1.0\ntimestep 0.1\nthermo 0\nvelocity all create " + T + " 4321 loop geom\n"
           "fix ed all hardsphere/ed maxcross 100\nrun 10 post no";
  };
  const std::string out = screen_of(gas("1e4"));
  const size_t at = out.find(warning);
  ASSERT_NE(at, std::string::npos) << out;
  EXPECT_NE(out.find("times each, a tenth or more of the crossing cap maxcross = 100:", at), std::string::npos) << out;
  EXPECT_EQ(out.find(warning, at + 1), std::string::npos) << "once in a run: " << out;
  EXPECT_EQ(screen_of(gas("1")).find("WARNING"), std::string::npos);
}

// a bed over a static, non-thermal floor under gravity with inelastic collisions and nothing
// feeding energy in settles without end: warned at the start of the first run (once for two
// runs); not with a thermal floor, a vibrating one, kicks, or elastic collisions
TEST(InputChecks, SettlingBedWarned)
{
  const std::string warning = "WARNING: Fix hardsphere/ed ed: nothing feeds energy into the grains over fix "
                              "hardsphere/wall floor (static, not thermal, under gravity toward it)";
  auto bed = [](const std::string &r, const std::string &floor, const std::string &more) {
    return "units lj\ndimension 2\natom_style sphere\nboundary p f p\ncomm_modify vel yes\n"
           "region box block 0 10 -0.5 10 -0.5 0.5 units box\ncreate_box 1 box\nlattice sq 0.25\n"
           "region inner block EDGE EDGE 0.7 9.3 EDGE EDGE units box\ncreate_atoms 1 region inner\n"
           "set type 1 diameter 1.0\nset type 1 mass 1.0\npair_style hardsphere/rough inertia disc\n"
           "pair_coeff * * " + r + " -1.0\ntimestep 0.1\nthermo 0\n"
           "fix ed all hardsphere/ed gravity 0 -1 0 tc 0.01\nfix floor all hardsphere/wall ylo 0.0" +
           floor + "\nfix lid all hardsphere/wall yhi EDGE\n" + more + "run 1 post no";
  };
  const std::string out = screen_of(bed("0.9", "", "") + "\nrun 1 post no");
  EXPECT_NE(out.find(warning), std::string::npos) << out;
  EXPECT_EQ(out.find(warning, out.find(warning) + 1), std::string::npos) << "once, not every run: " << out;
  EXPECT_NE(out.find("Loop time"), std::string::npos) << out;
  EXPECT_NE(out.find("the TC model slows that but does not stop it"), std::string::npos) << out;
  for (const auto &quiet : {bed("0.9", " thermal 0.01 5", ""), bed("0.9", " vibrate sine 0.1 5.0", ""),
                            bed("0.9", "", "fix k all hardsphere/kick 0.1 1.0 5\n"), bed("1.0", "", "")}) {
    const std::string o = screen_of(quiet);
    EXPECT_EQ(o.find("WARNING"), std::string::npos) << o;
    EXPECT_NE(o.find("Loop time"), std::string::npos) << o;
  }
}

// a ball that comes to rest on an inelastic floor with the TC model ends up bouncing elastically
// with a period of about t_c (0.04 here): 2500 collisions in a step of 100, past the warning's
// 1000 (a hundredth of maxevents = 1e5, but at least 1000); warned once. Not in steps of 1.
// (The start of the run warns of the settling itself: a static inelastic floor, no driving.)
TEST(InputChecks, PilingCollisionsWarned)
{
  const std::string warning = "WARNING: Fix hardsphere/ed ed: in step ";
  auto bounce = [](const std::string &dt) {
    return ball("3") + "fix ed all hardsphere/ed gravity 0 -1 0 tc 0.05 maxevents 100000\n"
                       "fix floor all hardsphere/wall ylo EDGE\ntimestep " + dt + "\nrun 3 post no";
  };
  const std::string out = screen_of(bounce("100"));
  const size_t at = out.find(warning);
  ASSERT_NE(at, std::string::npos) << out;
  EXPECT_NE(out.find("a hundredth or more of the collision cap maxevents = 100000: collisions are piling up", at),
            std::string::npos) << out;
  EXPECT_EQ(out.find(warning, at + 1), std::string::npos) << "once in a run: " << out;
  const std::string quiet = screen_of(bounce("1"));
  EXPECT_EQ(quiet.find(warning), std::string::npos) << quiet;
  EXPECT_NE(quiet.find("Loop time"), std::string::npos) << quiet;
}

TEST(InputChecks, OverlapKeywordValues)
{
  auto lmp = make_lammps();
  run(lmp.get(), pair_of_discs("3.5"));
  EXPECT_LMP_ERROR(lmp.get(), "fix ed all hardsphere/ed overlap maybe",
                   "overlap maybe is not available \\(allowed: error, allow\\)");
  EXPECT_LMP_ERROR(lmp.get(), "fix ed all hardsphere/ed overlap", "Illegal fix hardsphere/ed overlap");
  EXPECT_EQ(error_of(lmp.get(), "fix ed all hardsphere/ed overlap error\nrun 1 post no"), "");
}

TEST(InputChecks, CrossedWalls)
{
  auto lmp = fails_at(ball("8") + "fix ed all hardsphere/ed gravity 0 -1 0 tc 0.05\n"
                                   "fix lo all hardsphere/wall ylo 12\nfix hi all hardsphere/wall yhi 6",
                      "run 0",
                      "^ERROR: Fix hardsphere/wall lo \\(ylo at 12\\) is not below fix "
                      "hardsphere/wall hi \\(yhi at 6\\): the lower wall must lie below the "
                      "upper one");
  // a vibrating lower wall whose top reaches the upper wall
  run(lmp.get(), "unfix lo\nunfix hi\nfix lo all hardsphere/wall ylo 5 vibrate sine 1.5 2.0\n"
                 "fix hi all hardsphere/wall yhi 6");
  EXPECT_LMP_ERROR(lmp.get(), "run 0", "lo \\(ylo at 5 \\+ amplitude 1.5\\) is not below fix "
                                       "hardsphere/wall hi \\(yhi at 6\\)");
}

TEST(InputChecks, AtomsBehindAWall)
{
  auto lmp = fails_at(ball("0.3") + "fix ed all hardsphere/ed\nfix floor all hardsphere/wall ylo EDGE",
                      "run 0",
                      "^ERROR: Fix hardsphere/ed: atom 1 at \\(5, 0.3, 0\\) with radius 0.5 "
                      "reaches behind fix hardsphere/wall floor \\(ylo at 0\\)");
  run(lmp.get(), "set atom 1 y 0.5");
  EXPECT_EQ(error_of(lmp.get(), "run 1 post no"), "") << "touching the wall is allowed";
  run(lmp.get(), "set atom 1 y 15\nfix top all hardsphere/wall yhi 15.2");
  EXPECT_LMP_ERROR(lmp.get(), "run 0", "atom 1 at \\(5, 15, 0\\) with radius 0.5 reaches behind "
                                       "fix hardsphere/wall top \\(yhi at 15.2\\)");
}

TEST(InputChecks, DiameterLongerThanTheBox)
{
  fails_at(pair_of_discs("5.0") + "set atom 3 diameter 12\nfix ed all hardsphere/ed", "run 0",
           "^ERROR: Fix hardsphere/ed: atom 3 has diameter 12, longer than the box in x "
           "\\(10 from 0 to 10\\)");
}

TEST(InputChecks, KickRatesAreBounded)
{
  const std::string setup = pair_of_discs("3.5") + "fix ed all hardsphere/ed\n";
  auto lmp = fails_at(setup + "fix k all hardsphere/kick 1e300 0.1 5", "run 1 post no",
                      "^ERROR: Fix hardsphere/kick k: f_dr = 1e\\+300 gives 1e\\+299 kicks per "
                      "step of 0.1 \\(at most 1e\\+06 are allowed\\)");
  EXPECT_LMP_ERROR(lmp.get(), "fix k2 all hardsphere/kick 1 1e200 5",
                   "v_dr = 1e\\+200 is out of range \\(at most 1e\\+150");
  lmp.reset();
  // at time 2: kick index 2e15 at the end of a run
  fails_at(setup + "fix k all hardsphere/kick 1e15 0.1 5\ntimestep 1e-10\nreset_timestep 0 time 2.0",
           "run 20 post no",
           "f_dr = 1e\\+15 reaches kick index 2e\\+15 by the end of the run at time 2");
  // (the bound on atom kicks per step: in the catalogue of bad inputs)
}

// the counts of a ball bouncing on a rough floor until it rests: every collision is a wall
// collision, and no partial count exceeds its total
TEST(InputChecks, BouncingBallCountsAreConsistent)
{
  auto lmp = make_lammps();
  run(lmp.get(), ball("3") + "velocity all set 1.0 0.0 0.0\n"
                             "fix ed all hardsphere/ed gravity 0 -1 0 tc 0.05\n"
                             "fix floor all hardsphere/wall ylo EDGE\n"
                             "fix top all hardsphere/wall yhi EDGE");
  auto *ed = lmp->modify->get_fix_by_id("ed");
  auto energy = [&]() {
    const double *v = lmp->atom->v[0], w = lmp->atom->omega[0][2];
    return 0.5 * (v[0] * v[0] + v[1] * v[1]) + 0.5 * 0.5 * 0.25 * w * w + lmp->atom->x[0][1];
  };
  const double E0 = energy();
  double steps_sum = 0.0;
  for (int s = 0; s < 60; s++) {
    run(lmp.get(), "run 1 post no");
    steps_sum += ed->compute_vector(0);
    EXPECT_EQ(ed->compute_vector(4), ed->compute_vector(0)) << "one particle takes every collision";
  }
  const double total = ed->compute_vector(1), wall = ed->compute_vector(9);
  EXPECT_GT(total, 20.0);
  EXPECT_EQ(total, wall) << "a single ball collides with the walls only";
  EXPECT_EQ(steps_sum, total) << "the steps' counts add up to the total";
  EXPECT_GT(ed->compute_vector(6), 0.0) << "the ball comes to rest: TC-elastic collisions";
  EXPECT_LE(ed->compute_vector(6), total);
  EXPECT_GT(ed->compute_vector(3), 0.0) << "the first impacts slide (mu 0.1)";
  EXPECT_LE(ed->compute_vector(3), total);
  EXPECT_EQ(ed->compute_vector(7), 0.0) << "the Walton law creates no energy";
  EXPECT_NEAR(ed->compute_vector(2), -ed->compute_vector(10), 1e-12)
      << "all dissipation is at the walls";
  EXPECT_NEAR(E0 - energy(), ed->compute_vector(2), 1e-9) << "the energy books close";
}

// run_style respa runs the window once per outer step: the verlet trajectory
TEST(InputChecks, RespaMovesAtomsAsVerlet)
{
  const std::string setup = pair_of_discs("3.5") + "set atom 1 vx 1.0 vy 0.1\n"
                            "set atom 2 vx -1.0\nfix ed all hardsphere/ed\n";
  double x[3][3];
  {
    auto a = make_lammps();
    run(a.get(), setup + "run 50 post no");
    for (int i = 0; i < 3; i++)
      for (int d = 0; d < 3; d++) x[a->atom->tag[i] - 1][d] = a->atom->x[i][d];
  }
  auto b = make_lammps();
  run(b.get(), setup + "run_style respa 2 2\nrun 50 post no");
  EXPECT_GT(b->modify->get_fix_by_id("ed")->compute_vector(1), 0.0) << "the discs collided";
  for (int i = 0; i < 3; i++)
    for (int d = 0; d < 3; d++) EXPECT_EQ(b->atom->x[i][d], x[b->atom->tag[i] - 1][d]);
}

}    // namespace
