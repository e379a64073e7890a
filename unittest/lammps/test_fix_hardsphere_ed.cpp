// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// fix hardsphere/ed through LAMMPS: whole trajectories equal to the brute-force reference
// (2D and 3D, every law, short and long steps), restart continuity, the TC model against the
// event cap in a collapsing system, and every invalid keyword or combination.
#include "lammps_fixture.h"

#include "atom.h"
#include "compute.h"
#include "domain.h"
#include "fix.h"
#include "force.h"
#include "modify.h"
#include "neighbor.h"
#include "pair.h"
#include "update.h"

#include "reference_ed.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <string>

using namespace granfric_test;
using granfric::Vec3;

namespace {

// a random gas of two sizes (diameters 0.8 and 1.2), no overlaps, zero total momentum
std::string gas(int dim, int n, double side, unsigned seed)
{
  std::string s = "units lj\natom_style sphere\nboundary p p p\ncomm_modify vel yes\n";
  if (dim == 2)
    s += "dimension 2\nregion box block 0 " + std::to_string(side) + " 0 " + std::to_string(side) +
        " -0.5 0.5\n";
  else
    s += "region box block 0 " + std::to_string(side) + " 0 " + std::to_string(side) + " 0 " +
        std::to_string(side) + "\n";
  s += "create_box 2 box\n";
  s += "create_atoms 1 random " + std::to_string(n) + " " + std::to_string(seed) +
      " NULL overlap 1.25 maxtry 10000\n";
  s += "set type 1 type/fraction 2 0.5 " + std::to_string(seed + 1) + "\n";
  s += "set type 1 diameter 0.8\nset type 2 diameter 1.2\n";
  s += "set type 1 density 1.0\nset type 2 density 1.5\n";
  s += "velocity all create 1.0 " + std::to_string(seed + 2) + " loop geom mom yes\n";
  if (dim == 2)
    s += "variable wz atom 0.9*sin(2.1*x+1.3*y)\nset group all omega 0.0 0.0 v_wz\n";
  else
    s += "variable wx atom 0.5*sin(2.3*x+1.1*z)\nvariable wy atom 0.5*cos(1.9*y+0.7*z)\n"
         "variable wz atom 0.5*sin(3.1*x+1.7*y+1)\nset group all omega v_wx v_wy v_wz\n";
  return s;
}

// the LAMMPS system as a brute-force Reference (positions unwrapped with image flags)
// a 2D gas as gas() makes it, with the y boundary yb ("f": walls at both box faces, "m": a
// floor only) and every atom at least 0.6 from y = 0 and y = side
std::string walled_gas(int n, double side, unsigned seed, const std::string &yb)
{
  std::string s = gas(2, n, side, seed);
  s.replace(s.find("boundary p p p"), 14, "boundary p " + yb + " p");
  s.replace(s.find("NULL overlap"), 4, "inner");
  s.replace(s.find("create_atoms"), 0, "region inner block EDGE EDGE 0.6 " +
            std::to_string(side - 0.6) + " EDGE EDGE\n");
  return s;
}

// walled_gas() with the Walton law, gravity toward the floor, the TC model and walls at both faces
std::string walled_bed(unsigned seed)
{
  return walled_gas(120, 20.0, seed, "f") +
      "pair_style hardsphere/walton inertia disc\npair_coeff * * 0.8 0.3 0.4\n"
      "fix ed all hardsphere/ed gravity 0.0 -0.3 0.0 tc 0.01\n"
      "fix floor all hardsphere/wall ylo EDGE\nfix top all hardsphere/wall yhi EDGE\n";
}

Reference reference_of(LAMMPS_NS::LAMMPS *lmp)
{
  Reference ref;
  auto *atom = lmp->atom;
  auto *domain = lmp->domain;
  // the pair style lives in the plugin: reach its laws and q through Pair::extract
  int dim;
  auto **laws = (granfric::LawParams **) lmp->force->pair->extract("hardsphere_laws", dim);
  const double q = *(double *) lmp->force->pair->extract("inertia", dim);
  ref.dim = domain->dimension;
  ref.lo = Vec3(domain->boxlo[0], domain->boxlo[1], domain->boxlo[2]);
  ref.L = Vec3(domain->prd[0], domain->prd[1], domain->prd[2]);
  ref.ntypes = atom->ntypes;
  ref.laws.resize((ref.ntypes + 1) * (ref.ntypes + 1));
  for (int i = 1; i <= ref.ntypes; i++)
    for (int j = 1; j <= ref.ntypes; j++) ref.laws[i * (ref.ntypes + 1) + j] = laws[i][j];
  ref.p.resize(atom->natoms);
  for (int i = 0; i < atom->nlocal; i++) {
    RefParticle &p = ref.p[atom->tag[i] - 1];
    double xu[3];
    domain->unmap(atom->x[i], atom->image[i], xu);
    p.x = Vec3::from(xu);
    p.v = Vec3::from(atom->v[i]);
    p.w = Vec3::from(atom->omega[i]);
    p.a = atom->radius[i];
    p.m = atom->rmass[i];
    p.q = q;
    p.type = atom->type[i];
  }
  return ref;
}

double max_deviation(LAMMPS_NS::LAMMPS *lmp, const Reference &ref)
{
  auto *atom = lmp->atom;
  double worst = 0.0;
  for (int i = 0; i < atom->nlocal; i++) {
    const RefParticle &p = ref.p[atom->tag[i] - 1];
    double xu[3];
    lmp->domain->unmap(atom->x[i], atom->image[i], xu);
    worst = std::max({worst, norm(Vec3::from(xu) - p.x), norm(Vec3::from(atom->v[i]) - p.v),
                      p.a * norm(Vec3::from(atom->omega[i]) - p.w)});
  }
  return worst;
}

struct TrajCase {
  int dim;
  const char *pair;
  const char *coeffs;
  double dt;
  int steps;
  const char *fixargs;
};

class FixTrajectory : public ::testing::TestWithParam<TrajCase> {};

std::string traj_name(const ::testing::TestParamInfo<TrajCase> &info)
{
  std::string law = std::string(info.param.pair).substr(11);    // after "hardsphere/"
  law = law.substr(0, law.find(' '));
  return law + "_" + std::to_string(info.param.dim) + "d_" + std::to_string(info.param.steps) +
      "steps";
}

TEST_P(FixTrajectory, EqualsBruteForceReference)
{
  const TrajCase c = GetParam();
  auto lmp = make_lammps();
  run(lmp.get(), gas(c.dim, c.dim == 2 ? 150 : 120, c.dim == 2 ? 22.0 : 9.0, 4711));
  run(lmp.get(), std::string("pair_style ") + c.pair + "\n" + c.coeffs);
  run(lmp.get(), std::string("fix ed all hardsphere/ed ") + c.fixargs + "\ntimestep " +
                     std::to_string(c.dt) + "\nthermo 0\nrun 0 post no");
  Reference ref = reference_of(lmp.get());
  auto *fix = lmp->modify->get_fix_by_id("ed");
  if (std::string(c.fixargs).find("gravity") != std::string::npos) {
    double g[3];
    std::sscanf(std::strstr(c.fixargs, "gravity"), "gravity %lf %lf %lf", &g[0], &g[1], &g[2]);
    ref.gravity = Vec3(g[0], g[1], g[2]);
  }
  if (std::string(c.fixargs).find("tc") != std::string::npos)
    std::sscanf(std::strstr(c.fixargs, "tc"), "tc %lf", &ref.tc);
  run(lmp.get(), "run " + std::to_string(c.steps) + " post no");
  ref.run_until(c.dt * c.steps);
  const long ncoll = (long) fix->compute_vector(1);
  EXPECT_GT(ncoll, (long) ref.p.size()) << "several collisions per particle";
  EXPECT_EQ(ncoll, ref.collisions);
  EXPECT_NEAR(fix->compute_vector(2), -ref.dE, 1e-9 * std::fabs(ref.dE));
  EXPECT_LT(max_deviation(lmp.get(), ref), 1e-9);
}

INSTANTIATE_TEST_SUITE_P(
    Lammps, FixTrajectory,
    ::testing::Values(
        TrajCase{2, "hardsphere/rough inertia disc", "pair_coeff * * 0.9 0.3", 0.05, 60, ""},
        TrajCase{2, "hardsphere/walton", "pair_coeff * * 0.95 0.3 0.4\npair_coeff 1 2 0.8 inf 0.2", 2.0, 2, ""},
        TrajCase{2, "hardsphere/jz inertia disc", "pair_coeff * * 0.05 0.05 0.3 0.3", 0.01, 300,
                 "gravity 0.1 -0.3 0.0"},
        TrajCase{3, "hardsphere/rough", "pair_coeff * * 0.8 -0.2", 0.3, 10, "tc 0.01"},
        TrajCase{3, "hardsphere/walton inertia 0.35", "pair_coeff * * 0.9 0.2 0.5", 0.02, 120,
                 "gravity 0.0 0.0 -0.5"},
        TrajCase{3, "hardsphere/jz", "pair_coeff * * 0.1 0.2 0.5 0.4", 4.0, 1, ""}),
    traj_name);

// The fix's virial, step by step (sum over the step's collisions of r (x) dP, divided by the
// step), summed over the run equals the brute-force reference's sum over its collisions; LAMMPS's
// compute pressure takes it (kinetic part plus virial trace / (d V)), and fix_modify virial no
// leaves it out.
TEST(FixHardsphereED, VirialIsTheCollisionsAndEntersThePressure)
{
  for (int dim = 2; dim <= 3; dim++) {
    auto lmp = make_lammps();
    run(lmp.get(), gas(dim, dim == 2 ? 150 : 120, dim == 2 ? 22.0 : 9.0, 4711));
    run(lmp.get(), "pair_style hardsphere/walton\npair_coeff * * 0.9 0.3 0.4\n"
                   "fix ed all hardsphere/ed\ntimestep 0.1\nthermo 0\nrun 0 post no");
    Reference ref = reference_of(lmp.get());
    auto *fix = lmp->modify->get_fix_by_id("ed");
    auto *press = lmp->modify->get_compute_by_id("thermo_press");
    auto *temp = lmp->modify->get_compute_by_id("thermo_temp");
    double sum[6] = {0, 0, 0, 0, 0, 0};
    const int steps = 30;
    for (int s = 0; s < steps; s++) {
      run(lmp.get(), "run 1 pre no post no");
      for (int k = 0; k < 6; k++) sum[k] += fix->virial[k] * 0.1;
      // LAMMPS's pressure: (dof T + virial trace) / (d V), with the fix's virial in it
      const double vol = lmp->domain->xprd * lmp->domain->yprd * (dim == 3 ? lmp->domain->zprd : 1.0);
      const double kin = temp->compute_scalar() * temp->dof;
      const double tr = fix->virial[0] + fix->virial[1] + (dim == 3 ? fix->virial[2] : 0.0);
      EXPECT_NEAR(press->compute_scalar(), (kin + tr) / (dim * vol), 1e-10 * (kin + std::fabs(tr)) / vol);
    }
    ref.run_until(0.1 * steps);
    ASSERT_GT(ref.collisions, (long) ref.p.size());
    const double scale = std::fabs(ref.virial[0]) + std::fabs(ref.virial[1]) + std::fabs(ref.virial[2]);
    for (int k = 0; k < 6; k++) EXPECT_NEAR(sum[k], ref.virial[k], 1e-9 * scale) << dim << "D, component " << k;
    EXPECT_GT(ref.virial[0] + ref.virial[1], 0.0);
    run(lmp.get(), "fix_modify ed virial no\nrun 1 post no");    // (pre yes: compute pressure re-initialised)
    const double vol = lmp->domain->xprd * lmp->domain->yprd * (dim == 3 ? lmp->domain->zprd : 1.0);
    EXPECT_NEAR(press->compute_scalar(), temp->compute_scalar() * temp->dof / (dim * vol), 1e-12)
        << "fix_modify virial no: the kinetic pressure only";
  }
}

// The equation of state of elastic hard spheres and discs from LAMMPS's own pressure (kinetic
// plus the fix's collision virial), averaged over 200 mean free times of N ~ 4000 after 20 of
// equilibration, against Carnahan-Starling (3D: Z = (1 + p + p^2 - p^3) / (1 - p)^3) and
// Henderson (2D: Z = (1 + p^2 / 8) / (1 - p)^2), both within 0.5 % of simulations at these
// fractions; Z = P V / (N T) with T from the kinetic energy (conserved).
TEST(FixHardsphereED, PressureFollowsTheEquationOfState)
{
  struct EOS {
    int dim;
    double phi;
  };
  for (const EOS c : {EOS{3, 0.25}, EOS{3, 0.40}, EOS{2, 0.30}}) {
    const double p = c.phi;
    const double z_eos = c.dim == 3 ? (1 + p + p * p - p * p * p) / std::pow(1 - p, 3)
                                    : (1 + p * p / 8) / ((1 - p) * (1 - p));
    const double rho = c.dim == 3 ? 6.0 * p / M_PI : 4.0 * p / M_PI;
    const double g = c.dim == 3 ? (1 - p / 2) / std::pow(1 - p, 3) : (1 - 7 * p / 16) / ((1 - p) * (1 - p));
    const double mft = 1.0 / ((c.dim == 3 ? 4.0 : 2.0) * rho * g * std::sqrt(M_PI));
    auto lmp = make_lammps();
    const std::string box = c.dim == 3 ? "lattice fcc " + std::to_string(rho) +
            "\nregion box block 0 10 0 10 0 10\n"
                                       : "lattice sq " + std::to_string(rho) +
            "\nregion box block 0 64 0 64 -0.5 0.5\n";
    run(lmp.get(), "units lj\ndimension " + std::to_string(c.dim) +
                       "\natom_style sphere\nboundary p p p\ncomm_modify vel yes\n" + box +
                       "create_box 1 box\ncreate_atoms 1 box\nset type 1 diameter 1.0\n"
                       "set type 1 mass 1.0\nvelocity all create 1.0 4321 loop geom mom yes dist gaussian\n"
                       "pair_style hardsphere/rough" + std::string(c.dim == 2 ? " inertia disc" : "") +
                       "\npair_coeff * * 1.0 -1.0\nfix ed all hardsphere/ed\ntimestep " +
                       std::to_string(mft) + "\nthermo 0\nrun 20 post no\nreset_timestep 0\n"
                       "compute ke all ke\nfix p all ave/time 1 200 200 c_thermo_press\nrun 200 post no");
    const double P = lmp->modify->get_fix_by_id("p")->compute_scalar();
    const double ke = lmp->modify->get_compute_by_id("ke")->compute_scalar();
    const double n = (double) lmp->atom->natoms;
    const double vol = lmp->domain->xprd * lmp->domain->yprd * (c.dim == 3 ? lmp->domain->zprd : 1.0);
    const double z = P * vol / (2.0 * ke / c.dim);    // (N T = 2 KE / d)
    EXPECT_NEAR(z / z_eos, 1.0, 0.01) << c.dim << "D, fraction " << p << ": Z = " << z
                                      << ", equation of state " << z_eos << " (N = " << n << ")";
  }
}

// compute hardsphere/collisions/local: one row per collision of the last step (pairs and walls),
// as many as the fix counts, the energy changes add up to the fix's dissipation; a head-on
// collision of two equal spheres has the impact angle pi, no tangential speed, the normal impulse
// m_n (1 + r) |g_n| and the energy change -m_n (1 - r^2) g_n^2 / 2; the group selects rows.
TEST(ComputeCollisionsLocal, RowsAreTheStepsCollisions)
{
  auto lmp = make_lammps();
  run(lmp.get(), walled_bed(33) + "compute cl all hardsphere/collisions/local ed\ngroup half id <= 60\n"
                     "compute ch half hardsphere/collisions/local ed\ntimestep 0.2\nthermo 0\n"
                     "run 0 post no");
  auto *ed = lmp->modify->get_fix_by_id("ed");
  auto *cl = lmp->modify->get_compute_by_id("cl"), *ch = lmp->modify->get_compute_by_id("ch");
  long walls = 0;
  for (int step = 0; step < 30; step++) {
    const double lost0 = ed->compute_vector(2);
    run(lmp.get(), "run 1 post no");
    cl->compute_local();
    ch->compute_local();
    ASSERT_EQ(cl->size_local_rows, (int) ed->compute_vector(0)) << "step " << step;
    double dE = 0.0;
    int half = 0;
    for (int r = 0; r < cl->size_local_rows; r++) {
      const double *a = cl->array_local[r];
      dE += a[9];
      walls += a[3] > 0;
      EXPECT_EQ(a[3] > 0, a[2] == 0.0) << "a wall row has no second atom";
      EXPECT_GT(a[4], 0.0) << "approaching";
      EXPECT_TRUE(a[6] > M_PI / 2 && a[6] <= M_PI);
      half += a[1] <= 60 || (a[2] > 0 && a[2] <= 60);
    }
    EXPECT_NEAR(dE, -(ed->compute_vector(2) - lost0), 1e-9 * (1.0 + std::fabs(dE)));
    EXPECT_EQ(ch->size_local_rows, half) << "rows with an atom of the group";
  }
  EXPECT_GT(walls, 10);
  lmp.reset();    // (one LAMMPS instance at a time: the plugin is registered with one only)

  auto two = make_lammps();
  run(two.get(), "units lj\ndimension 3\natom_style sphere\nboundary p p p\ncomm_modify vel yes\n"
                 "region box block 0 10 0 10 0 10\ncreate_box 1 box\ncreate_atoms 1 single 2 5 5\n"
                 "create_atoms 1 single 6 5 5\nset type 1 diameter 1.0\nset type 1 mass 1.0\n"
                 "velocity all set 0 0 0\nset atom 1 vx 1.5\nset atom 2 vx -0.5\n"
                 "pair_style hardsphere/rough\npair_coeff * * 0.7 0.4\nfix ed all hardsphere/ed\n"
                 "compute cl all hardsphere/collisions/local ed\ntimestep 2.0\nthermo 0\nrun 1 post no");
  auto *c2 = two->modify->get_compute_by_id("cl");
  c2->compute_local();
  ASSERT_EQ(c2->size_local_rows, 1);
  const double *a = c2->array_local[0];
  EXPECT_NEAR(a[0], 1.5, 1e-12) << "gap 3 closed at relative speed 2";
  EXPECT_EQ(a[1] + a[2], 3.0);
  EXPECT_NEAR(a[4], 2.0, 1e-12);
  EXPECT_NEAR(a[5], 0.0, 1e-12);
  EXPECT_NEAR(a[6], M_PI, 1e-7);
  EXPECT_NEAR(a[8], 0.5 * 1.7 * 2.0, 1e-12);
  EXPECT_NEAR(a[9], -0.5 * 0.5 * (1 - 0.49) * 4.0, 1e-12);
}

// Per-atom virials and compute hardsphere/atom, step by step with walls: compute stress/atom
// (virial part) summed over the atoms is minus the fix's global collision virial (half of a pair
// collision's to each partner, a wall's to its atom); the per-atom collisions add up to twice the
// pair collisions plus the wall collisions, the energy changes to the step's dissipation; each
// atom's values follow it when LAMMPS sorts the atoms (every step here: the same values by atom
// ID as without sorting).
TEST(FixHardsphereED, PerAtomVirialsAndTalliesAddUp)
{
  std::vector<std::vector<double>> by_id[2];    // per run: per step, stress xx and dE by atom ID
  for (int sorted = 0; sorted < 2; sorted++) {
    auto lmp = make_lammps();
    run(lmp.get(), walled_bed(8) + (sorted ? "atom_modify sort 1 3.0\n" : "") +
                       "compute s all stress/atom NULL virial\ncompute h all hardsphere/atom ed\n"
                       "compute sr all reduce sum c_s[1] c_s[2] c_s[3] c_s[4] c_s[5] c_s[6]\n"
                       "compute hr all reduce sum c_h[1] c_h[2] c_h[3] c_h[4] c_h[5]\n"
                       "thermo_style custom step c_sr[1] c_hr[1]\nthermo 1\ntimestep 0.2\nrun 0 post no");
    auto *fix = lmp->modify->get_fix_by_id("ed");
    auto *sr = lmp->modify->get_compute_by_id("sr"), *hr = lmp->modify->get_compute_by_id("hr");
    auto *s = lmp->modify->get_compute_by_id("s"), *h = lmp->modify->get_compute_by_id("h");
    double trace = 0.0, walls = 0.0;
    for (int step = 0; step < 20; step++) {
      const double lost0 = fix->compute_vector(2);
      run(lmp.get(), "run 1 post no");
      sr->compute_vector();
      hr->compute_vector();
      const double scale = std::fabs(fix->virial[0]) + std::fabs(fix->virial[1]) + 1.0;
      for (int k = 0; k < 6; k++)
        EXPECT_NEAR(-sr->vector[k], fix->virial[k], 1e-10 * scale) << "step " << step << ", " << k;
      const double nwall = fix->compute_vector(0) - hr->vector[0] / 2.0;    // (pairs count twice)
      EXPECT_EQ(hr->vector[1], nwall) << "step " << step;
      EXPECT_NEAR(hr->vector[2] + hr->vector[3] + hr->vector[4], -(fix->compute_vector(2) - lost0),
                  1e-9 * (1.0 + std::fabs(lost0))) << "step " << step;
      trace += fix->virial[0] + fix->virial[1];
      walls += nwall;
      s->compute_peratom();
      h->compute_peratom();
      std::vector<double> v(2 * lmp->atom->natoms + 2, 0.0);
      for (int i = 0; i < lmp->atom->nlocal; i++) {
        v[2 * lmp->atom->tag[i]] = s->array_atom[i][0];
        v[2 * lmp->atom->tag[i] + 1] = h->array_atom[i][2];
        const auto *u = lmp->update;
        const double now = u->atime + (double) (u->ntimestep - u->atimestep) * u->dt;
        if (h->array_atom[i][0] + h->array_atom[i][1] > 0) {    // (a collision in this step)
          EXPECT_GE(h->array_atom[i][5], now - u->dt - 1e-12);
          EXPECT_LE(h->array_atom[i][5], now + 1e-12);
        }
      }
      by_id[sorted].push_back(v);
    }
    EXPECT_GT(trace, 0.0);
    EXPECT_GT(walls, 0.0);
  }
  {
    // 3D with LAMMPS's default atom sorting (at the run's setup): the tallies, asked for by a
    // compute defined after the fix, are sorted with the atoms
    auto lmp = make_lammps();
    run(lmp.get(), "units lj\natom_style sphere\ncomm_modify vel yes\nlattice fcc 0.6\n"
                   "region box block 0 6 0 6 0 6\ncreate_box 1 box\ncreate_atoms 1 box\n"
                   "set type 1 diameter 1.0\nset type 1 mass 1.0\n"
                   "velocity all create 1.0 4321 loop geom mom yes dist gaussian\n"
                   "pair_style hardsphere/walton\npair_coeff * * 0.9 0.3 0.4\nfix ed all hardsphere/ed\n"
                   "compute s all stress/atom NULL virial\ncompute h all hardsphere/atom ed\n"
                   "compute sr all reduce sum c_s[1] c_h[1]\nthermo_style custom step c_sr[1] c_sr[2]\n"
                   "timestep 0.05\nthermo 5\nrun 10 post no");
    auto *sr = lmp->modify->get_compute_by_id("sr");
    sr->compute_vector();
    EXPECT_NEAR(-sr->vector[0], lmp->modify->get_fix_by_id("ed")->virial[0], 1e-9 * std::fabs(sr->vector[0]));
    EXPECT_EQ(sr->vector[1], 2.0 * lmp->modify->get_fix_by_id("ed")->compute_vector(0));
  }
  ASSERT_EQ(by_id[0].size(), by_id[1].size());
  for (size_t k = 0; k < by_id[0].size(); k++)
    for (size_t e = 0; e < by_id[0][k].size(); e++)
      EXPECT_NEAR(by_id[0][k][e], by_id[1][k][e], 1e-9 * (1.0 + std::fabs(by_id[0][k][e])))
          << "step " << k << ", value " << e << ": per-atom values must follow the atoms";
}

TEST(FixHardsphereED, RestartContinuesTheTrajectory)
{
  const std::string setup = gas(2, 150, 22.0, 99) +
      "pair_style hardsphere/walton\npair_coeff * * 0.8 0.3 0.4\n"
      "fix ed all hardsphere/ed tc 0.05\nfix k all hardsphere/kick 3.0 0.1 99\n"
      "timestep 0.1\nthermo 0\n";
  auto a = make_lammps();
  run(a.get(), setup + "run 40 post no");
  Reference ra = reference_of(a.get());
  const double colla = a->modify->get_fix_by_id("ed")->compute_vector(1);
  a.reset();    // one LAMMPS instance at a time: a plugin is registered with one instance only

  const std::string rst = "granfric_test_ed_" + std::to_string(::getpid()) + ".restart";
  {
    auto b = make_lammps();
    run(b.get(), setup + "run 20 post no\nwrite_restart " + rst);
  }
  auto c = make_lammps();
  run(c.get(), "read_restart " + rst + "\ncomm_modify vel yes\nfix ed all hardsphere/ed tc 0.05\n"
               "fix k all hardsphere/kick 3.0 0.1 99\ntimestep 0.1\nthermo 0\nrun 20 post no");
  std::remove(rst.c_str());
  // the continuous run keeps its event queue across the step where the other one restarts and
  // predicts afresh: the same trajectory up to rounding
  EXPECT_LT(max_deviation(c.get(), ra), 1e-9) << "restart must continue the same trajectory";
  EXPECT_EQ(c->modify->get_fix_by_id("ed")->compute_vector(1), colla)
      << "collision totals are kept in the restart file";
  EXPECT_EQ(c->modify->get_fix_by_id("k")->compute_scalar(), 12.0)
      << "the kick counter is kept in the restart file (kicks at t = 0, 1/3, ..., 11/3)";
}

// Without the TC model the fix keeps no last-collision times (8 bytes per atom less, and as
// many in the core); a restart file written then holds none, so a fix with tc that reads it
// starts with no previous collisions, as a fix defined afresh does.
TEST(FixHardsphereED, LastCollisionTimesOnlyWithTC)
{
  const std::string setup = gas(2, 150, 22.0, 5) +
      "pair_style hardsphere/rough\npair_coeff * * 0.7 0.3\ntimestep 0.1\nthermo 0\n";
  const std::string rst = "granfric_test_tc_" + std::to_string(::getpid()) + ".restart";
  auto a = make_lammps();
  run(a.get(), setup + "fix ed all hardsphere/ed\nrun 20 post no");
  const double mem0 = a->modify->get_fix_by_id("ed")->memory_usage();
  run(a.get(), "write_restart " + rst + "\nunfix ed\nfix ed all hardsphere/ed tc 0.5\nrun 20 post no");
  const double mem1 = a->modify->get_fix_by_id("ed")->memory_usage();
  EXPECT_GE(mem1 - mem0, 16.0 * a->atom->nlocal) << "tc keeps a time per atom in the fix and in the core";
  EXPECT_GT(a->modify->get_fix_by_id("ed")->compute_vector(6), 0.0)
      << "the TC model made collisions elastic (else this test shows nothing)";
  Reference ra = reference_of(a.get());
  a.reset();
  auto b = make_lammps();
  run(b.get(), "read_restart " + rst);
  // (a file that announced per-atom data its atoms do not hold gave the fix below uninitialized
  // last-collision times, and a trajectory that changed from run to run)
  EXPECT_EQ(b->atom->nextra_store, 0) << "a fix without the TC model writes no per-atom data";
  run(b.get(), "comm_modify vel yes\nfix ed all hardsphere/ed tc 0.5\ntimestep 0.1\nthermo 0\nrun 20 post no");
  std::remove(rst.c_str());
  EXPECT_LT(max_deviation(b.get(), ra), 1e-9)
      << "a restart without last-collision times: the TC model starts from none";
}

// Consecutive runs keep the event queue when nothing changed (no rebuild, the trajectory of
// one long run), and rebuild it when the configuration did (new pair coefficients).
TEST(FixHardsphereED, QueueKeptAcrossRunsUnlessConfigurationChanges)
{
  const std::string setup = gas(2, 150, 22.0, 7) +
      "pair_style hardsphere/rough\npair_coeff * * 0.9 0.2\nfix ed all hardsphere/ed\n"
      "timestep 0.1\nthermo 0\n";
  auto a = make_lammps();
  run(a.get(), setup + "run 30 post no");
  Reference ra = reference_of(a.get());
  a.reset();
  auto b = make_lammps();
  run(b.get(), setup + "run 10 post no\nrun 10 post no\nrun 10 post no");
  auto *fix = b->modify->get_fix_by_id("ed");
  EXPECT_EQ(fix->compute_vector(5), 1.0) << "one build for three runs of an unchanged system";
  EXPECT_LT(max_deviation(b.get(), ra), 1e-12) << "split runs follow the one-run trajectory";
  run(b.get(), "pair_coeff * * 0.8 0.2\nrun 5 post no");
  EXPECT_EQ(fix->compute_vector(5), 2.0) << "new coefficients: the queue must be rebuilt";
  run(b.get(), "velocity all scale 1.5\nrun 5 post no");
  EXPECT_EQ(fix->compute_vector(5), 3.0) << "velocities changed by a command: rebuilt";
  // the same atoms in another storage order (LAMMPS sorts them at every reneighboring now)
  std::vector<LAMMPS_NS::tagint> before(b->atom->tag, b->atom->tag + b->atom->nlocal);
  run(b.get(), "atom_modify sort 1 1.0\nrun 20 post no");
  std::vector<LAMMPS_NS::tagint> after(b->atom->tag, b->atom->tag + b->atom->nlocal);
  EXPECT_NE(before, after) << "the atoms were sorted in memory";
  EXPECT_EQ(fix->compute_vector(5), 3.0) << "the same atoms in another order: the queue is kept";
  run(b.get(), "group one id 7\ndelete_atoms group one\nrun 5 post no");
  EXPECT_EQ(fix->compute_vector(5), 4.0) << "an atom fewer: rebuilt";
}

// The fix keeps, per atom and dimension, the periods between the core's unwrapped frame and
// LAMMPS's positions in one byte (at most +-100). Two discs in separate rows fly along x
// without ever colliding, crossing the box about once per step (LAMMPS wraps them as it
// reneighbors) or 120 times within one long step: when an offset would leave its range the
// next step starts afresh, and the positions stay exact.
TEST(FixHardsphereED, ManyPeriodsCrossedStayExact)
{
  const std::string setup =
      "units lj\ndimension 2\natom_style sphere\nboundary p p p\ncomm_modify vel yes\n"
      "region box block 0 4 0 4 -0.5 0.5\ncreate_box 1 box\n"
      "create_atoms 1 single 0.5 1.0 0.0\ncreate_atoms 1 single 2.5 3.0 0.0\n"
      "set type 1 diameter 0.5\nset type 1 density 1.0\n"
      "set atom 1 vx 3.3 vy 0.0\nset atom 2 vx -2.9 vy 0.0\n"
      "pair_style hardsphere/rough inertia disc\npair_coeff * * 0.9 0.2\n"
      "fix ed all hardsphere/ed\nthermo 0\n";
  const double x0[2] = {0.5, 2.5}, vx[2] = {3.3, -2.9};
  auto check = [&](LAMMPS_NS::LAMMPS *lmp, double t, const char *what) {
    auto *atom = lmp->atom;
    for (int i = 0; i < atom->nlocal; i++) {
      const int k = (int) atom->tag[i] - 1;
      double xu[3];
      lmp->domain->unmap(atom->x[i], atom->image[i], xu);
      EXPECT_NEAR(xu[0], x0[k] + vx[k] * t, 1e-9 * (1.0 + std::fabs(vx[k] * t))) << what;
      EXPECT_EQ(atom->v[i][0], vx[k]) << what;
      EXPECT_GE(atom->x[i][0], -2.0) << what << ": LAMMPS's position stays near the box";
      EXPECT_LE(atom->x[i][0], 6.0) << what << ": LAMMPS's position stays near the box";
    }
  };
  auto a = make_lammps();
  run(a.get(), setup + "timestep 1.0\nrun 400 post no");
  check(a.get(), 400.0, "one crossing per step");
  // atom 1 crosses 330 periods: its offset passes +-100 three times, so at least three more
  // starts than the first one (and not one per step)
  const double starts = a->modify->get_fix_by_id("ed")->compute_vector(5);
  EXPECT_GE(starts, 4.0);
  EXPECT_LE(starts, 8.0);
  a.reset();
  auto b = make_lammps();
  run(b.get(), setup + "timestep 150.0\nrun 3 post no");
  check(b.get(), 450.0, "about 120 crossings per step");
  EXPECT_EQ(b->modify->get_fix_by_id("ed")->compute_vector(5), 3.0)
      << "every step's offsets leave their range: each step starts afresh";
}

// The memory-saving LAMMPS settings the doc recommends (no atom sorting, no displacement check,
// no neighbor skin: ghost atoms only within the contact distance) give the same trajectory as
// LAMMPS's displacement check with sorting at every build and the default skin, at a step short
// enough for LAMMPS to skip some builds (0.02 collision times) and at a long one.
TEST(FixHardsphereED, LeanLammpsSettingsSameTrajectory)
{
  for (const char *dt : {"0.005", "0.3"}) {
    const std::string setup = gas(2, 150, 22.0, 5) +
        "pair_style hardsphere/rough inertia disc\npair_coeff * * 0.9 0.2\n"
        "fix ed all hardsphere/ed\nthermo 0\ntimestep " + std::string(dt) + "\n";
    auto a = make_lammps();
    run(a.get(), setup + "atom_modify sort 1 1.0\nrun 200 post no");
    Reference ra = reference_of(a.get());
    const double builds = a->neighbor->ncalls;
    const int ghosts = a->atom->nghost;
    a.reset();
    auto b = make_lammps();
    run(b.get(), setup + "atom_modify sort 0 0\nneigh_modify every 1 delay 0 check no\n"
                         "neighbor 0.0 bin\nrun 200 post no");
    EXPECT_LT(b->atom->nghost, ghosts) << "dt " << dt << ": no skin, fewer ghost atoms";
    // (the core's trajectory is the same; LAMMPS may have wrapped an atom in one run and not
    // yet in the other, and unwrapping x - L + L rounds in the last bit)
    EXPECT_LT(max_deviation(b.get(), ra), 1e-12) << "dt " << dt << ": the same trajectory";
    EXPECT_GE(b->neighbor->ncalls, 200) << "dt " << dt << ": lean settings build at every step";
    if (std::string(dt) == "0.005") EXPECT_LT(builds, 150) << "the default check skips builds";
  }
}

// r = 0.5 at area fraction 0.6: inelastic collapse without the TC model
std::string collapsing()
{
  return "units lj\ndimension 2\natom_style sphere\nboundary p p p\ncomm_modify vel yes\n"
         "lattice sq 0.7639437\nregion box block 0 50 0 50 -0.5 0.5\ncreate_box 1 box\n"
         "create_atoms 1 box\nset type 1 diameter 1.0\nset type 1 density 1.2732395\n"
         "velocity all create 1.0 3 loop geom mom yes\n"
         "pair_style hardsphere/rough inertia disc\npair_coeff * * 0.5 -1.0\ntimestep 1.0\n"
         "thermo 0\n";
}

TEST(FixHardsphereED, CollapseStopsWithClearErrorWithoutTC)
{
  auto lmp = make_lammps();
  run(lmp.get(), collapsing() + "fix ed all hardsphere/ed maxevents 100000");
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_LMP_ERROR(lmp.get(), "run 100 post no",
                   "Fix hardsphere/ed: atom [0-9]+ had [0-9]+ collisions within step "
                   "[0-9]+ \\(maxevents 100000\\), the last one with atom [0-9]+.*inelastic collapse. Use the TC model");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 120.0);
}

