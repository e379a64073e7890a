// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// Every invalid input of the hardsphere/* pair styles gets an error that names what was wrong
// and what is allowed; kappa_d > kappa_s is accepted with a warning.
#include "lammps_fixture.h"

#include "force.h"
#include "pair.h"

using namespace granfric_test;

namespace {

const char *BOX3D = "units lj\natom_style sphere\ncomm_modify vel yes\n"
                    "region box block 0 4 0 4 0 4\ncreate_box 2 box\n"
                    "create_atoms 1 single 1 1 1\ncreate_atoms 2 single 2 2 2";
const char *BOX2D = "units lj\ndimension 2\natom_style sphere\ncomm_modify vel yes\n"
                    "region box block 0 4 0 4 -0.5 0.5\ncreate_box 2 box\n"
                    "create_atoms 1 single 1 1 0\ncreate_atoms 2 single 2 2 0";

class PairErrors : public ::testing::Test {
 protected:
  std::unique_ptr<LAMMPS_NS::LAMMPS> lmp;
  void SetUp() override
  {
    lmp = make_lammps();
    run(lmp.get(), BOX3D);
  }
};

TEST_F(PairErrors, RoughRanges)
{
  run(lmp.get(), "pair_style hardsphere/rough");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff 1 1 1.2 0.5", "r = 1.2 is out of range \\(0 <= r <= 1\\)");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff 1 1 -0.1 0.5", "r = -0.1 is out of range");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff 1 1 0.9 1.5",
                   "beta = 1.5 is out of range \\(-1 <= beta <= 1\\)");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff 1 1 0.9 -1.01", "beta = -1.01 is out of range");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff 1 1 0.9", "pair_coeff I J r beta for hardsphere/rough");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff 1 1 0.9 0.1 0.3", "pair_coeff I J r beta");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff 1 1 abc 0.1", "r = abc is not a number");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff 1 1 0.9 inf", "beta = inf is not a number");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff 1 3 0.9 0.1", "Numeric index 3 is out of bounds");
}

TEST_F(PairErrors, WaltonRanges)
{
  run(lmp.get(), "pair_style hardsphere/walton");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff * * 1.01 0.5 0.4", "r = 1.01 is out of range");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff * * 0.9 -0.5 0.4",
                   "mu = -0.5 is out of range \\(mu >= 0, or inf\\)");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff * * 0.9 0.5 1.4",
                   "rtmax = 1.4 is out of range \\(-1 <= rtmax <= 1\\)");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff * * 0.9 0.5 -1.4", "rtmax = -1.4 is out of range");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff * * 0.9 0.5", "pair_coeff I J r mu rtmax");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff * * 0.9 -inf 0.4", "mu = -inf is not a number");
  EXPECT_EQ(error_of(lmp.get(), "pair_coeff * * 0.9 inf 0.4"), "");
  EXPECT_EQ(error_of(lmp.get(), "pair_coeff * * 0.9 INF 0.4"), "");
}

TEST_F(PairErrors, JenkinsZhangRanges)
{
  run(lmp.get(), "pair_style hardsphere/jz");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff * * 0.6 0.1 0.3 0.3",
                   "qn = 0.6 is out of range \\(0 <= qn <= 0.5\\)");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff * * -0.1 0.1 0.3 0.3", "qn = -0.1 is out of range");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff * * 0.1 1.1 0.3 0.3",
                   "qt = 1.1 is out of range \\(0 <= qt <= 1\\)");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff * * 0.1 -0.1 0.3 0.3", "qt = -0.1 is out of range");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff * * 0.1 0.1 -0.3 0.3", "kappa_s = -0.3 is out of range");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff * * 0.1 0.1 0.3 -0.3", "kappa_d = -0.3 is out of range");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff * * 0.1 0.1 0.3 inf",
                   "kappa_d = inf needs kappa_s = inf");
  EXPECT_EQ(error_of(lmp.get(), "pair_coeff * * 0.1 0.1 inf inf"), "");
  EXPECT_LMP_ERROR(lmp.get(), "pair_coeff * * 0.1 0.1 0.3",
                   "pair_coeff I J qn qt kappa_s kappa_d");
}

