// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: compute hardsphere/temp. Temperatures per degree of freedom (doc/conventions.rst):
   2d: T_tr = E_tr/(N k_B), T_rot = 2 E_rot/(N k_B) (one spin dof, about z);
   3d: T_tr = 2 E_tr/(3 N k_B), T_rot = 2 E_rot/(3 N k_B). E_rot uses I = q m a^2 with q of the
   hardsphere pair style (or the inertia keyword), not LAMMPS's fixed 2/5. In a box sheared by
   fix deform (remap v): of the motion relative to the flow (see sums()).
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
    GRANFRIC_COMPUTE_BASE(lmp, narg, arg), qshape(-1.0)
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

// the shape factor per type: the inertia keyword's for all, or the pair style's per type
void ComputeHardsphereTemp::init()
{
  qused.assign(atom->ntypes + 1, qshape);
  if (qshape > 0.0) return;
  auto *pair = dynamic_cast<PairHardsphere *>(force->pair);
  if (!pair)
    error->all(FLERR,
               "Compute hardsphere/temp takes the shape factor from a hardsphere pair style; "
               "with pair style {} give it with the inertia keyword",
               force->pair_style ? force->pair_style : "none");
  for (int t = 1; t <= atom->ntypes; t++) qused[t] = pair->shape_factor(t);
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

// In a box that fix deform shears with remap v (fix hardsphere/ed's simple shear) the
// temperatures are those of the peculiar motion: each atom's velocity less the streaming
// velocity of the deforming box where it is (the box's rate of change times its fractional
// coordinates, as compute temp/deform takes it off), and its spin less the group's mean spin
// (which the shear's vorticity drives)
void ComputeHardsphereTemp::sums(double *all)
{
  double **x = atom->x, **v = atom->v, **omega = atom->omega;
  const double *radius = atom->radius, *rmass = atom->rmass;
  const int *mask = atom->mask, *type = atom->type;
  const bool dim2 = domain->dimension == 2;
  const bool peculiar = domain->deform_vremap;
  double mean[4] = {0.0, 0.0, 0.0, 0.0};    // the group's mean spin, and its count
  if (peculiar) {
    double local[4] = {0.0, 0.0, 0.0, 0.0};
    for (int i = 0; i < atom->nlocal; i++) {
      if (!(mask[i] & groupbit)) continue;
      for (int d = 0; d < 3; d++) local[d] += omega[i][d];
      local[3] += 1.0;
    }
    MPI_Allreduce(local, mean, 4, MPI_DOUBLE, MPI_SUM, world);
    for (int d = 0; d < 3 && mean[3] > 0.0; d++) mean[d] /= mean[3];
  }
  const double *h = domain->h_rate, *hlo = domain->h_ratelo;
  double local[3] = {0.0, 0.0, 0.0};    // sum m c^2, sum I (w - mean)^2, count
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    double c[3] = {v[i][0], v[i][1], v[i][2]}, w[3] = {omega[i][0], omega[i][1], omega[i][2]};
    if (peculiar) {
      double l[3];
      domain->x2lamda(x[i], l);
      c[0] -= h[0] * l[0] + h[5] * l[1] + h[4] * l[2] + hlo[0];
      c[1] -= h[1] * l[1] + h[3] * l[2] + hlo[1];
      c[2] -= h[2] * l[2] + hlo[2];
      for (int d = 0; d < 3; d++) w[d] -= mean[d];
    }
    local[0] += rmass[i] * (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    const double w2 = dim2 ? w[2] * w[2] : w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    local[1] += qused[type[i]] * rmass[i] * radius[i] * radius[i] * w2;
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