// Elastic discs placed at random with overlap allow: some are caged by neighbours they overlap
// and collide without end. The laws conserve energy, so the error says that this is no
// inelastic collapse (which the TC model would not help) and names the overlaps
TEST(FixHardsphereED, EndlessElasticCollisionsAreNoCollapse)
{
  auto lmp = make_lammps();
  run(lmp.get(), "units lj\ndimension 2\natom_style sphere\ncomm_modify vel yes\n"
                 "region box block 0 8 0 8 -0.5 0.5\ncreate_box 1 box\ncreate_atoms 1 random 100 77 NULL\n"
                 "set group all diameter 1.0\nset group all mass 1.0\nvelocity all create 1.0 4321 loop geom\n"
                 "pair_style hardsphere/rough inertia disc\npair_coeff * * 1.0 -1.0\n"
                 "fix ed all hardsphere/ed overlap allow maxevents 2000\ntimestep 1.0\nthermo 0");
  EXPECT_LMP_ERROR(lmp.get(), "run 20 post no",
                   "every collision law here conserves energy, so this is no inelastic collapse: "
                   "atoms that overlap their neighbours \\(overlap allow\\) can be caged");
}

// Energy that runs away (Jenkins-Zhang with kappa_d > kappa_s; the temperature grows from 1 to
// ~150 in 35 steps and then without bound) stops with an error that names energy creation, not
// inelastic collapse, within bounded time; an atom that crosses cells without end (alone, at
// 1e8) stops at the cap on cell crossings (maxcross x atoms per step), which names it and its
// speed.
TEST(FixHardsphereED, RunawayAndFastAtomsStopWithClearErrors)
{
  const std::string lattice = "units lj\ndimension 2\natom_style sphere\nboundary p p p\n"
                              "comm_modify vel yes\nlattice sq 0.3\nregion box block 0 10 0 10 -0.5 0.5\n"
                              "create_box 1 box\ncreate_atoms 1 box\nset type 1 diameter 1.0\n"
                              "set type 1 mass 1.0\nvelocity all create 1.0 4321 loop geom mom yes dist gaussian\n";
  const auto t0 = std::chrono::steady_clock::now();
  {
    auto lmp = make_lammps();
    run(lmp.get(), lattice + "pair_style hardsphere/jz inertia disc\npair_coeff * * 0.05 0.05 0.1 0.5\n"
                             "fix ed all hardsphere/ed maxevents 1000\ntimestep 1\nthermo 0");
    EXPECT_LMP_ERROR(lmp.get(), "run 60 post no",
                     "atom [0-9]+ had 1001 collisions within step [0-9]+ \\(maxevents 1000\\).*can create "
                     "energy \\(hardsphere/jz with kappa_d > kappa_s\\)");
  }
  {
    // (alone in its box and at rest: a kick at time 0 would make it cross cells without end;
    // the check of the scales before the run counts the speed the kicks give)
    auto lmp = make_lammps();
    run(lmp.get(), "units lj\ndimension 2\natom_style sphere\nboundary p p p\ncomm_modify vel yes\n"
                   "region box block 0 10 0 10 -0.5 0.5\ncreate_box 1 box\ncreate_atoms 1 single 5 5 0\n"
                   "set type 1 diameter 1.0\nset type 1 mass 1.0\n"
                   "pair_style hardsphere/rough inertia disc\npair_coeff * * 1.0 -1.0\n"
                   "fix ed all hardsphere/ed maxevents 10\nfix k all hardsphere/kick 1.0 1e8 4711 momentum no\n"
                   "timestep 1\nthermo 0");
    EXPECT_LMP_ERROR(lmp.get(), "run 1 post no",
                     "the atoms would travel 1.41e\\+08 diameters per step on average \\(mean speed 0, 0 "
                     "from moving or thermal walls, 1.41e\\+08 from kicks");
    lmp.reset();
    // the same speed at the start is refused before the run
    lmp = make_lammps();
    run(lmp.get(), "units lj\ndimension 2\natom_style sphere\nboundary p p p\ncomm_modify vel yes\n"
                   "region box block 0 10 0 10 -0.5 0.5\ncreate_box 1 box\ncreate_atoms 1 single 5 5 0\n"
                   "set type 1 diameter 1.0\nset type 1 mass 1.0\nvelocity all set 1e8 3.0 0.0\n"
                   "pair_style hardsphere/rough inertia disc\npair_coeff * * 1.0 -1.0\n"
                   "fix ed all hardsphere/ed maxevents 10\ntimestep 1\nthermo 0");
    EXPECT_LMP_ERROR(lmp.get(), "run 1 post no",
                     "the atoms would travel 1e\\+08 diameters per step on average \\(mean speed 1e\\+08");
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 60.0);
}

