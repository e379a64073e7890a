// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: compute hardsphere/temp. Temperatures per degree of freedom (doc/conventions.rst):
   2d: T_tr = E_tr/(N k_B), T_rot = 2 E_rot/(N k_B) (one spin dof, about z);
   3d: T_tr = 2 E_tr/(3 N k_B), T_rot = 2 E_rot/(3 N k_B). E_rot uses I = q m a^2 with q of the
   hardsphere pair style (or the inertia keyword), not LAMMPS's fixed 2/5.
------------------------------------------------------------------------- */

#include "compute_hardsphere_temp.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "hardsphere_host.h"
#include "pair_hardsphere.h"
#include "update.h"

#include <cstring>

using namespace LAMMPS_NS;

ComputeHardsphereTemp::ComputeHardsphereTemp(LAMMPS *lmp, int narg, char **arg) :
    GRANFRIC_COMPUTE_BASE(lmp, narg, arg), qshape(-1.0), qused(0.4)
{
  int iarg = 3;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "inertia") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "compute hardsphere/temp inertia", error);
      bool disc;
      qshape = hardsphere::parse_inertia(lmp, "Compute hardsphere/temp", arg[iarg + 1], disc);
      if (disc && domain->dimension != 2)
        error->all(FLERR, "Compute hardsphere/temp inertia disc requires a 2d simulation");
      iarg += 2;
    } else
      error->all(FLERR, "Unknown compute hardsphere/temp keyword: {} (allowed: inertia)",
                 arg[iarg]);
  }
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag)
    error->all(FLERR, "Compute hardsphere/temp requires atom_style sphere (radius, mass, omega)");
  scalar_flag = 1;
  extscalar = 0;
  tempflag = 1;    // (a temperature LAMMPS's commands accept)
  vector_flag = 1;
  size_vector = 5;
  extvector = -1;
  extlist = new int[5]{0, 0, 0, 1, 1};
  vector = new double[5];
}

ComputeHardsphereTemp::~ComputeHardsphereTemp()
{
  delete[] vector;
  delete[] extlist;
}

void ComputeHardsphereTemp::init()
{
  if (qshape > 0.0) {
    qused = qshape;
    return;
  }
  auto *pair = dynamic_cast<PairHardsphere *>(force->pair);
  if (!pair)
    error->all(FLERR,
               "Compute hardsphere/temp takes the shape factor from a hardsphere pair style; "
               "with pair style {} give it with the inertia keyword",
               force->pair_style ? force->pair_style : "none");
  qused = pair->shape_factor();
}

// degrees of freedom of the scalar: d per atom of the group, as in the papers' T_tr (no
// correction for the total momentum, unlike compute temp); counted at the start of each run
void ComputeHardsphereTemp::setup()
{
  dof = domain->dimension * (double) group->count(igroup);
}

double ComputeHardsphereTemp::compute_scalar()
{
  invoked_scalar = update->ntimestep;
  double all[3];
  sums(all);
  scalar = dof > 0.0 ? all[0] * force->mvv2e / (dof * force->boltz) : 0.0;
  return scalar;
}

void ComputeHardsphereTemp::sums(double *all)
{
  double **v = atom->v, **omega = atom->omega;
  const double *radius = atom->radius, *rmass = atom->rmass;
  const int *mask = atom->mask;
  const bool dim2 = domain->dimension == 2;
  double local[3] = {0.0, 0.0, 0.0};    // sum m v^2, sum I w^2, count
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    local[0] += rmass[i] * (v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
    const double w2 = dim2 ? omega[i][2] * omega[i][2]
                           : omega[i][0] * omega[i][0] + omega[i][1] * omega[i][1] + omega[i][2] * omega[i][2];
    local[1] += qused * rmass[i] * radius[i] * radius[i] * w2;
    local[2] += 1.0;
  }
  MPI_Allreduce(local, all, 3, MPI_DOUBLE, MPI_SUM, world);
}

void ComputeHardsphereTemp::compute_vector()
{
  invoked_vector = update->ntimestep;
  double all[3];
  sums(all);
  const double etr = 0.5 * all[0] * force->mvv2e, erot = 0.5 * all[1] * force->mvv2e;
  const double n = all[2];
  const double kb = force->boltz;
  const bool dim2 = domain->dimension == 2;
  const double dtr = dim2 ? 2.0 : 3.0, drot = dim2 ? 1.0 : 3.0;
  vector[0] = n > 0 ? 2.0 * etr / (dtr * n * kb) : 0.0;
  vector[1] = n > 0 ? 2.0 * erot / (drot * n * kb) : 0.0;
  vector[2] = vector[0] > 0.0 ? vector[1] / vector[0] : 0.0;
  vector[3] = etr;
  vector[4] = erot;
}
