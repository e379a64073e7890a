// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC under LIGGGHTS 3.8: LIGGGHTS's own main program (from its shared library) with every
   GRANFRIC style (granfric_styles.h) added to its style tables once LIGGGHTS is constructed.
   The styles live in the tables of that first Force and Modify: the `clear` command makes new
   ones from LIGGGHTS's own styles alone.
------------------------------------------------------------------------- */

#include "lammps.h"
#include "force.h"
#include "input.h"
#include "modify.h"
#include "neighbor.h"
#include "host_compat.h"

#include "granfric_styles.h"

#include <map>
#include <mpi.h>
#include <string>

using namespace LAMMPS_NS;

namespace {

using FixTable = std::map<std::string, Fix *(*) (LAMMPS *, int, char **)>;
using ComputeTable = std::map<std::string, Compute *(*) (LAMMPS *, int, int, char **)>;

/* ----------------------------------------------------------------------
   private_style_tables(modify): the tables of fix and compute styles of LIGGGHTS's Modify,
   which are private; with Reach and its tags just before it (and pairs_excluded below, which
   reads Neighbor's protected exclusion counts the same way), the only code that reaches a
   private member of LIGGGHTS.
   Why: LIGGGHTS 3.8 has no plugin interface and no call that adds a style; its styles are
   compiled into the tables from its own style_*.h. Force::pair_map is public, but
   Modify::fix_map and Modify::compute_map (pointers to std::map<std::string, creator>) are
   private. The C++ standard lets an explicit instantiation name a private member (the usual
   access checking does not apply to the names it uses, [temp.explicit]), so
   Reach<Tag, &Modify::x> is instantiated explicitly and its friend function table(Tag) hands
   that member pointer out.
   What would break it: a LIGGGHTS that renames fix_map or compute_map, changes their type (the
   map, the creator's signature, a map held by value) or replaces them by another registry
   stops this file from compiling. The member pointers are resolved from the modify.h compiled
   against, so a libliggghts whose Modify has another member layout than that header (the
   library of another LIGGGHTS version under these headers) would be written at the wrong
   place, with no error. A LIGGGHTS that fills or rebuilds the tables after its construction
   would drop GRANFRIC's styles, and they would be unknown to the input script.
------------------------------------------------------------------------- */
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
struct ExcludeTag {
  using type = int Neighbor::*;
  friend type table(ExcludeTag);
};
struct GroupExcludeTag {
  using type = int Neighbor::*;
  friend type table(GroupExcludeTag);
};
struct MolExcludeTag {
  using type = int Neighbor::*;
  friend type table(MolExcludeTag);
};
template struct Reach<FixTag, &Modify::fix_map>;
template struct Reach<ComputeTag, &Modify::compute_map>;
template struct Reach<ExcludeTag, &Neighbor::nex_type>;
template struct Reach<GroupExcludeTag, &Neighbor::nex_group>;
template struct Reach<MolExcludeTag, &Neighbor::nex_mol>;

struct ModifyTables {
  FixTable &fixes;
  ComputeTable &computes;
};

ModifyTables private_style_tables(Modify *modify)
{
  return {*(modify->*table(FixTag())), *(modify->*table(ComputeTag()))};
}

}    // namespace

// (declared in host_compat.h) whether neigh_modify exclude removed pairs from the neighbour
// lists: the counts of its type, group and molecule exclusions, which LIGGGHTS keeps
// protected, read through Reach as the style tables are (the same reasons, the same risks)
bool LAMMPS_NS::host::pairs_excluded(const Neighbor *neighbor)
{
  return neighbor->*table(ExcludeTag()) + neighbor->*table(GroupExcludeTag()) +
      neighbor->*table(MolExcludeTag()) > 0;
}

namespace {

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
// (LIGGGHTS passes computes one more argument, which GRANFRIC's computes do not use)
template <class C>
Compute *compute_creator(LAMMPS *lmp, int, int narg, char **arg)
{
  return new C(lmp, narg, arg);
}

void add_styles(LAMMPS *lmp)
{
  auto &pairs = *lmp->force->pair_map;
  ModifyTables tables = private_style_tables(lmp->modify);
#define GRANFRIC_PAIR(name, Class, header, info) pairs[name] = &pair_creator<Class>;
#define GRANFRIC_FIX(name, Class, header, info) tables.fixes[name] = &fix_creator<Class>;
#define GRANFRIC_COMPUTE(name, Class, header, info) tables.computes[name] = &compute_creator<Class>;
  GRANFRIC_STYLES(GRANFRIC_PAIR, GRANFRIC_FIX, GRANFRIC_COMPUTE)
#undef GRANFRIC_PAIR
#undef GRANFRIC_FIX
#undef GRANFRIC_COMPUTE
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