TEST(FixHardsphereED, CollapseAvoidedWithTC)
{
  auto lmp = make_lammps();
  run(lmp.get(), collapsing() + "fix ed all hardsphere/ed tc 1e-4 maxevents 100000");
  EXPECT_EQ(error_of(lmp.get(), "run 100 post no"), "");
  auto *fix = lmp->modify->get_fix_by_id("ed");
  EXPECT_GT(fix->compute_vector(6), 0.0) << "some collisions were made elastic";
  EXPECT_LT(fix->compute_vector(4), 100000.0);
}

class FixErrors : public ::testing::Test {
 protected:
  std::unique_ptr<LAMMPS_NS::LAMMPS> lmp;
  void SetUp() override
  {
    lmp = make_lammps();
    run(lmp.get(), gas(2, 20, 10.0, 5) + "pair_style hardsphere/rough\npair_coeff * * 0.9 0.0\n");
  }
};

TEST_F(FixErrors, Keywords)
{
  EXPECT_LMP_ERROR(lmp.get(), "fix ed all hardsphere/ed tc -1",
                   "tc = -1 must be >= 0 \\(0: TC model off\\)");
  EXPECT_LMP_ERROR(lmp.get(), "fix ed all hardsphere/ed tc", "Illegal fix hardsphere/ed tc");
  EXPECT_LMP_ERROR(lmp.get(), "fix ed all hardsphere/ed maxevents 0", "maxevents = 0 must be >= 1");
  EXPECT_LMP_ERROR(lmp.get(), "fix ed all hardsphere/ed maxevents 1.5", "Expected integer");
  EXPECT_LMP_ERROR(lmp.get(), "fix ed all hardsphere/ed gravity 0 -1",
                   "Illegal fix hardsphere/ed gravity");
  EXPECT_LMP_ERROR(lmp.get(), "fix ed all hardsphere/ed gravity 0 -1 0.5",
                   "gravity must have gz = 0 in a 2d simulation");
  EXPECT_LMP_ERROR(lmp.get(), "fix ed all hardsphere/ed gravity a b 0", "Expected floating point");
  EXPECT_LMP_ERROR(lmp.get(), "fix ed all hardsphere/ed speed 2",
                   "Unknown fix hardsphere/ed keyword: speed \\(allowed: gravity, tc, maxevents, "
                   "maxcross, parallel, reach, check, overlap\\)");
  EXPECT_LMP_ERROR(lmp.get(), "fix ed all hardsphere/ed parallel fast",
                   "parallel fast is not available \\(allowed: domain, gather\\)");
  EXPECT_LMP_ERROR(lmp.get(), "fix ed all hardsphere/ed check maybe",
                   "check maybe is not available \\(allowed: yes, no\\)");
  EXPECT_LMP_ERROR(lmp.get(), "fix ed all hardsphere/ed parallel", "Illegal fix hardsphere/ed parallel");
  EXPECT_LMP_ERROR(lmp.get(), "fix ed all hardsphere/ed reach 0.5", "reach = 0.5 must be >= 1");
  EXPECT_LMP_ERROR(lmp.get(), "fix ed all hardsphere/ed reach x", "Expected floating point");
}

