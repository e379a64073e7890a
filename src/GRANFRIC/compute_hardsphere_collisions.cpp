// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: compute hardsphere/collisions (see the header)
------------------------------------------------------------------------- */

#include "compute_hardsphere_collisions.h"

#include "atom.h"
#include "error.h"
#include "fix_hardsphere_ed.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "update.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

ComputeHardsphereCollisions::ComputeHardsphereCollisions(LAMMPS *lmp, int narg, char **arg) :
    GRANFRIC_COMPUTE_BASE(lmp, narg, arg), fix(nullptr), nbins(36), seen_time(0.0), computed_step(-1)
{
  if (narg < 4) utils::missing_cmd_args(FLERR, "compute hardsphere/collisions", error);
  fixid = arg[3];
  int iarg = 4;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "bins") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "compute hardsphere/collisions bins", error);
      nbins = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (nbins < 1 || nbins > 100000)
        error->all(FLERR, "Compute hardsphere/collisions bins = {} is out of range (1..100000)",
                   nbins);
      iarg += 2;
    } else
      error->all(FLERR, "Unknown compute hardsphere/collisions keyword: {} (allowed: bins)",
                 arg[iarg]);
  }
  vector_flag = 1;
  size_vector = 7;
  extvector = 0;
  array_flag = 1;
  size_array_rows = nbins;
  size_array_cols = 2;
  extarray = 0;
  vector = new double[7]{0, 0, 0, 0, 0, 0, 0};
  memory->create(array, nbins, 2, "hardsphere/collisions:array");
  for (int k = 0; k < nbins; k++) {
    array[k][0] = 0.5 * M_PI + (k + 0.5) * 0.5 * M_PI / nbins;
    array[k][1] = 0.0;
  }
}

ComputeHardsphereCollisions::~ComputeHardsphereCollisions()
{
  delete[] vector;
  memory->destroy(array);
}

void ComputeHardsphereCollisions::init()
{
  fix = FixHardsphereED::lookup(lmp, fixid, "Compute hardsphere/collisions");
  fix->request_gamma_bins(nbins);
  // the first window of a run starts with the run
  seen = fix->cumulative();
  seen_time = fix->cumulative_time();
  computed_step = -1;
}

// statistics since the last window; a vector and an array request on the same step share it
void ComputeHardsphereCollisions::update_window()
{
  if (computed_step == update->ntimestep) return;
  const granfric::EDStats &now = fix->cumulative();
  const double dt = fix->cumulative_time() - seen_time;
  const long ncoll = now.collisions - seen.collisions;
  const double natoms = (double) atom->natoms;
  vector[0] = (dt > 0.0 && natoms > 0) ? 2.0 * ncoll / (natoms * dt) : 0.0;
  vector[1] = ncoll > 0 ? (now.dE - seen.dE) * force->mvv2e / ncoll : 0.0;
  const long nwall = now.wall_collisions - seen.wall_collisions;
  // (the core counts sliding pair and wall collisions together)
  vector[2] = ncoll + nwall > 0 ? double(now.sliding - seen.sliding) / (ncoll + nwall) : 0.0;
  vector[3] = (double) ncoll;
  vector[4] = dt;
  vector[5] = nwall > 0 ? (now.dE_wall - seen.dE_wall) * force->mvv2e / nwall : 0.0;
  vector[6] = (double) nwall;
  const double width = 0.5 * M_PI / nbins;
  for (int k = 0; k < nbins; k++) {
    const long c = (k < (int) now.gamma_hist.size() ? now.gamma_hist[k] : 0) -
        (k < (int) seen.gamma_hist.size() ? seen.gamma_hist[k] : 0);
    array[k][1] = ncoll > 0 ? c / (ncoll * width) : 0.0;
  }
  seen = now;
  seen_time = fix->cumulative_time();
  computed_step = update->ntimestep;
}

void ComputeHardsphereCollisions::compute_vector()
{
  invoked_vector = update->ntimestep;
  update_window();
}

void ComputeHardsphereCollisions::compute_array()
{
  invoked_array = update->ntimestep;
  update_window();
}
