// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: compute hardsphere/atom (see the header)
------------------------------------------------------------------------- */

#include "compute_hardsphere_atom.h"

#include "atom.h"
#include "error.h"
#include "fix_hardsphere_ed.h"
#include "memory.h"
#include "update.h"

using namespace LAMMPS_NS;

ComputeHardsphereAtom::ComputeHardsphereAtom(LAMMPS *lmp, int narg, char **arg) :
    GRANFRIC_COMPUTE_BASE(lmp, narg, arg), fix(nullptr), nmax(0)
{
  if (narg < 4) utils::missing_cmd_args(FLERR, "compute hardsphere/atom", error);
  if (narg > 4)
    error->all(FLERR, "Compute hardsphere/atom takes one argument, the ID of a fix "
               "hardsphere/ed ({} given)", narg - 3);
  fixid = arg[3];
  peratom_flag = 1;
  size_peratom_cols = NCOL;
  array_atom = nullptr;
}

ComputeHardsphereAtom::~ComputeHardsphereAtom()
{
  memory->destroy(array_atom);
}

void ComputeHardsphereAtom::init()
{
  fix = FixHardsphereED::lookup(lmp, fixid, "Compute hardsphere/atom");
  fix->request_atom_tallies();
}

void ComputeHardsphereAtom::compute_peratom()
{
  invoked_peratom = update->ntimestep;
  if (atom->nmax > nmax) {
    nmax = atom->nmax;
    memory->destroy(array_atom);
    memory->create(array_atom, nmax, NCOL, "hardsphere/atom:array_atom");
  }
  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++) {
    const double *t = fix->atom_tally(i);
    for (int k = 0; k < NCOL; k++)
      array_atom[i][k] = (mask[i] & groupbit) ? t[FixHardsphereED::Tally::T_COLL + k] : 0.0;
  }
}

double ComputeHardsphereAtom::memory_usage()
{
  return (double) nmax * NCOL * sizeof(double);
}