TEST_F(FixErrors, Combinations)
{
  run(lmp.get(), "fix ed all hardsphere/ed\nfix nve all nve/sphere");
  EXPECT_LMP_ERROR(lmp.get(), "run 0", "Fix nve \\(nve/sphere\\) integrates the same atoms as fix "
                                       "hardsphere/ed ed");
  run(lmp.get(), "unfix nve\nfix g all gravity 1.0 vector 0 -1 0");
  EXPECT_LMP_ERROR(lmp.get(), "run 0", "Fix g \\(gravity\\) acts together with fix hardsphere/ed "
                                       "ed: use the gravity keyword");
  run(lmp.get(), "unfix g\ngroup half id <= 10\nunfix ed\nfix ed half hardsphere/ed");
  EXPECT_LMP_ERROR(lmp.get(), "run 0", "must be applied to group all");
  run(lmp.get(), "unfix ed\nfix ed all hardsphere/ed\nrun 0 post no");
  run(lmp.get(), "fix d all deform 1 x scale 1.1");
  EXPECT_LMP_ERROR(lmp.get(), "run 0", "does not support a box whose size or shape changes during the run \\(fix d deform\\)");
}

TEST_F(FixErrors, RefusesOtherPairStyles)
{
  run(lmp.get(), "pair_style granular\npair_coeff * * hooke 1000.0 50.0 tangential linear_nohistory 1.0 0.4\n"
                 "fix ed all hardsphere/ed");
  EXPECT_LMP_ERROR(lmp.get(), "run 0",
                   "requires pair style hardsphere/rough, hardsphere/walton or hardsphere/jz "
                   "\\(found granular\\)");
}

