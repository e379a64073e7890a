// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC under LIGGGHTS 3.8: LIGGGHTS's own main program (from its shared library) with every
   GRANFRIC style added to its style tables. LIGGGHTS has no plugin loader; its tables of pair
   styles are public and those of fixes and computes private, reached here through an explicit
   template instantiation (which may name a private member: the standard's own way in).
------------------------------------------------------------------------- */

#include "lammps.h"
#include "force.h"
#include "input.h"
#include "modify.h"

#include "compute_hardsphere_atom.h"
#include "compute_hardsphere_collisions.h"
#include "compute_hardsphere_collisions_local.h"
#include "compute_hardsphere_convection.h"
#include "compute_hardsphere_temp.h"
#include "fix_hardsphere_ed.h"
#include "fix_hardsphere_kick.h"
#include "fix_hardsphere_wall.h"
#include "pair_hardsphere.h"

#include <map>
#include <mpi.h>
#include <string>

using namespace LAMMPS_NS;

namespace {

using FixTable = std::map<std::string, Fix *(*) (LAMMPS *, int, char **)>;
using ComputeTable = std::map<std::string, Compute *(*) (LAMMPS *, int, int, char **)>;

// a member pointer to a private table, handed out by a friend of an explicit instantiation
template <class Tag, typename Tag::type M>
struct Reach {
  friend typename Tag::type table(Tag) { return M; }
};
struct FixTag {
  using type = FixTable *Modify::*;
  friend type table(FixTag);
};
struct ComputeTag {
  using type = ComputeTable *Modify::*;
  friend type table(ComputeTag);
};
template struct Reach<FixTag, &Modify::fix_map>;
template struct Reach<ComputeTag, &Modify::compute_map>;

template <class P>
Pair *pair_creator(LAMMPS *lmp)
{
  return new P(lmp);
}
template <class F>
Fix *fix_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new F(lmp, narg, arg);
}
template <class C>
Compute *compute_creator(LAMMPS *lmp, int, int narg, char **arg)
{
  return new C(lmp, narg, arg);
}

void add_styles(LAMMPS *lmp)
{
  auto &pairs = *lmp->force->pair_map;
  pairs["hardsphere/rough"] = &pair_creator<PairHardsphereRough>;
  pairs["hardsphere/walton"] = &pair_creator<PairHardsphereWalton>;
  pairs["hardsphere/jz"] = &pair_creator<PairHardsphereJZ>;
  auto &fixes = *(lmp->modify->*table(FixTag()));
  fixes["hardsphere/ed"] = &fix_creator<FixHardsphereED>;
  fixes["hardsphere/kick"] = &fix_creator<FixHardsphereKick>;
  fixes["hardsphere/wall"] = &fix_creator<FixHardsphereWall>;
  auto &computes = *(lmp->modify->*table(ComputeTag()));
  computes["hardsphere/atom"] = &compute_creator<ComputeHardsphereAtom>;
  computes["hardsphere/collisions"] = &compute_creator<ComputeHardsphereCollisions>;
  computes["hardsphere/collisions/local"] = &compute_creator<ComputeHardsphereCollisionsLocal>;
  computes["hardsphere/convection"] = &compute_creator<ComputeHardsphereConvection>;
  computes["hardsphere/temp"] = &compute_creator<ComputeHardsphereTemp>;
}

}    // namespace

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  auto *lmp = new LAMMPS(argc, argv, MPI_COMM_WORLD);
  add_styles(lmp);
  lmp->input->file();
  delete lmp;
  MPI_Finalize();
  return 0;
}
