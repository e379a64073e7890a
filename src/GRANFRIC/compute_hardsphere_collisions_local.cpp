// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: compute hardsphere/collisions/local (see the header)
------------------------------------------------------------------------- */

#include "compute_hardsphere_collisions_local.h"

#include "error.h"
#include "fix_hardsphere_ed.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "update.h"

#include <algorithm>
#include <cmath>

using namespace LAMMPS_NS;

ComputeHardsphereCollisionsLocal::ComputeHardsphereCollisionsLocal(LAMMPS *lmp, int narg,
                                                                   char **arg) :
    GRANFRIC_COMPUTE_BASE(lmp, narg, arg), fix(nullptr), nmax(0)
{
  if (narg < 4) utils::missing_cmd_args(FLERR, "compute hardsphere/collisions/local", error);
  if (narg > 4)
    error->all(FLERR, "Compute hardsphere/collisions/local takes one argument, the ID of a fix "
               "hardsphere/ed ({} given)", narg - 3);
  fixid = arg[3];
  local_flag = 1;
  size_local_rows = 0;
  size_local_cols = NCOL;
  array_local = nullptr;
}

ComputeHardsphereCollisionsLocal::~ComputeHardsphereCollisionsLocal()
{
  memory->destroy(array_local);
}

void ComputeHardsphereCollisionsLocal::init()
{
  fix = FixHardsphereED::lookup(lmp, fixid, "Compute hardsphere/collisions/local");
  fix->request_collision_rows();
}

void ComputeHardsphereCollisionsLocal::compute_local()
{
  invoked_local = update->ntimestep;
  const auto &rows = fix->collision_rows();
  int n = 0;
  for (const auto &r : rows) n += ((r.mask[0] | r.mask[1]) & groupbit) != 0;
  if (n > nmax) {
    nmax = n;
    memory->destroy(array_local);
    memory->create(array_local, nmax, NCOL, "hardsphere/collisions/local:array_local");
  }
  const double v2e = force->mvv2e;
  int k = 0;
  for (const auto &r : rows) {
    if (((r.mask[0] | r.mask[1]) & groupbit) == 0) continue;
    double *a = array_local[k++];
    a[0] = r.t;
    a[1] = (double) r.id[0];
    a[2] = (double) r.id[1];
    a[3] = (double) r.wall;
    a[4] = -r.c.gn;
    a[5] = r.c.gt;
    a[6] = std::acos(std::max(-1.0, std::min(1.0, r.c.cos_gamma)));
    a[7] = r.c.sliding ? 1.0 : 0.0;
    a[8] = r.c.jn;    // (mass x velocity)
    a[9] = r.c.dE * v2e;
  }
  size_local_rows = n;
}

double ComputeHardsphereCollisionsLocal::memory_usage()
{
  return (double) nmax * NCOL * sizeof(double);
}