// side^2 elastic smooth discs at rest (area fraction 0.05) kicked once per unit time with
// v_dr = 0.05 (fix k), steps of 0.3
std::string kicked_gas(int side)
{
  return "units lj\ndimension 2\natom_style sphere\ncomm_modify vel yes\n"
         "lattice sq 0.0637\nregion box block 0 " + std::to_string(side) + " 0 " + std::to_string(side) +
         " -0.5 0.5\ncreate_box 1 box\ncreate_atoms 1 box\nset type 1 diameter 1.0\nset type 1 mass 1.0\n"
         "pair_style hardsphere/rough inertia disc\npair_coeff * * 1.0 -1.0\n"
         "fix ed all hardsphere/ed\nfix k all hardsphere/kick 1.0 0.05 4711\ntimestep 0.3\n";
}

// homogeneous driving: without dissipation (elastic smooth discs) T_tr grows at the rate
// f_dr m v_dr^2 (Herbst eqs 7-9), kicks keep the total momentum zero, and the energy books close
TEST(FixHardsphereKick, HeatingRateMomentumAndEnergyBooks)
{
  auto lmp = make_lammps();
  run(lmp.get(), kicked_gas(100) + "compute T all hardsphere/temp\nthermo_style custom step c_T[1]\n"
                                   "run 100 post no");
  auto *T = lmp->modify->get_compute_by_id("T");
  T->compute_vector();
  const double t = 30.0, expected = 1.0 * 1.0 * 0.05 * 0.05 * t * (1.0 - 1.0 / 10000);
  // 30 kicks (t = 0, 1, ..., 29); the relative noise of the mean of 2N squares is 1 %
  EXPECT_NEAR(T->vector[0] / expected, 1.0, 0.04);
  double P[2] = {0, 0};
  for (int i = 0; i < lmp->atom->nlocal; i++)
    for (int d = 0; d < 2; d++) P[d] += lmp->atom->rmass[i] * lmp->atom->v[i][d];
  EXPECT_LT(std::fabs(P[0]) + std::fabs(P[1]), 1e-12);
  EXPECT_EQ(lmp->modify->get_fix_by_id("k")->compute_scalar(), 30.0);    // next kick index

  // dissipative collisions: injected - dissipated = change of kinetic energy
  run(lmp.get(), "pair_coeff * * 0.8 0.3\nrun 100 post no");
  auto *ed = lmp->modify->get_fix_by_id("ed");
  T->compute_vector();
  const double E = T->vector[3] + T->vector[4];
  EXPECT_GT(ed->compute_vector(2), 0.0);
  EXPECT_NEAR(ed->compute_vector(8) - ed->compute_vector(2), E, 1e-9 * E);
}

// The kicks follow the simulation time through reset_timestep: after a reset to time 0 they go
// on at once (9 kicks in 9 time units, as in the first run, with new random numbers: as much
// energy again, not the replay of the first run's increments), and a jump to time 500 gives the
// 3 kicks of the next 3 time units, not the 494 between the old time and the new; a restart
// file keeps the schedule
TEST(FixHardsphereKick, ScheduleFollowsResetTimestep)
{
  auto lmp = make_lammps();
  run(lmp.get(), kicked_gas(20) + "run 30 post no");
  auto *k = lmp->modify->get_fix_by_id("k");
  auto *ed = lmp->modify->get_fix_by_id("ed");
  EXPECT_EQ(k->compute_scalar(), 9.0);
  const double e1 = ed->compute_vector(8);
  ASSERT_GT(e1, 0.0);
  run(lmp.get(), "reset_timestep 0\nrun 30 post no");
  EXPECT_EQ(k->compute_scalar(), 18.0);
  const double e2 = ed->compute_vector(8);
  EXPECT_NEAR((e2 - e1) / e1, 1.0, 0.3);
  run(lmp.get(), "reset_timestep 1000 time 500.0\nrun 10 post no");
  EXPECT_EQ(k->compute_scalar(), 21.0);
  const double e3 = ed->compute_vector(8) - e2;
  EXPECT_GT(e3 / e1, 0.1);
  EXPECT_LT(e3 / e1, 0.7);
  // a restart file written now continues with the kicks at 503, 504, 505
  const std::string rst = "granfric_test_kick_" + std::to_string(::getpid()) + ".restart";
  run(lmp.get(), "write_restart " + rst);
  lmp.reset();    // one LAMMPS instance at a time: a plugin is registered with one instance only
  auto b = make_lammps();
  run(b.get(), "read_restart " + rst + "\ncomm_modify vel yes\nfix ed all hardsphere/ed\n"
               "fix k all hardsphere/kick 1.0 0.05 4711\ntimestep 0.3\nrun 10 post no");
  std::remove(rst.c_str());
  EXPECT_EQ(b->modify->get_fix_by_id("k")->compute_scalar(), 24.0);
}

// total energy of the system: kinetic (translation and rotation) plus potential m |g| y
double total_energy(LAMMPS_NS::LAMMPS *lmp, double g)
{
  auto *atom = lmp->atom;
  auto *T = lmp->modify->get_compute_by_id("T");
  T->compute_vector();
  double pot = 0.0;
  for (int i = 0; i < atom->nlocal; i++) pot += atom->rmass[i] * g * atom->x[i][1];
  return T->vector[3] + T->vector[4] + pot;
}

// the energy books close over a million collisions: energy injected (kicks, vibrating base)
// minus energy dissipated (pair and wall collisions) equals the change of the total energy to
// 1e-9 of the energy that went through the system. Herbst's driven gas (Walton law, kicks
// with spin driving) and Risso's vibrated bed (JZ law, gravity, vibrating base, side walls, lid)
TEST(EnergyBooks, CloseOverAMillionCollisions)
{
  struct Scene {
    const char *name, *setup;
    double g;
    int steps;
  };
  const Scene scenes[] = {
      {"driven gas",
       "boundary p p p\nlattice sq 0.3\nregion box block 0 30 0 30 -0.5 0.5\n"
       "create_box 1 box\ncreate_atoms 1 box\nset type 1 diameter 1.0\nset type 1 mass 1.0\n"
       "velocity all create 1.0 5 loop geom mom yes dist gaussian\n"
       "pair_style hardsphere/walton inertia sphere\npair_coeff * * 0.95 0.5 0.4\n"
       "fix ed all hardsphere/ed\nfix k all hardsphere/kick 5.0 0.15 4711 spin 0.2\n"
       "timestep 0.5\n",
       0.0, 400},
      {"vibrated bed",
       "boundary f f p\nregion box block 0 30 -0.1 80 -0.5 0.5\ncreate_box 1 box\n"
       "lattice sq 0.8\nregion start block 0.6 29.4 0.5 20 -0.5 0.5 units box\n"
       "create_atoms 1 region start\n"
       "set type 1 diameter 1.0\nset type 1 mass 1.0\n"
       "velocity all create 1.0 5 loop geom mom yes dist gaussian\n"
       "pair_style hardsphere/jz inertia disc\npair_coeff * * 0.02 0.02 0.3 0.3\n"
       "fix ed all hardsphere/ed gravity 0 -0.015625 0 tc 1e-4\n"
       "fix base all hardsphere/wall ylo 0.0 vibrate parabolic 0.1 10.0\n"
       "fix left all hardsphere/wall xlo EDGE\nfix right all hardsphere/wall xhi EDGE\n"
       "fix lid all hardsphere/wall yhi EDGE\ntimestep 0.6283185307179586\n",
       0.015625, 2000},
  };
  for (const auto &sc : scenes) {
    SCOPED_TRACE(sc.name);
    auto lmp = make_lammps();
    run(lmp.get(), std::string("units lj\ndimension 2\natom_style sphere\ncomm_modify vel yes\n") +
                       sc.setup + "compute T all hardsphere/temp\nthermo 0\nrun 0 post no");
    auto *ed = lmp->modify->get_fix_by_id("ed");
    const double E0 = total_energy(lmp.get(), sc.g);
    while (ed->compute_vector(1) < 1.0e6)
      run(lmp.get(), "run " + std::to_string(sc.steps) + " post no");
    const double E1 = total_energy(lmp.get(), sc.g);
    // dissipated is net of what the walls gave (WALL_ENERGY): pair losses = the sum of both
    const double injected = ed->compute_vector(8), dissipated = ed->compute_vector(2);
    const double wall = ed->compute_vector(10), pair_loss = dissipated + wall;
    EXPECT_GT(pair_loss, 0.0);
    EXPECT_GT(injected + wall, 0.0) << "energy was injected";
    const double through = injected + std::fabs(wall) + pair_loss;
    EXPECT_NEAR((E1 - E0) / through, (injected - dissipated) / through, 1e-9)
        << ed->compute_vector(1) << " collisions, E " << E0 << " -> " << E1 << ", injected "
        << injected << ", dissipated " << dissipated;
  }
}

TEST_F(FixErrors, Kick)
{
  run(lmp.get(), "fix ed all hardsphere/ed");
  EXPECT_LMP_ERROR(lmp.get(), "fix k all hardsphere/kick 0 0.1 5", "f_dr = 0 must be > 0");
  EXPECT_LMP_ERROR(lmp.get(), "fix k all hardsphere/kick 1 -0.1 5", "v_dr = -0.1 must be >= 0");
  EXPECT_LMP_ERROR(lmp.get(), "fix k all hardsphere/kick 1 0.1 0", "seed = 0 must be > 0");
  EXPECT_LMP_ERROR(lmp.get(), "fix k all hardsphere/kick 1 0.1", "Illegal fix hardsphere/kick");
  EXPECT_LMP_ERROR(lmp.get(), "fix k all hardsphere/kick 1 0.1 5 momentum maybe",
                   "Expected boolean parameter instead of 'maybe'");
  EXPECT_LMP_ERROR(lmp.get(), "fix k all hardsphere/kick 1 0.1 5 spin -1", "spin = -1 must be >= 0");
  EXPECT_LMP_ERROR(lmp.get(), "fix k all hardsphere/kick 1 0.1 5 heat 2",
                   "Unknown fix hardsphere/kick keyword: heat \\(allowed: momentum, spin\\)");
  run(lmp.get(), "unfix ed\nfix k all hardsphere/kick 1 0.1 5\nfix n all nve/sphere");
  EXPECT_LMP_ERROR(lmp.get(), "run 0", "needs fix hardsphere/ed");
}

