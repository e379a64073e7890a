// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: fix hardsphere/kick (see the header and doc/fix_hardsphere_kick.rst)
------------------------------------------------------------------------- */

#include "fix_hardsphere_kick.h"

#include "hardsphere_host.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "modify.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>

using namespace LAMMPS_NS;

FixHardsphereKick::FixHardsphereKick(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), next_kick(0), kick_shift(0)
{
  if (narg < 6) utils::missing_cmd_args(FLERR, "fix hardsphere/kick f_dr v_dr seed", error);
  double &fdr = law.fdr, &vdr = law.vdr, &spin = law.spin;
  fdr = utils::numeric(FLERR, arg[3], false, lmp);
  vdr = utils::numeric(FLERR, arg[4], false, lmp);
  law.seed = utils::bnumeric(FLERR, arg[5], false, lmp);
  const long seed = law.seed;
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
      law.momentum = utils::logical(FLERR, arg[iarg + 1], false, lmp) != 0;
      iarg += 2;
    } else if (strcmp(arg[iarg], "spin") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix hardsphere/kick spin", error);
      spin = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(spin >= 0.0))
        error->all(FLERR, "Fix hardsphere/kick spin = {} must be >= 0 (rotational power as a "
                   "fraction of the translational power)", spin);
      if (spin > MAX_SPIN)
        error->all(FLERR, "Fix hardsphere/kick spin = {} is out of range (at most {:g} times the "
                   "translational power: rough collisions pass the spins' energy on to the "
                   "translation, and speeds that far beyond the driving end the run in cell "
                   "crossings)", spin, MAX_SPIN);
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
  // the kicks follow the simulation time, through reset_timestep and restarts alike: the next
  // kick of a run is the first kick time at or after the time the run starts
  kick_shift = law.shift_at(hardsphere::time_at_step(update, update->ntimestep), next_kick, kick_shift);
}

// Every kick of a step is processed inside it, each over all atoms (brought to the kick time
// and predicted afresh): a bound on both keeps a step finite. The kick indices of the run stay
// exact in a double.
void FixHardsphereKick::check_kicks_per_step() const
{
  const double fdr = law.fdr;
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

// the kicks of a step add independent Gaussian increments of v_dr per component: their sum
// grows as the square root of their number (at least one kick's)
double FixHardsphereKick::speed_scale(double dt, int dim) const
{
  return law.vdr * std::sqrt((double) dim * std::max(1.0, law.fdr * dt));
}

double FixHardsphereKick::compute_scalar()
{
  return (double) next_kick;
}

void FixHardsphereKick::kicks_in(double t0, double t1, std::vector<double> &times,
                                 std::vector<long> &index)
{
  law.kicks_in(t0, t1, next_kick, times, index, kick_shift);
}

// the core's momentum sums over this rank's atoms of the group, summed over the ranks (the same
// bits on any number of ranks)
granfric::Vec3 FixHardsphereKick::momentum_shift(long k, int dim) const
{
  if (!law.momentum) return granfric::Vec3();
  double mmax = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit) mmax = std::max(mmax, atom->rmass[i]);
  MPI_Allreduce(MPI_IN_PLACE, &mmax, 1, MPI_DOUBLE, MPI_MAX, world);
  granfric::Kicks::MomentumSums s = law.momentum_sums(mmax, (double) atom->natoms);
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit) law.add(s, (long) atom->tag[i], atom->rmass[i], k, dim);
  MPI_Allreduce(MPI_IN_PLACE, s.count, 4, MPI_INT64_T, MPI_SUM, world);
  return law.shift(s);
}

void FixHardsphereKick::apply(granfric::EventDriven &ed, const std::vector<tagint> &tag,
                              const std::vector<int> &mask, long k, int dim,
                              const granfric::Vec3 &dvcm) const
{
  const int n = ed.size();
  for (int e = 0; e < n; e++)
    if (mask[e] & groupbit) law.apply(ed.particle(e), (long) tag[e], k, dim, dvcm);
}

// (a negative first value marks the format: files of earlier versions hold next_kick alone)
void FixHardsphereKick::write_restart(FILE *fp)
{
  if (comm->me == 0) {
    const double v[3] = {-1.0, (double) next_kick, (double) kick_shift};
    int size = sizeof(v);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(v, sizeof(double), 3, fp);
  }
}

void FixHardsphereKick::restart(char *buf)
{
  double v[3];
  memcpy(v, buf, sizeof(double));
  if (v[0] >= 0.0) {
    next_kick = (long) v[0];
    kick_shift = 0;
  } else {
    memcpy(v, buf, sizeof(v));
    next_kick = (long) v[1];
    kick_shift = (long) v[2];
  }
  // (init checks both against the time)
}
