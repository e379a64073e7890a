// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: compute hardsphere/convection (see the header)
------------------------------------------------------------------------- */

#include "compute_hardsphere_convection.h"

#include "fix_hardsphere_ed.h"
#include "hardsphere_host.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "modify.h"
#include "update.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

ComputeHardsphereConvection::ComputeHardsphereConvection(LAMMPS *lmp, int narg, char **arg) :
    GRANFRIC_COMPUTE_BASE(lmp, narg, arg)
{
  for (int iarg = 3; iarg < narg; iarg += 2) {
    if (strcmp(arg[iarg], "vertical") != 0)
      error->all(FLERR, "Unknown compute hardsphere/convection keyword: {} (allowed: vertical)",
                 arg[iarg]);
    if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "compute hardsphere/convection vertical", error);
    const std::string v = arg[iarg + 1];
    asked = v == "gravity" ? -1 : v == "x" ? 0 : v == "y" ? 1 : v == "z" ? 2 : -2;
    if (asked == -2 || asked >= domain->dimension)
      error->all(FLERR, "Compute hardsphere/convection vertical {} is not available (allowed: "
                 "gravity, {})", v, domain->dimension == 2 ? "x, y" : "x, y, z");
  }
  vector_flag = 1;
  size_vector = 2 * (domain->dimension - 1);
  extvector = 0;
  vector = new double[size_vector];
}

ComputeHardsphereConvection::~ComputeHardsphereConvection()
{
  delete[] vector;
}

// The vertical axis: the keyword's, else the one gravity (the keyword of fix hardsphere/ed)
// acts along, upward against it; without gravity y in 2d (Risso's box), and in 3d an error,
// since no axis is singled out there
void ComputeHardsphereConvection::init()
{
  const int dim = domain->dimension;
  up = asked;
  sign = 1.0;
  if (asked < 0) {
    const double *g = nullptr;
    for (const auto &f : host::fixes(modify))
      if (auto *ed = dynamic_cast<FixHardsphereED *>(f)) g = ed->gravity();
    int along = -1, naxes = 0;
    for (int d = 0; g && d < dim; d++)
      if (g[d] != 0.0) along = d, naxes++;
    if (naxes > 1)
      error->all(FLERR, "Compute hardsphere/convection {}: gravity ({}, {}, {}) does not act along "
                 "an axis; choose the vertical axis with keyword vertical x, y or z", id, g[0],
                 g[1], g[2]);
    if (naxes == 1) {
      up = along;
      sign = g[along] < 0.0 ? 1.0 : -1.0;
    } else if (dim == 2) {
      up = 1;
    } else {
      error->all(FLERR, "Compute hardsphere/convection {} in 3d needs a vertical axis: the gravity "
                 "keyword of fix hardsphere/ed, or keyword vertical x, y or z", id);
    }
  }
  nh = 0;
  for (int d = 0; d < dim; d++)
    if (d != up) horizontal[nh++] = d;
}

void ComputeHardsphereConvection::compute_vector()
{
  invoked_vector = update->ntimestep;
  double **x = atom->x, **v = atom->v;
  const int *mask = atom->mask;
  double local[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
  for (int k = 0; k < nh; k++) {
    const int h = horizontal[k];
    const double lo = domain->boxlo[h], wave = 2.0 * M_PI / domain->prd[h];
    for (int i = 0; i < atom->nlocal; i++) {
      if (!(mask[i] & groupbit)) continue;
      const double phase = wave * (x[i][h] - lo), vup = sign * v[i][up];
      local[2 * k] += vup * std::sin(phase);
      local[2 * k + 1] -= vup * std::cos(phase);
    }
  }
  for (int i = 0; i < atom->nlocal; i++)
    if (mask[i] & groupbit) local[4] += 1.0;
  double all[5];
  MPI_Allreduce(local, all, 5, MPI_DOUBLE, MPI_SUM, world);
  for (int k = 0; k < 2 * nh; k++) vector[k] = all[4] > 0 ? all[k] / all[4] : 0.0;
}