// Risso eqs 10-11 on flow fields of known order parameters: one roll v_y ~ sin(2 pi x / L),
// two rolls v_y ~ -cos(2 pi x / L)
// a gas between a floor and a ceiling under gravity: trajectories equal the brute-force
// reference with the same walls, nobody leaves the box, and every invalid wall input errs
TEST(FixHardsphereWall, EqualsReferenceAndHolds)
{
  for (int dim = 2; dim <= 3; dim++) {
    auto lmp = make_lammps();
    std::string s = gas(dim, dim == 2 ? 120 : 100, dim == 2 ? 20.0 : 8.0, 77);
    s.replace(s.find("boundary p p p"), 14, "boundary p f p");
    // atoms at least a radius away from the floor and the ceiling
    const std::string side = dim == 2 ? "20.0" : "8.0";
    s.replace(s.find("NULL overlap"), 4, "inner");
    s.replace(s.find("create_atoms"), 0, "region inner block EDGE EDGE 0.6 " +
              std::to_string(std::stod(side) - 0.6) + " EDGE EDGE\n");
    run(lmp.get(), s + "pair_style hardsphere/walton" + (dim == 2 ? " inertia disc" : "") +
                       "\npair_coeff * * 0.9 0.4 0.3\n"
                       "fix ed all hardsphere/ed gravity 0.0 -0.3 0.0 tc 0.01\n"
                       "fix floor all hardsphere/wall ylo EDGE\n"
                       "fix top all hardsphere/wall yhi EDGE coeffs 0.7 inf 0.5\n"
                       "timestep 0.1\nthermo 0\nrun 0 post no");
    Reference ref = reference_of(lmp.get());
    ref.periodic[1] = false;
    ref.gravity = Vec3(0.0, -0.3, 0.0);
    ref.tc = 0.01;    // a ball bouncing on an inelastic floor collapses without it
    auto *dom = lmp->domain;
    ref.walls.push_back({1, -1, dom->boxlo[1], granfric::LawParams::walton(0.9, 0.4, 0.3)});
    ref.walls.push_back({1, +1, dom->boxhi[1], granfric::LawParams::walton(0.7, granfric::INF, 0.5)});
    for (int step = 0; step < 25; step++) {
      run(lmp.get(), "run 1 post no");
      for (int i = 0; i < lmp->atom->nlocal; i++) {
        ASSERT_GE(lmp->atom->x[i][1] - lmp->atom->radius[i], dom->boxlo[1] - 1e-12);
        ASSERT_LE(lmp->atom->x[i][1] + lmp->atom->radius[i], dom->boxhi[1] + 1e-12);
      }
    }
    ref.run_until(25 * 0.1);
    auto *fix = lmp->modify->get_fix_by_id("ed");
    EXPECT_GT(fix->compute_vector(9), 10.0) << "wall collisions";
    EXPECT_LT(fix->compute_vector(1), 8.0 * lmp->atom->natoms) << "a few collisions per particle";
    EXPECT_EQ((long) fix->compute_vector(9), ref.wall_collisions);
    // (the fix's total counts wall collisions too)
    EXPECT_EQ((long) fix->compute_vector(1), ref.collisions + ref.wall_collisions);
    EXPECT_NEAR(fix->compute_vector(2), -ref.dE, 1e-9 * std::fabs(ref.dE));
    EXPECT_LT(max_deviation(lmp.get(), ref), 1e-9);
  }
}

// The wall's force outputs: the momentum balance of a gas under gravity above a floor (no lid:
// the box follows the gas) holds exactly, step by step and over the whole run (impulse on the
// floor = weight x time + the particles' momentum change), and for an elastic gas (a steady
// atmosphere) the floor's force averaged over a long run equals the weight within 0.5 %; the
// floor's collisions and energy are the fix's.
TEST(FixHardsphereWall, FloorCarriesTheWeight)
{
  auto lmp = make_lammps();
  const std::string s = walled_gas(120, 20.0, 91, "m");
  const double g = 0.3, dt = 0.5;
  // (perfectly rough and elastic: the floor exchanges spin with the gas, not energy)
  run(lmp.get(), s + "pair_style hardsphere/rough inertia disc\npair_coeff * * 1.0 1.0\n"
                     "fix ed all hardsphere/ed gravity 0.0 -0.3 0.0\n"
                     "fix floor all hardsphere/wall ylo 0.0\ntimestep 0.5\nthermo 0\nrun 0 post no");
  auto *atom = lmp->atom;
  double weight = 0.0;
  for (int i = 0; i < atom->nlocal; i++) weight += atom->rmass[i] * g;
  auto momentum = [&]() {
    double p = 0.0;
    for (int i = 0; i < atom->nlocal; i++) p += atom->rmass[i] * atom->v[i][1];
    return p;
  };
  auto *floor = lmp->modify->get_fix_by_id("floor"), *ed = lmp->modify->get_fix_by_id("ed");
  const double p0 = momentum();
  double p_prev = p0;
  for (int step = 0; step < 20; step++) {
    run(lmp.get(), "run 1 post no");
    // d p / dt = -weight - (force on the floor), over each step
    const double p = momentum();
    EXPECT_NEAR((p - p_prev) / dt, -weight - floor->compute_vector(3), 1e-9 * weight) << "step " << step;
    p_prev = p;
  }
  run(lmp.get(), "run 4000 post no");
  const double T = 4020 * dt, favg = floor->compute_vector(6);
  EXPECT_NEAR((momentum() - p0) / T, -weight - favg, 1e-9 * weight) << "in total";
  EXPECT_NEAR(-favg / weight, 1.0, 0.005) << "the floor carries the weight";
  EXPECT_GT(floor->compute_vector(8), 1000.0);
  EXPECT_EQ(floor->compute_vector(8), ed->compute_vector(9)) << "wall collisions";
  EXPECT_NEAR(floor->compute_vector(9), ed->compute_vector(10), 1e-9)
      << "energy given by the floor = the fix's wall energy";
}

// A bed of inelastic grains: the base's force averaged over a long run equals the bed's weight
// within 0.5 % (the bed's momentum stays bounded), on a vibrating base that drives it (and gives
// energy) and on a static one where it comes to rest (and loses energy)
TEST(FixHardsphereWall, BaseCarriesTheBedsWeight)
{
  for (const char *motion : {" vibrate parabolic 0.3 8.0", ""}) {
    // (on the static base the TC model keeps the resting bed's collisions finite: t_c = 0.05)
    auto lmp = make_lammps();
    run(lmp.get(), walled_gas(120, 20.0, 29, "m") +
                       "pair_style hardsphere/jz inertia disc\npair_coeff * * 0.05 0.05 0.3 0.3\n"
                       "fix ed all hardsphere/ed gravity 0.0 -1.0 0.0 tc " + (*motion ? "0.001" : "0.05") + "\n"
                       "fix base all hardsphere/wall ylo 0.0" + std::string(motion) +
                       "\ntimestep 0.2\nthermo 0\nrun 5000 post no");
    double weight = 0.0;
    for (int i = 0; i < lmp->atom->nlocal; i++) weight += lmp->atom->rmass[i] * 1.0;
    auto *base = lmp->modify->get_fix_by_id("base");
    const bool driven = *motion != 0;
    EXPECT_NEAR(-base->compute_vector(6) / weight, 1.0, 0.005)
        << (driven ? "vibrating" : "static") << " base: it carries the bed";
    EXPECT_EQ(base->compute_vector(9) > 0.0, driven) << "energy given by the base";
  }
}

// a rough disc (r = 0.8, beta = 0.2) falling straight down at speed 1 from y = 3 onto a floor
// at y = 0 that moves as `motion` says (it lands at t = 2.5), run for 4 time units
std::string disc_onto_floor(const std::string &motion)
{
  return "units lj\ndimension 2\natom_style sphere\ncomm_modify vel yes\nboundary p f p\n"
         "region box block 0 10 0 10 -0.5 0.5\ncreate_box 1 box\ncreate_atoms 1 single 5 3 0\n"
         "set group all diameter 1.0\nset group all mass 1.0\nvelocity all set 0.0 -1.0 0.0\n"
         "pair_style hardsphere/rough inertia disc\npair_coeff * * 0.8 0.2\n"
         "fix ed all hardsphere/ed\nfix floor all hardsphere/wall ylo 0.0 " + motion + "\n"
         "timestep 1.0\nthermo 0\nrun 4 post no";
}

// A disc falling straight onto a rough floor that slides along x: the rough law acts on the
// velocity relative to the floor's surface, so the disc leaves with the floor's share of its
// tangential motion (v_x = (1 + beta) q / (1 + q) u, spin to match), and the floor feels the
// opposite impulse
TEST(FixHardsphereWall, SlidingFloorDragsAnAtom)
{
  auto lmp = make_lammps();
  run(lmp.get(), disc_onto_floor("slide 2.0 0.0 0.0"));
  const double q = 0.5, beta = 0.2, u = 2.0;
  const double vx = (1.0 + beta) * q / (1.0 + q) * u;
  EXPECT_NEAR(lmp->atom->v[0][0], vx, 1e-12);
  EXPECT_NEAR(lmp->atom->v[0][1], 0.8, 1e-12);
  // (the impulse along +x at the contact point below the centre spins the disc counterclockwise:
  // d omega = a dp / (q m a^2))
  EXPECT_NEAR(lmp->atom->omega[0][2], 2.0 * vx / (q * 1.0), 1e-12);
  auto *floor = lmp->modify->get_fix_by_id("floor");
  EXPECT_EQ(floor->compute_vector(8), 1.0);
  // (momentum given to the floor over the 4 time units since it was defined)
  EXPECT_NEAR(floor->compute_vector(5) * 4.0, -vx, 1e-12);
  EXPECT_NEAR(floor->compute_vector(6) * 4.0, -1.8, 1e-12);
  EXPECT_NEAR(floor->compute_vector(9), 0.5 * (vx * vx + 0.64 - 1.0) + 0.5 * q * 0.25 *
              lmp->atom->omega[0][2] * lmp->atom->omega[0][2], 1e-12);
}

// The same disc onto a floor shaken along x, A sin(omega t): the floor's surface moves at
// A omega cos(omega t_c) when the disc lands at t_c = 2.5, and drags it by the rough law's share
TEST(FixHardsphereWall, ShakenFloorDragsAnAtomAtItsPhase)
{
  auto lmp = make_lammps();
  run(lmp.get(), disc_onto_floor("shake x 0.3 2.0"));
  const double q = 0.5, beta = 0.2, u = 0.3 * 2.0 * std::cos(2.0 * 2.5);
  EXPECT_NEAR(lmp->atom->v[0][0], (1.0 + beta) * q / (1.0 + q) * u, 1e-12);
  EXPECT_NEAR(lmp->atom->v[0][1], 0.8, 1e-12);
}

// A Couette cell: the floor and the lid slide in opposite directions; in the steady state the
// momentum the lid gives the gas along x is what the floor takes (the wall forces balance),
// and the shear force is nonzero
TEST(FixHardsphereWall, CouetteWallForcesBalance)
{
  auto lmp = make_lammps();
  run(lmp.get(), walled_gas(150, 20.0, 37, "f") +
                     "pair_style hardsphere/rough inertia disc\npair_coeff * * 1.0 -1.0\n"
                     "fix ed all hardsphere/ed\n"
                     "fix floor all hardsphere/wall ylo EDGE thermal 1.0 4099 slide -0.5 0.0 0.0\n"
                     "fix lid all hardsphere/wall yhi EDGE thermal 1.0 4111 slide 0.5 0.0 0.0\n"
                     "timestep 0.5\nthermo 0\nrun 400 post no\n"
                     "unfix floor\nunfix lid\n"
                     "fix floor all hardsphere/wall ylo EDGE thermal 1.0 4099 slide -0.5 0.0 0.0\n"
                     "fix lid all hardsphere/wall yhi EDGE thermal 1.0 4111 slide 0.5 0.0 0.0\n"
                     "run 2000 post no");
  auto *floor = lmp->modify->get_fix_by_id("floor"), *lid = lmp->modify->get_fix_by_id("lid");
  const double ffloor = floor->compute_vector(5), flid = lid->compute_vector(5);
  EXPECT_GT(ffloor, 0.0) << "the gas drags the floor toward +x";
  EXPECT_LT(flid, 0.0) << "and the lid toward -x";
  EXPECT_NEAR(ffloor + flid, 0.0, 0.1 * ffloor);
}

