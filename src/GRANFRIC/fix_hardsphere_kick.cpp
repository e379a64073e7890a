// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: fix hardsphere/kick (see the header and doc/fix_hardsphere_kick.rst)
------------------------------------------------------------------------- */

#include "fix_hardsphere_kick.h"

#include "hardsphere_host.h"
#include "fixed_sum.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "modify.h"
#include "update.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>

using namespace LAMMPS_NS;

FixHardsphereKick::FixHardsphereKick(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), spin(0.0), momentum(1), next_kick(0), started(false)
{
  if (narg < 6) utils::missing_cmd_args(FLERR, "fix hardsphere/kick f_dr v_dr seed", error);
  fdr = utils::numeric(FLERR, arg[3], false, lmp);
  vdr = utils::numeric(FLERR, arg[4], false, lmp);
  seed = utils::bnumeric(FLERR, arg[5], false, lmp);
  if (!(fdr > 0.0)) error->all(FLERR, "Fix hardsphere/kick f_dr = {} must be > 0", fdr);
  if (!(vdr >= 0.0)) error->all(FLERR, "Fix hardsphere/kick v_dr = {} must be >= 0", vdr);
  if (vdr > MAX_VDR)
    error->all(FLERR, "Fix hardsphere/kick v_dr = {} is out of range (at most {:g}: the energy a "
               "kick adds, m v_dr^2, must stay finite)", vdr, MAX_VDR);
  if (seed <= 0) error->all(FLERR, "Fix hardsphere/kick seed = {} must be > 0", seed);
  int iarg = 6;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "momentum") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix hardsphere/kick momentum", error);
      momentum = utils::logical(FLERR, arg[iarg + 1], false, lmp);
      iarg += 2;
    } else if (strcmp(arg[iarg], "spin") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix hardsphere/kick spin", error);
      spin = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(spin >= 0.0))
        error->all(FLERR, "Fix hardsphere/kick spin = {} must be >= 0 (rotational power as a "
                   "fraction of the translational power)", spin);
      iarg += 2;
    } else {
      error->all(FLERR, "Unknown fix hardsphere/kick keyword: {} (allowed: momentum, spin)",
                 arg[iarg]);
    }
  }
  scalar_flag = 1;
  global_freq = 1;
  extscalar = 0;
  restart_global = 1;
}

int FixHardsphereKick::setmask()
{
  return 0;    // called by fix hardsphere/ed inside its window
}

void FixHardsphereKick::init()
{
  hardsphere::require_ed(lmp, style, id, "applies the kicks at their times inside each step");
  check_kicks_per_step();
  // the first kick of a new run is the first kick time at or after the current time
  if (!started) {
    const double now = hardsphere::time_at_step(update, update->ntimestep);
    next_kick = std::max(next_kick, (long) std::ceil(now * fdr - 1e-9));
    started = true;
  }
}

// Every kick of a step is processed inside it, each over all atoms (brought to the kick time
// and predicted afresh): a bound on both keeps a step finite. The kick indices of the run stay
// exact in a double.
void FixHardsphereKick::check_kicks_per_step() const
{
  const double per_step = fdr * update->dt, natoms = (double) atom->natoms;
  if (per_step > MAX_KICKS_PER_STEP)
    error->all(FLERR, "Fix hardsphere/kick {}: f_dr = {:g} gives {:.6g} kicks per step of {} (at most "
               "{:g} are allowed): lower f_dr or the timestep", id, fdr, per_step, update->dt,
               MAX_KICKS_PER_STEP);
  if (per_step * natoms > MAX_ATOM_KICKS_PER_STEP)
    error->all(FLERR, "Fix hardsphere/kick {}: {:.6g} kicks per step (f_dr = {:g}, timestep {}) on "
               "{:.0f} atoms are {:.6g} atom kicks per step (at most {:g} are allowed): lower f_dr "
               "or the timestep", id, per_step, fdr, update->dt, natoms, per_step * natoms,
               MAX_ATOM_KICKS_PER_STEP);
  const double t_end = hardsphere::time_at_step(update, update->laststep);
  if (fdr * std::fabs(t_end) > MAX_KICK_INDEX)
    error->all(FLERR, "Fix hardsphere/kick {}: f_dr = {:g} reaches kick index {:.6g} by the end of "
               "the run at time {:.6g} (at most {:g}: kick times k/f_dr must stay exact)", id, fdr,
               fdr * std::fabs(t_end), t_end, MAX_KICK_INDEX);
}

double FixHardsphereKick::compute_scalar()
{
  return (double) next_kick;
}

