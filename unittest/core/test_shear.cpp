// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// Core tests of Lees-Edwards boundaries (EDOptions::shear): trajectories in a sheared periodic
// box equal the brute-force reference, whose images across the y faces are shifted and move in
// x independently of the core's cells and shear ticks; with the queue kept across windows; a
// static tilt; the shear work against the energy balance; the options refused.
#include "ed_fixture.h"

#include <gtest/gtest.h>

using namespace granfric;
using namespace granfric_test;

namespace {

struct ShearCase {
  int law, dim, n;
  double phi, rate, dt_mft, T_mft;    // rate: the shear rate in units of the rms speed
};

class Sheared : public ::testing::TestWithParam<ShearCase> {};

double rms_speed(const Reference &ref)
{
  double s = 0.0;
  for (const auto &a : ref.p) s += norm2(a.v);
  return std::sqrt(s / ref.p.size());
}

// a system of the case with its shear: the image one period up moves at rate times the rms
// speed, and starts shifted by a third of the box
Reference sheared_system(const ShearCase &c, unsigned seed)
{
  SystemSpec s;
  s.n = c.n;
  s.dim = c.dim;
  s.phi = c.phi;
  s.q = c.dim == 2 ? 0.5 : 0.4;
  s.seed = seed;
  Reference ref = make_system(s, law_of(c.law));
  ref.shear = true;
  ref.shear_rate = c.rate * rms_speed(ref);
  ref.shift0 = 0.37 * ref.L.x;
  return ref;
}

TEST_P(Sheared, EqualsBruteForceReference)
{
  const ShearCase c = GetParam();
  Reference ref = sheared_system(c, 300 + c.law * 10 + c.dim + c.n);
  const double mft = mean_free_time(ref);
  const double T = c.T_mft * mft;
  CoreRun run(ref);
  run.run(T, c.dt_mft * mft);
  ref.run_until(T);
  ASSERT_GE(ref.collisions, std::max(4, c.n));
  // the shift went past two cells (of width about a diameter) at least
  EXPECT_GT(std::fabs(ref.shear_rate) * T, 2.0) << "too little shear";
  EXPECT_EQ(run.total.collisions, ref.collisions);
  EXPECT_NEAR(run.total.dE, ref.dE, 1e-9 * std::fabs(ref.dE));
  double vir = 0.0;
  for (int k = 0; k < 3; k++) vir += std::fabs(ref.virial[k]);
  for (int k = 0; k < 6; k++) EXPECT_NEAR(run.total.virial[k], ref.virial[k], 1e-9 * vir) << "component " << k;
  double vrms = rms_speed(ref), dx = 0, dv = 0;
  for (size_t i = 0; i < ref.p.size(); i++) {
    dx = std::max(dx, norm(ref.p[i].x - run.ed.particle((int) i).x));
    dv = std::max(dv, norm(ref.p[i].v - run.ed.particle((int) i).v) / vrms);
  }
  EXPECT_LT(dx, 1e-9);
  EXPECT_LT(dv, 1e-9);
  // no pair overlaps, across the sheared faces either
  run.ed.set_shear_shift(ref.shift(T));
  run.ed.start();
  long ki, kj;
  double depth;
  EXPECT_EQ(run.ed.overlaps(1e-9, ki, kj, depth), 0) << "atoms " << ki << " and " << kj << " overlap by " << depth;
}

std::string shear_name(const ::testing::TestParamInfo<ShearCase> &info)
{
  static const char *law[] = {"rough", "walton", "jz"};
  const ShearCase &c = info.param;
  return std::string(law[c.law]) + "_" + std::to_string(c.dim) + "d_n" + std::to_string(c.n) + "_" +
      std::to_string(info.index);
}

// shear rates of either sign, from slow to faster than the particles; windows from 0.05 to 10
// mean free times
INSTANTIATE_TEST_SUITE_P(
    Core, Sheared,
    ::testing::Values(ShearCase{0, 2, 3, 0.12, 1.0, 0.3, 6}, ShearCase{1, 2, 20, 0.3, 1.0, 1.0, 6},
                      ShearCase{2, 2, 20, 0.3, -2.0, 10.0, 6}, ShearCase{0, 3, 20, 0.2, 1.5, 0.3, 6},
                      ShearCase{1, 3, 20, 0.2, -1.5, 10.0, 6}, ShearCase{0, 2, 200, 0.3, 1.0, 2.0, 4},
                      ShearCase{2, 2, 200, 0.1, -0.3, 0.5, 3}, ShearCase{1, 3, 200, 0.25, 4.0, 1.0, 3},
                      ShearCase{0, 3, 200, 0.1, 3.0, 0.05, 3}),
    shear_name);

// The bands of rows of cells move with the flow and are shifted by D = (s + w L_x) / n_b
// against each other (n_b <= n_y bands): fast shear in dilute gases over long runs, so that D
// passes whole periods of x (its labels start again), in both directions; the brute-force
// reference knows nothing of rows
TEST(Shear, RowsPassingWholePeriodsEqualReference)
{
  const ShearCase cases[] = {ShearCase{0, 2, 8, 0.01, 3.0, 0.5, 0}, ShearCase{2, 2, 8, 0.01, -3.0, 1.0, 0},
                             ShearCase{1, 3, 8, 0.005, 4.0, 0.5, 0}, ShearCase{0, 3, 8, 0.005, -6.0, 1.0, 0}};
  for (const ShearCase &c : cases) {
    Reference ref = sheared_system(c, 500 + c.dim + (c.rate > 0));
    double amax = 0.0;
    for (const auto &a : ref.p) amax = std::max(amax, a.a);
    // (the rows as the core makes them: cells of the automatic width, at least 3 rows; the run
    // lasts until the shift has passed 2.2 times their number of periods)
    const double area = c.dim == 2 ? ref.L.x * ref.L.y : ref.L.x * ref.L.y * ref.L.z;
    const double w = EventDriven::auto_cell_width(c.dim, 2.0 * amax, c.n / area);
    const double rows = std::max(3.0, std::floor(ref.L.y / w));
    const double mft = mean_free_time(ref), T = 2.2 * rows * ref.L.x / std::fabs(ref.shear_rate);
    const Reference start = ref;
    CoreRun run(ref);
    run.run(T, c.dt_mft * mft);
    ref.run_until(T);
    EXPECT_GE(ref.collisions, c.n / 2);
    EXPECT_EQ(run.total.collisions, ref.collisions) << "dim " << c.dim << " rate " << c.rate;
    double dx = 0.0;
    for (size_t i = 0; i < ref.p.size(); i++) dx = std::max(dx, norm(ref.p[i].x - run.ed.particle((int) i).x));
    if (dx < 1e-9) continue;
    // Particles cross the sheared faces many times at speeds of several times the shear rate,
    // and the shift the reference keeps grows without bound, while the core's stays within a
    // period: their roundings differ, and collisions amplify the difference. The reference run
    // again with a shear rate one rounding away (a shift that differs as much as the roundings
    // of the two do) measures how far the trajectory is determined.
    Reference nudged = start;
    nudged.shear_rate = std::nextafter(nudged.shear_rate, 1e300);
    nudged.run_until(T);
    double spread = 0.0;
    for (size_t i = 0; i < ref.p.size(); i++) spread = std::max(spread, norm(nudged.p[i].x - ref.p[i].x));
    EXPECT_LT(dx, 100.0 * spread) << "dim " << c.dim << " rate " << c.rate;
  }
}

// The rows of cells move in bands (EDOptions::shear_band rows each, the last ones one more
// where they do not divide the rows): every choice, from a band per row to one band for the
// box, gives the reference's trajectory and the same bits as a band per row, the cells being
// only where candidates are looked for; in 2d and 3d, slow and fast shear of either sign. (Each
// window starts afresh here. With the queue kept across windows the images' shift is carried
// forward at every window, a pair predicted again later may differ in its last bit, and the
// cells decide when: there the bits depend on the bands.)
TEST(Shear, BandsOfRowsGiveTheSameBits)
{
  const ShearCase cases[] = {ShearCase{0, 2, 200, 0.2, 1.0, 1.0, 3}, ShearCase{2, 2, 200, 0.1, -3.0, 0.5, 3},
                             ShearCase{1, 3, 200, 0.2, 1.5, 1.0, 3}, ShearCase{0, 3, 200, 0.1, -4.0, 0.3, 3}};
  for (const ShearCase &c : cases) {
    const Reference start = sheared_system(c, 700 + c.dim + (c.rate > 0));
    const double mft = mean_free_time(start), T = c.T_mft * mft;
    Reference ref = start;
    ref.run_until(T);
    ASSERT_GE(ref.collisions, c.n);
    std::vector<Vec3> first;
    int bands_seen = 1 << 30, kinds = 0;
    for (int rows : {1, 2, 3, 5, 1000}) {
      SCOPED_TRACE("dim " + std::to_string(c.dim) + ", rate " + std::to_string(c.rate) + ", rows per band " +
                   std::to_string(rows));
      CoreRun run(start);
      EDOptions o = run.ed.options();
      o.shear_band = rows;
      run.ed.configure(o, start.ntypes, start.laws);
      run.run(T, c.dt_mft * mft);
      const int nb = run.ed.shear_band_count();
      EXPECT_LE(nb, bands_seen);
      kinds += nb != bands_seen;
      bands_seen = nb;
      EXPECT_EQ(run.total.collisions, ref.collisions);
      double dx = 0.0;
      for (size_t i = 0; i < ref.p.size(); i++) dx = std::max(dx, norm(ref.p[i].x - run.ed.particle((int) i).x));
      EXPECT_LT(dx, 1e-9);
      for (int i = 0; i < run.ed.size(); i++) {
        const Vec3 x = run.ed.particle(i).x;
        if (rows == 1) {
          first.push_back(x);
          continue;
        }
        ASSERT_TRUE(x.x == first[i].x && x.y == first[i].y && x.z == first[i].z) << "particle " << i;
      }
    }
    EXPECT_EQ(bands_seen, 1);
    EXPECT_GE(kinds, 3);
  }
}

// The automatic bands: as many rows as keep the flow's difference across a band within f times
// the spread of x velocities about the streaming profile (f = 1 in 2d, 3 in 3d); one band
// without shear
TEST(Shear, AutomaticBandsFollowTheThermalSpeed)
{
  for (int dim = 2; dim <= 3; dim++)
    for (double rate : {0.0, 0.05, 0.7, 2.3, 6.1}) {
      ShearCase c{0, dim, dim == 2 ? 400 : 2000, 0.2, 1.0, 0.1, 0};
      Reference ref = sheared_system(c, 900 + dim);
      // velocities on the streaming profile, the x spread known
      double n = 0.0, sum = 0.0, sum2 = 0.0;
      for (const auto &a : ref.p) n += 1.0, sum += a.v.x, sum2 += a.v.x * a.v.x;
      const double spread = std::sqrt(sum2 / n - (sum / n) * (sum / n));
      ref.shear_rate = rate * spread;
      for (auto &a : ref.p) a.v.x += ref.shear_rate * (a.x.y - ref.lo[1]) / ref.L.y;
      CoreRun run(ref);
      run.run(0.01 * mean_free_time(ref), 0.01 * mean_free_time(ref));
      const int ny = (int) std::floor(ref.L.y / run.ed.cell_size() + 1e-9);    // (cubic cells)
      const double f = dim == 3 ? 3.0 : 1.0;
      const int rows = rate == 0.0 ? ny : std::min(ny, (int) std::floor(f * ny / rate));
      SCOPED_TRACE(std::to_string(dim) + "D, rate " + std::to_string(rate) + ", rows " + std::to_string(ny));
      EXPECT_EQ(run.ed.shear_band_count(), std::max(1, ny / std::max(1, rows)));
    }
}

// start / advance_to / rebase with the queue kept, as fix hardsphere/ed runs, and gravity
TEST(Shear, QueueKeptAcrossWindowsEqualsReference)
{
  for (int dim = 2; dim <= 3; dim++) {
    SCOPED_TRACE(std::to_string(dim) + "D");
    Reference ref = sheared_system(ShearCase{1, dim, 150, 0.25, 3.0, 0, 0}, 71 + dim);
    ref.gravity = dim == 2 ? Vec3(0.0, 0.0, 0.0) : Vec3(0.0, 0.0, -0.4);
    ref.shift0 = 0.93 * ref.L.x;    // (close to a period: the core's shift passes it)
    ref.tc = 0.005;
    CoreRun run(ref);
    run.ed.set_shear_shift(ref.shift0);
    const double dt = 0.37 * mean_free_time(ref);
    const int nwin = 12;
    kept_queue_equals_reference(ref, run, dt, nwin);
    // the shift the core keeps is the reference's, less whole periods (at least one)
    const double s = ref.shift(nwin * dt), k = std::round((s - run.ed.shear_shift()) / ref.L.x);
    EXPECT_NEAR(run.ed.shear_shift() + k * ref.L.x, s, 1e-9 * ref.L.x);
    EXPECT_GE(k, 1.0);
  }
}

// A sheared slab between walls on the z faces (the walls a sheared box allows), under gravity
// along -z: z is not periodic, so the rows of cells next to the walls have no layer beyond them
TEST(Shear, SlabBetweenZWallsEqualsReference)
{
  for (double rate : {2.0, -1.0}) {
    Reference ref = sheared_system(ShearCase{1, 3, 150, 0.2, rate, 0, 0}, 61 + (rate > 0));
    ref.periodic[2] = false;
    ref.walls.push_back({2, -1, ref.lo.z - 0.6, LawParams::walton(0.8, 0.3, 0.4)});
    ref.walls.push_back({2, +1, ref.lo.z + ref.L.z + 0.6, LawParams::rough(0.9, 0.0)});
    ref.gravity = Vec3(0.0, 0.0, -0.3);
    CoreRun run(ref);
    run.ed.set_shear_shift(ref.shift0);
    const double dt = 0.45 * mean_free_time(ref);
    kept_queue_equals_reference(ref, run, dt, 12);
    EXPECT_GT(ref.wall_collisions, 10);
    EXPECT_EQ(run.total.wall_collisions, ref.wall_collisions);
  }
}

// a static tilt (shift without rate): the same as the reference's tilted lattice
TEST(Shear, StaticTiltEqualsReference)
{
  for (int dim = 2; dim <= 3; dim++) {
    Reference ref = sheared_system(ShearCase{0, dim, 60, 0.3, 0.0, 0, 0}, 81 + dim);
    ref.shift0 = -1.3 * ref.L.x;
    const double mft = mean_free_time(ref);
    CoreRun run(ref);
    run.run(5 * mft, 0.7 * mft);
    ref.run_until(5 * mft);
    EXPECT_EQ(run.total.collisions, ref.collisions);
    for (size_t i = 0; i < ref.p.size(); i++) EXPECT_LT(norm(run.ed.particle((int) i).x - ref.p[i].x), 1e-9);
  }
}

// Elastic smooth particles: no energy is lost in collisions, and the shear heats the gas: the
// kinetic energy of the velocities relative to the streaming profile u (y - lo_y) / L_y grows
// (viscous heating), and that profile is continuous across the y faces, where a particle's
// stored velocity is its image's
TEST(Shear, ElasticGasHeats)
{
  Reference ref = sheared_system(ShearCase{0, 2, 200, 0.2, 3.0, 0, 0}, 91);
  ref.laws.assign(9, LawParams::rough(1.0, -1.0));
  auto peculiar = [&](const CoreRun &r) {
    double e = 0.0;
    for (int i = 0; i < r.ed.size(); i++) {
      const auto p = r.ed.particle(i);
      Vec3 c = p.v;
      c.x -= ref.shear_rate * (p.x.y - ref.lo.y) / ref.L.y;
      e += 0.5 * p.m * norm2(c);
    }
    return e;
  };
  for (auto &a : ref.p) a.v.x += ref.shear_rate * (a.x.y - ref.lo.y) / ref.L.y;    // (the profile at the start)
  // (the x momentum relative to the profile is conserved: a particle's stored velocity less
  // the profile at its unwrapped position is the same in every image)
  auto drift = [&](const CoreRun &r) {
    double p = 0.0;
    for (int i = 0; i < r.ed.size(); i++) {
      const auto q = r.ed.particle(i);
      p += q.m * (q.v.x - ref.shear_rate * (q.x.y - ref.lo.y) / ref.L.y);
    }
    return p;
  };
  CoreRun run(ref);
  const double e0 = peculiar(run), p0 = drift(run), mft = mean_free_time(ref);
  run.run(20 * mft, 2 * mft);
  EXPECT_GT(peculiar(run), 1.2 * e0);
  double py = 0.0;    // (less the profile's change along the y momentum's path)
  for (const auto &q : ref.p) py += q.m * q.v.y;
  EXPECT_NEAR(drift(run), p0 - ref.shear_rate / ref.L.y * py * run.time, 1e-9 * std::sqrt(e0 * ref.p.size()));
  EXPECT_NEAR(run.total.dE, 0.0, 1e-9 * e0);
}

TEST(Shear, OptionsRefused)
{
  EventDriven ed;
  std::vector<LawParams> laws(4, LawParams::rough(0.9, 0.0));
  EDOptions o;
  o.dim = 2;
  o.shear_rate = 1.0;
  EXPECT_THROW(ed.configure(o, 1, laws), std::invalid_argument);    // (a rate without shear)
  o.shear = true;
  o.periodic[1] = false;
  o.open[1] = true;
  EXPECT_THROW(ed.configure(o, 1, laws), std::invalid_argument);    // (y not periodic)
  o.periodic[1] = true;
  o.open[1] = false;
  o.neighbours = EDOptions::LISTS;
  EXPECT_THROW(ed.configure(o, 1, laws), std::invalid_argument);    // (lists)
  o.neighbours = EDOptions::CELLS;
  o.shear_rate = INFINITY;
  EXPECT_THROW(ed.configure(o, 1, laws), std::invalid_argument);
  o.shear_rate = 1.0;
  o.shear_band = -1;
  EXPECT_THROW(ed.configure(o, 1, laws), std::invalid_argument);    // (rows per band)
  o.shear_band = 0;
  EXPECT_NO_THROW(ed.configure(o, 1, laws));
  EXPECT_THROW(ed.set_shear_shift(NAN), std::invalid_argument);
}

}    // namespace