// the floor's totals (collisions, momentum and energy exchanged, time) continue across a restart
TEST(FixHardsphereWall, TotalsKeptInRestartFiles)
{
  const std::string s = walled_gas(80, 20.0, 17, "m");
  const std::string fixes = "fix ed all hardsphere/ed gravity 0.0 -0.5 0.0 tc 0.05\n"
                            "fix floor all hardsphere/wall ylo 0.0 coeffs 0.8 -1.0\n"
                            "timestep 0.2\nthermo 0\n";
  const std::string rst = "granfric_test_wall_" + std::to_string(::getpid()) + ".restart";
  double before[10];
  {
    auto a = make_lammps();
    run(a.get(), s + "pair_style hardsphere/rough inertia disc\npair_coeff * * 0.9 -1.0\n" + fixes +
                     "run 50 post no\nwrite_restart " + rst);
    for (int k = 0; k < 10; k++) before[k] = a->modify->get_fix_by_id("floor")->compute_vector(k);
  }
  auto b = make_lammps();
  run(b.get(), "read_restart " + rst + "\ncomm_modify vel yes\n" + fixes);
  std::remove(rst.c_str());
  auto *floor = b->modify->get_fix_by_id("floor");
  EXPECT_GT(before[8], 10.0) << "collisions with the floor";
  EXPECT_LT(before[9], 0.0) << "an inelastic floor takes energy";
  for (int k = 5; k < 10; k++) EXPECT_EQ(floor->compute_vector(k), before[k]) << "element " << k + 1;
}

// a ball dropped on an inelastic floor bounces infinitely often in finite time (r^k series):
// without the TC model the event cap stops the run with a clear error, with it the ball rests
TEST(FixHardsphereWall, BouncingBallCollapseAndTC)
{
  const std::string ball = "units lj\ndimension 2\natom_style sphere\nboundary p f p\n"
                           "comm_modify vel yes\nregion box block 0 10 0 10 -0.5 0.5\n"
                           "create_box 1 box\ncreate_atoms 1 single 5 3 0\n"
                           "pair_style hardsphere/rough inertia disc\npair_coeff * * 0.8 -1.0\n"
                           "fix floor all hardsphere/wall ylo EDGE\ntimestep 10.0\nthermo 0\n";
  auto lmp = make_lammps();
  run(lmp.get(), ball + "fix ed all hardsphere/ed gravity 0 -1 0 maxevents 10000");
  // it reaches the floor after 2.2 time units and would come to rest at t = 20
  EXPECT_LMP_ERROR(lmp.get(), "run 3 post no",
                   "atom 1 had 10001 collisions within step [0-9]+ \\(maxevents 10000\\), the "
                   "last one with fix hardsphere/wall floor at time .*: inelastic collapse. Use the TC model");
  lmp.reset();
  auto l2 = make_lammps();
  // with t_c the ball ends up bouncing elastically with a period below t_c (height < g t_c^2/8)
  run(l2.get(), ball + "fix ed all hardsphere/ed gravity 0 -1 0 maxevents 10000 tc 0.05\n"
                       "run 3 post no");
  EXPECT_GE(l2->atom->x[0][1], 0.5 - 1e-9);
  EXPECT_LT(l2->atom->x[0][1], 0.5 + 0.05 * 0.05 / 8 + 1e-9);
}

// a bed settling on a thermal floor at a small temperature (with the TC model) stays agitated at
// about that temperature: its collisions per step level off instead of growing as it cools, and
// no grain gets below the floor
TEST(FixHardsphereWall, BedSettlesOnAThermalFloor)
{
  auto lmp = make_lammps();
  run(lmp.get(), "units lj\ndimension 2\natom_style sphere\nboundary p f p\ncomm_modify vel yes\n"
                 "region box block 0 14 0 40 -0.5 0.5\ncreate_box 1 box\nlattice sq 0.25\n"
                 "region start block 0.5 13.5 0.5 39 -0.5 0.5 units box\n"
                 "create_atoms 1 region start\nset type 1 diameter 1.0\nset type 1 mass 1.0\n"
                 "velocity all create 1.0 5 loop geom mom yes dist gaussian\n"
                 "pair_style hardsphere/rough inertia disc\npair_coeff * * 0.5 0.0\n"
                 "fix ed all hardsphere/ed gravity 0.0 -0.2 0.0 tc 0.01\n"
                 "fix floor all hardsphere/wall ylo 0.0 thermal 0.001 7\n"
                 "fix lid all hardsphere/wall yhi EDGE\ntimestep 0.05\nthermo 0\n"
                 "run 600 post no");    // (settled: the bed's top below 8 diameters)
  auto *ed = lmp->modify->get_fix_by_id("ed");
  const double n0 = ed->compute_vector(1);
  run(lmp.get(), "run 600 post no");
  const double n1 = ed->compute_vector(1);
  run(lmp.get(), "run 600 post no");
  const double n2 = ed->compute_vector(1);
  ASSERT_EQ(lmp->atom->natoms, 114);
  double ke = 0.0, top = 0.0;
  for (int i = 0; i < lmp->atom->nlocal; i++) {
    const double *v = lmp->atom->v[i];
    EXPECT_GE(lmp->atom->x[i][1], 0.5 - 1e-9) << "atom " << lmp->atom->tag[i];
    top = std::max(top, lmp->atom->x[i][1]);
    ke += 0.5 * (v[0] * v[0] + v[1] * v[1]);
  }
  EXPECT_LT(top, 8.0) << "a settled bed of about 8 layers";
  // about k T per disc in translation (measured 0.6 - 0.8 of it), far below the 1 it began with
  EXPECT_GT(ke / 114, 1e-4);
  EXPECT_LT(ke / 114, 3e-3);
  // measured 2300 - 3800 collisions per step for 12000 steps; an inelastic floor grew 14x from
  // step 1000 to 2000
  EXPECT_GT(n1 - n0, 600 * 1000.0);
  EXPECT_LT((n2 - n1) / (n1 - n0), 1.5);
  EXPECT_GT((n2 - n1) / (n1 - n0), 0.67);
}

// a vibrating base (piecewise parabolic) under an elastic bed: it injects energy, and no
// particle ever gets below it
TEST(FixHardsphereWall, VibratingBaseInjectsEnergy)
{
  for (const std::string motion : {"parabolic", "sine"}) {
  auto lmp = make_lammps();
  run(lmp.get(), "units lj\ndimension 2\natom_style sphere\nboundary p m p\ncomm_modify vel yes\n"
                 "region box block 0 20 0 20 -0.5 0.5\ncreate_box 1 box\n"
                 "region inner block EDGE EDGE 1.0 19 EDGE EDGE\n"
                 "create_atoms 1 random 80 17 inner overlap 1.05 maxtry 1000\n"
                 "set type 1 diameter 1.0\nset type 1 mass 1.0\n"
                 "velocity all create 0.01 5 loop geom mom yes dist gaussian\n"
                 "pair_style hardsphere/rough inertia disc\npair_coeff * * 1.0 -1.0\n"
                 "fix ed all hardsphere/ed gravity 0 -1 0 tc 1e-4\n"
                 "fix base all hardsphere/wall ylo EDGE vibrate " + motion + " 0.1 10.0\n"
                 "timestep 0.05\nthermo 0");
  auto *base = lmp->modify->get_fix_by_id("base");
  for (int s = 0; s < 200; s++) {
    run(lmp.get(), "run 1 post no");
    const double floor = base->compute_vector(0);
    EXPECT_LE(std::fabs(floor), 0.1 + 1e-12);
    for (int i = 0; i < lmp->atom->nlocal; i++)
      ASSERT_GE(lmp->atom->x[i][1] - lmp->atom->radius[i], floor - 1e-9) << "below the base";
  }
  auto *ed = lmp->modify->get_fix_by_id("ed");
  EXPECT_GT(ed->compute_vector(9), 100.0) << "wall collisions";
  EXPECT_GT(ed->compute_vector(10), 0.0) << "energy injected by the base";
  // compute hardsphere/collisions books pair and wall collisions apart
  run(lmp.get(), "compute c all hardsphere/collisions ed\nthermo_style custom step c_c[2] c_c[6]\n"
                 "run 100 post no");
  auto *c = lmp->modify->get_compute_by_id("c");
  c->compute_vector();
  EXPECT_GT(c->vector[6], 10.0) << "wall collisions in the window";
  EXPECT_GT(c->vector[5], 0.0) << "the base injects energy per wall collision";
  EXPECT_EQ(c->vector[1], 0.0) << "elastic pair collisions lose nothing";
  }
}

TEST_F(FixErrors, Wall)
{
  run(lmp.get(), "fix ed all hardsphere/ed");
  EXPECT_LMP_ERROR(lmp.get(), "fix w all hardsphere/wall ylo EDGE",
                   "face ylo needs a non-periodic boundary in y");
  EXPECT_LMP_ERROR(lmp.get(), "fix w all hardsphere/wall top EDGE",
                   "face top is not one of xlo, xhi, ylo, yhi, zlo, zhi");
  EXPECT_LMP_ERROR(lmp.get(), "fix w all hardsphere/wall zlo EDGE", "not allowed in a 2d simulation");
  EXPECT_LMP_ERROR(lmp.get(), "fix w all hardsphere/wall ylo", "Illegal fix hardsphere/wall");
  lmp.reset();
  auto l = make_lammps();
  run(l.get(), "units lj\ndimension 2\natom_style sphere\nboundary p f p\ncomm_modify vel yes\n"
               "region box block 0 10 0 10 -0.5 0.5\ncreate_box 1 box\ncreate_atoms 1 single 5 5 0\n"
               "pair_style hardsphere/rough\npair_coeff * * 0.9 0.0\nfix ed all hardsphere/ed");
  // (a fix whose constructor failed leaves its ID half-defined in LAMMPS: use fresh IDs)
  EXPECT_LMP_ERROR(l.get(), "fix w1 all hardsphere/wall ylo abc", "Expected floating point");
  EXPECT_LMP_ERROR(l.get(), "fix w2 all hardsphere/wall ylo EDGE spin 3",
                   "Unknown fix hardsphere/wall keyword: spin \\(allowed: coeffs, thermal, vibrate, slide, shake\\)");
  EXPECT_LMP_ERROR(l.get(), "fix w8 all hardsphere/wall ylo EDGE thermal -1 5", "thermal T = -1 must be > 0");
  EXPECT_LMP_ERROR(l.get(), "fix w11 all hardsphere/wall ylo EDGE vibrate square 0.1 10",
                   "vibrate square is not available \\(allowed: sine, parabolic\\)");
  EXPECT_LMP_ERROR(l.get(), "fix w12 all hardsphere/wall ylo EDGE vibrate parabolic 0 10",
                   "amplitude A = 0 must be > 0");
  EXPECT_LMP_ERROR(l.get(), "fix w13 all hardsphere/wall ylo EDGE vibrate parabolic 0.1 -1",
                   "angular frequency = -1 must be > 0");
  EXPECT_LMP_ERROR(l.get(), "fix w15 all hardsphere/wall ylo EDGE vibrate parabolic 0.1",
                   "Illegal fix hardsphere/wall vibrate sine\\|parabolic A omega");
  EXPECT_LMP_ERROR(l.get(), "fix w16 all hardsphere/wall ylo EDGE vibrate parabolic 0.1 10 thermal 1 5",
                   "a thermal wall cannot vibrate");
  EXPECT_LMP_ERROR(l.get(), "fix w9 all hardsphere/wall ylo EDGE thermal 1 0", "thermal seed = 0 must be > 0");
  EXPECT_LMP_ERROR(l.get(), "fix w10 all hardsphere/wall ylo EDGE thermal 1",
                   "Illegal fix hardsphere/wall thermal T seed");
  EXPECT_LMP_ERROR(l.get(), "fix w3 all hardsphere/wall ylo EDGE coeffs",
                   "coeffs needs the law's coefficients");
  run(l.get(), "fix w4 all hardsphere/wall ylo EDGE coeffs 0.9");
  EXPECT_LMP_ERROR(l.get(), "run 0", "coeffs: 1 values given, pair style hardsphere/rough takes 2 \\(r beta\\)");
  run(l.get(), "unfix w4\nfix w5 all hardsphere/wall ylo EDGE coeffs 1.5 0.0");
  EXPECT_LMP_ERROR(l.get(), "run 0", "r = 1.5 is out of range");
  run(l.get(), "unfix w5\nfix w6 all hardsphere/wall ylo 12.0");
  EXPECT_LMP_ERROR(l.get(), "run 0", "position 12 lies outside the box");
  run(l.get(), "unfix w6\nunfix ed\nfix w7 all hardsphere/wall ylo EDGE\nfix n all nve/sphere");
  EXPECT_LMP_ERROR(l.get(), "run 0", "needs fix hardsphere/ed");
}