void FixHardsphereKick::kicks_in(double t0, double t1, std::vector<double> &times,
                                 std::vector<long> &index)
{
  while (next_kick / fdr < t1) {
    times.push_back(std::max(next_kick / fdr, t0));
    index.push_back(next_kick);
    next_kick++;
  }
}

// counter-based random numbers: splitmix64 of (seed, atom ID, kick, number) -> two uniforms ->
// Box-Muller; reproducible for an atom on any number of ranks
static inline uint64_t splitmix64(uint64_t z)
{
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

double FixHardsphereKick::gaussian(long seed, long tag, long k, int n)
{
  const uint64_t base = splitmix64(splitmix64(splitmix64((uint64_t) seed) ^ (uint64_t) tag) ^
                                   (uint64_t) k);
  const uint64_t a = splitmix64(base ^ (uint64_t) (2 * (n / 2) + 1));
  const uint64_t b = splitmix64(a);
  const double u1 = ((a >> 11) + 0.5) * 0x1.0p-53;    // (0, 1)
  const double u2 = (b >> 11) * 0x1.0p-53;            // [0, 1)
  const double r = std::sqrt(-2.0 * std::log(u1));
  return (n % 2 == 0) ? r * std::cos(2.0 * M_PI * u2) : r * std::sin(2.0 * M_PI * u2);
}

// The sums over the group are fixed-point sums (core/fixed_sum.h): the shift is the same, bit
// for bit, whatever the atoms' order and their split among ranks. Gaussians from Box-Muller with
// 53-bit uniforms stay below 9 in magnitude.
granfric::Vec3 FixHardsphereKick::momentum_shift(long k, int dim) const
{
  if (!momentum) return granfric::Vec3();
  double mmax = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit) mmax = std::max(mmax, atom->rmass[i]);
  MPI_Allreduce(MPI_IN_PLACE, &mmax, 1, MPI_DOUBLE, MPI_MAX, world);
  const double n = (double) atom->natoms;
  const double sp = granfric::fixed_scale(9.0 * vdr * mmax, n), sm = granfric::fixed_scale(mmax, n);
  int64_t sum[4] = {0, 0, 0, 0};
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    const long t = (long) atom->tag[i];
    const double m = atom->rmass[i];
    for (int d = 0; d < dim; d++) sum[d] += granfric::to_fixed(m * vdr * gaussian(seed, t, k, d), sp);
    sum[3] += granfric::to_fixed(m, sm);
  }
  MPI_Allreduce(MPI_IN_PLACE, sum, 4, MPI_INT64_T, MPI_SUM, world);
  if (sum[3] <= 0) return granfric::Vec3();
  const double M = granfric::from_fixed(sum[3], sm);
  return (1.0 / M) * granfric::Vec3(granfric::from_fixed(sum[0], sp), granfric::from_fixed(sum[1], sp),
                                    granfric::from_fixed(sum[2], sp));
}

void FixHardsphereKick::apply(granfric::EventDriven &ed, const std::vector<tagint> &tag,
                              const std::vector<int> &mask, long k, int dim,
                              const granfric::Vec3 &dvcm) const
{
  using granfric::Vec3;
  const int n = ed.size();
  for (int e = 0; e < n; e++) {
    if (!(mask[e] & groupbit)) continue;
    auto p = ed.particle(e);
    const long t = (long) tag[e];
    p.v += vdr * Vec3(gaussian(seed, t, k, 0), gaussian(seed, t, k, 1),
                      dim == 3 ? gaussian(seed, t, k, 2) : 0.0) - dvcm;
    if (spin > 0.0) {
      // rotational power = spin x translational power: d_tr v_dr^2 m / 2 per kick against
      // d_rot w^2 I / 2 with I = q m a^2
      const int dtr = dim, drot = dim == 2 ? 1 : 3;
      const double w = vdr * std::sqrt(spin * dtr / (p.q * p.a * p.a * drot));
      if (dim == 2)
        p.w.z += w * gaussian(seed, t, k, 3);
      else
        p.w += w * Vec3(gaussian(seed, t, k, 3), gaussian(seed, t, k, 4), gaussian(seed, t, k, 5));
    }
  }
}

void FixHardsphereKick::write_restart(FILE *fp)
{
  if (comm->me == 0) {
    int size = sizeof(double);
    double v = (double) next_kick;
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(&v, sizeof(double), 1, fp);
  }
}

void FixHardsphereKick::restart(char *buf)
{
  double v;
  memcpy(&v, buf, sizeof(double));
  next_kick = (long) v;
  started = true;
}