TEST_F(PairErrors, JenkinsZhangDynamicAboveStaticWarns)
{
  lmp.reset();
  std::unique_ptr<LAMMPS_NS::LAMMPS> l;
  ::testing::internal::CaptureStdout();
  {
    // screen output is needed to see the warning
    std::vector<std::string> words = {"t", "-log", "none", "-nocite"};
    std::vector<char *> argv;
    for (auto &w : words) argv.push_back(w.data());
    l = std::make_unique<LAMMPS_NS::LAMMPS>((int) argv.size(), argv.data(), MPI_COMM_WORLD);
    run(l.get(), std::string("plugin load ") + GRANFRIC_PLUGIN);
    run(l.get(), BOX3D);
    run(l.get(), "pair_style hardsphere/jz\npair_coeff * * 0.1 0.1 0.2 0.3");
  }
  l.reset();
  const std::string out = ::testing::internal::GetCapturedStdout();
  EXPECT_NE(out.find("WARNING: Pair_coeff hardsphere/jz: kappa_d = 0.3 > kappa_s = 0.2"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("can create energy"), std::string::npos);
}

TEST_F(PairErrors, Settings)
{
  EXPECT_LMP_ERROR(lmp.get(), "pair_style hardsphere/rough inertia cube",
                   "inertia must be sphere, disc or a number 0 < q <= 1, not cube");
  EXPECT_LMP_ERROR(lmp.get(), "pair_style hardsphere/rough inertia 1.5",
                   "inertia q = I/\\(m a\\^2\\) = 1.5 is out of range \\(0 < q <= 1\\)");
  EXPECT_LMP_ERROR(lmp.get(), "pair_style hardsphere/rough inertia 0", "is out of range");
  EXPECT_LMP_ERROR(lmp.get(), "pair_style hardsphere/rough inertia", "Illegal pair_style inertia");
  EXPECT_LMP_ERROR(lmp.get(), "pair_style hardsphere/walton spin 1",
                   "Unknown pair style hardsphere/walton keyword: spin \\(allowed: inertia, inertia/type\\)");
}

TEST_F(PairErrors, DiscNeeds2d)
{
  run(lmp.get(), "pair_style hardsphere/jz inertia disc\npair_coeff * * 0.1 0.1 0.2 0.2");
  EXPECT_LMP_ERROR(lmp.get(), "run 0", "inertia disc requires a 2d simulation");
}

TEST_F(PairErrors, MissingCoefficients)
{
  run(lmp.get(), "pair_style hardsphere/rough\npair_coeff 1 1 0.9 0.0");
  EXPECT_LMP_ERROR(lmp.get(), "run 0", "All pair coeffs are not set");
}

TEST_F(PairErrors, GhostVelocity)
{
  run(lmp.get(), "comm_modify vel no\npair_style hardsphere/rough\npair_coeff * * 0.9 0.0");
  EXPECT_LMP_ERROR(lmp.get(), "run 0", "requires ghost atoms to store velocity: use comm_modify vel yes");
}

TEST(PairErrorsAtomStyle, WrongAtomStyle)
{
  auto lmp = make_lammps();
  run(lmp.get(), "units lj\natom_style atomic\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\n"
                 "create_atoms 1 single 1 1 1\nmass 1 1.0\ncomm_modify vel yes\n"
                 "pair_style hardsphere/walton\npair_coeff * * 0.9 0.5 0.4");
  EXPECT_LMP_ERROR(lmp.get(), "run 0",
                   "requires per-atom radius, mass and angular velocity \\(atom_style sphere\\)");
}

TEST(PairValid, TwoDimensionalDiscAndMixing)
{
  auto lmp = make_lammps();
  run(lmp.get(), BOX2D);
  run(lmp.get(), "pair_style hardsphere/walton inertia disc\n"
                 "pair_coeff 1 1 0.9 0.5 0.4\npair_coeff 2 2 0.7 inf -0.2\nrun 0 post no");
  auto *p = lmp->force->pair;
  int dim;
  EXPECT_DOUBLE_EQ(*(double *) p->extract("inertia", dim), 0.5);
}

}    // namespace
