// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: compute hardsphere/convection (see the header)
------------------------------------------------------------------------- */

#include "compute_hardsphere_convection.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "update.h"

#include <cmath>

using namespace LAMMPS_NS;

ComputeHardsphereConvection::ComputeHardsphereConvection(LAMMPS *lmp, int narg, char **arg) :
    GRANFRIC_COMPUTE_BASE(lmp, narg, arg)
{
  if (narg != 3)
    error->all(FLERR, "Compute hardsphere/convection takes no arguments after the style name "
               "({} given)", narg - 3);
  vector_flag = 1;
  size_vector = 2;
  extvector = 0;
  vector = new double[2];
}

ComputeHardsphereConvection::~ComputeHardsphereConvection()
{
  delete[] vector;
}

void ComputeHardsphereConvection::compute_vector()
{
  invoked_vector = update->ntimestep;
  double **x = atom->x, **v = atom->v;
  const int *mask = atom->mask;
  const double lo = domain->boxlo[0], k = 2.0 * M_PI / domain->prd[0];
  double local[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double phase = k * (x[i][0] - lo);
    local[0] += v[i][1] * std::sin(phase);
    local[1] -= v[i][1] * std::cos(phase);
    local[2] += 1.0;
  }
  double all[3];
  MPI_Allreduce(local, all, 3, MPI_DOUBLE, MPI_SUM, world);
  vector[0] = all[2] > 0 ? all[0] / all[2] : 0.0;
  vector[1] = all[2] > 0 ? all[1] / all[2] : 0.0;
}