TEST(ComputeConvection, OneAndTwoRolls)
{
  auto lmp = make_lammps();
  run(lmp.get(), "units lj\ndimension 2\natom_style sphere\ncomm_modify vel yes\n"
                 "region box block -3 17 0 20 -0.5 0.5\ncreate_box 1 box\n"
                 "lattice sq 1.0\ncreate_atoms 1 box\nset type 1 diameter 0.9\n"
                 "variable vy atom 0.3*sin(2*PI*(x+3)/20)\n"
                 "velocity all set 0.0 v_vy 0.0\ncompute c all hardsphere/convection\n"
                 "thermo_style custom step c_c[1] c_c[2]\nrun 0 post no");
  auto *c = lmp->modify->get_compute_by_id("c");
  c->compute_vector();
  EXPECT_NEAR(c->vector[0], 0.15, 1e-12);    // <0.3 sin^2> = 0.15
  EXPECT_NEAR(c->vector[1], 0.0, 1e-12);
  run(lmp.get(), "variable vy atom -0.3*cos(2*PI*(x+3)/20)\nvelocity all set 0.0 v_vy 0.0");
  c->compute_vector();
  EXPECT_NEAR(c->vector[0], 0.0, 1e-12);
  EXPECT_NEAR(c->vector[1], 0.15, 1e-12);
  EXPECT_LMP_ERROR(lmp.get(), "compute d all hardsphere/convection 3",
                   "Unknown compute hardsphere/convection keyword: 3 \\(allowed: vertical\\)");
}

// In 3d the vertical axis comes from gravity (upward against it) or the keyword, and each
// horizontal axis has its own pair of order parameters
TEST(ComputeConvection, ThreeDimensionsFollowGravity)
{
  auto lmp = make_lammps();
  run(lmp.get(), "units lj\natom_style sphere\ncomm_modify vel yes\n"
                 "region box block -3 7 0 4 0 4\ncreate_box 1 box\n"
                 "lattice sc 1.0\ncreate_atoms 1 box\nset type 1 diameter 0.9\nset type 1 mass 1.0\n"
                 "pair_style hardsphere/rough\npair_coeff * * 0.9 0.0\n"
                 "variable vz atom 0.3*sin(2*PI*(x+3)/10)\n"
                 "velocity all set 0.0 0.0 v_vz\nfix ed all hardsphere/ed gravity 0 0 -1\n"
                 "compute c all hardsphere/convection\ncompute v all hardsphere/convection vertical x\n"
                 "thermo_style custom step c_c[1] c_v[1]\nrun 0 post no");
  auto *c = lmp->modify->get_compute_by_id("c");
  ASSERT_EQ(c->size_vector, 4);
  c->compute_vector();
  EXPECT_NEAR(c->vector[0], 0.15, 1e-12);    // along x: <0.3 sin^2> = 0.15
  EXPECT_NEAR(c->vector[1], 0.0, 1e-12);
  EXPECT_NEAR(c->vector[2], 0.0, 1e-12);     // along y: v_z does not vary with y
  EXPECT_NEAR(c->vector[3], 0.0, 1e-12);
  auto *v = lmp->modify->get_compute_by_id("v");    // (x vertical: v_x = 0 everywhere)
  v->compute_vector();
  for (int k = 0; k < 4; k++) EXPECT_EQ(v->vector[k], 0.0);
  // gravity upward: the upward velocity is -v_z
  run(lmp.get(), "unfix ed\nfix ed all hardsphere/ed gravity 0 0 1\nrun 0 post no");
  c->compute_vector();
  EXPECT_NEAR(c->vector[0], -0.15, 1e-12);
  run(lmp.get(), "unfix ed\nfix ed all hardsphere/ed\n");
  EXPECT_LMP_ERROR(lmp.get(), "run 0 post no", "in 3d needs a vertical axis");
}

TEST_F(FixErrors, Computes)
{
  EXPECT_LMP_ERROR(lmp.get(), "compute t all hardsphere/temp inertia cube",
                   "inertia must be sphere, disc or a number 0 < q <= 1, not cube");
  EXPECT_LMP_ERROR(lmp.get(), "compute t all hardsphere/temp inertia 1.2",
                   "inertia q = I/\\(m a\\^2\\) = 1.2 is out of range \\(0 < q <= 1\\)");
  EXPECT_LMP_ERROR(lmp.get(), "compute t all hardsphere/temp inertia", "Illegal compute hardsphere/temp inertia");
  EXPECT_LMP_ERROR(lmp.get(), "compute t all hardsphere/temp mass 1",
                   "Unknown compute hardsphere/temp keyword: mass \\(allowed: inertia\\)");
  EXPECT_LMP_ERROR(lmp.get(), "compute c all hardsphere/collisions",
                   "Illegal compute hardsphere/collisions");
  EXPECT_LMP_ERROR(lmp.get(), "compute c all hardsphere/collisions ed bins 0",
                   "bins = 0 is out of range \\(1..100000\\)");
  EXPECT_LMP_ERROR(lmp.get(), "compute c all hardsphere/collisions ed window 3",
                   "Unknown compute hardsphere/collisions keyword: window \\(allowed: bins\\)");
  run(lmp.get(), "compute c all hardsphere/collisions nofix\nthermo_style custom step c_c[1]");
  EXPECT_LMP_ERROR(lmp.get(), "run 0", "fix ID nofix does not exist");
  run(lmp.get(), "uncompute c\nfix m all momentum 1 linear 1 1 1\n"
                 "compute c all hardsphere/collisions m\nthermo_style custom step c_c[1]");
  EXPECT_LMP_ERROR(lmp.get(), "run 0", "fix m is of style momentum, not hardsphere/ed");
  run(lmp.get(), "uncompute c\nunfix m\nfix ed all hardsphere/ed\n"
                 "compute c1 all hardsphere/collisions ed bins 10\n"
                 "compute c2 all hardsphere/collisions ed bins 20\n"
                 "thermo_style custom step c_c1[1] c_c2[1]");
  EXPECT_LMP_ERROR(lmp.get(), "run 0", "computes asked for 10 and 20 impact-angle bins");
}

// The scalar of compute hardsphere/temp is the translational temperature T_tr with d N degrees
// of freedom: LAMMPS's temperature commands take it (thermo_modify temp, velocity scale,
// compute pressure, whose kinetic part is then sum m v^2 / (d V) exactly)
TEST(ComputeTemp, ScalarIsATemperatureForLammps)
{
  for (int dim = 2; dim <= 3; dim++) {
    auto lmp = make_lammps();
    run(lmp.get(), gas(dim, dim == 2 ? 150 : 120, dim == 2 ? 22.0 : 9.0, 5) +
                       "pair_style hardsphere/rough" + (dim == 2 ? " inertia disc" : "") +
                       "\npair_coeff * * 0.9 0.2\nfix ed all hardsphere/ed\ncompute T all hardsphere/temp\n"
                       "thermo_modify temp T\nvelocity all scale 2.5 temp T\ncompute P all pressure T\n"
                       "timestep 0.1\nthermo 0\nrun 3 post no");
    auto *T = lmp->modify->get_compute_by_id("T");
    const double n = (double) lmp->atom->natoms;
    EXPECT_EQ(T->dof, dim * n);
    double mv2 = 0.0;
    for (int i = 0; i < lmp->atom->nlocal; i++) {
      const double *v = lmp->atom->v[i];
      mv2 += lmp->atom->rmass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    }
    EXPECT_NEAR(T->compute_scalar(), mv2 / (dim * n), 1e-12 * mv2);
    T->compute_vector();
    EXPECT_NEAR(T->compute_scalar(), T->vector[0], 1e-12) << "the scalar is T_tr";
    run(lmp.get(), "velocity all scale 2.5 temp T");
    EXPECT_NEAR(T->compute_scalar(), 2.5, 1e-12);
    auto *fix = lmp->modify->get_fix_by_id("ed");
    auto *P = lmp->modify->get_compute_by_id("P");
    run(lmp.get(), "run 1 post no");
    const double vol = lmp->domain->xprd * lmp->domain->yprd * (dim == 3 ? lmp->domain->zprd : 1.0);
    mv2 = T->compute_scalar() * dim * n;
    const double tr = fix->virial[0] + fix->virial[1] + (dim == 3 ? fix->virial[2] : 0.0);
    EXPECT_NEAR(P->compute_scalar(), (mv2 + tr) / (dim * vol), 1e-10 * (mv2 + std::fabs(tr)) / vol);
  }
}

TEST(ComputeTemp, PairStyleWithoutShapeFactorNeedsInertia)
{
  auto lmp = make_lammps();
  run(lmp.get(), gas(2, 20, 10.0, 5) +
                     "pair_style granular\npair_coeff * * hooke 1000.0 50.0 tangential "
                     "linear_nohistory 1.0 0.4\ncompute t all hardsphere/temp\n"
                     "thermo_style custom step c_t[1]");
  EXPECT_LMP_ERROR(lmp.get(), "run 0", "give it with the inertia keyword");
  run(lmp.get(), "uncompute t\ncompute t all hardsphere/temp inertia disc\n"
                 "thermo_style custom step c_t[1] c_t[2]\nrun 0 post no");
  lmp.reset();
  auto l3 = make_lammps();
  run(l3.get(), gas(3, 20, 8.0, 5));
  EXPECT_LMP_ERROR(l3.get(), "compute t all hardsphere/temp inertia disc",
                   "inertia disc requires a 2d simulation");
}

TEST(FixErrorsBox, NonPeriodicAndPointParticles)
{
  auto lmp = make_lammps();
  run(lmp.get(), "units lj\ndimension 2\natom_style sphere\nboundary p f p\ncomm_modify vel yes\n"
                 "region box block 0 10 0 10 -0.5 0.5\ncreate_box 1 box\ncreate_atoms 1 single 5 5 0\n"
                 "pair_style hardsphere/rough\npair_coeff * * 0.9 0.0\nfix ed all hardsphere/ed");
  EXPECT_LMP_ERROR(lmp.get(), "run 0", "the non-periodic dimension y needs a fix hardsphere/wall");
  lmp.reset();
  auto l2 = make_lammps();
  run(l2.get(), "units lj\ndimension 2\natom_style sphere\nboundary p p p\ncomm_modify vel yes\n"
                "region box block 0 10 0 10 -0.5 0.5\ncreate_box 1 box\ncreate_atoms 1 single 5 5 0\n"
                "set atom 1 diameter 0.0\nset atom 1 mass 1.0\n"
                "pair_style hardsphere/rough\npair_coeff * * 0.9 0.0\nfix ed all hardsphere/ed");
  EXPECT_LMP_ERROR(l2.get(), "run 0", "requires every atom to have a radius > 0");
}

}    // namespace
