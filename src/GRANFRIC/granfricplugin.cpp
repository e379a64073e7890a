// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC plugin: registers every GRANFRIC style with LAMMPS
------------------------------------------------------------------------- */

#include "lammpsplugin.h"
#include "version.h"

#include "compute_hardsphere_atom.h"
#include "compute_hardsphere_collisions.h"
#include "compute_hardsphere_collisions_local.h"
#include "compute_hardsphere_convection.h"
#include "compute_hardsphere_temp.h"
#include "fix_hardsphere_ed.h"
#include "fix_hardsphere_kick.h"
#include "fix_hardsphere_wall.h"
#include "pair_hardsphere.h"

using namespace LAMMPS_NS;

namespace {

template <class P> Pair *pair_creator(LAMMPS *lmp)
{
  return new P(lmp);
}

template <class S> S *style_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new S(lmp, argc, argv);
}

void add(lammpsplugin_regfunc reg, void *lmp, void *handle, const char *style, const char *name,
         const char *info, void *creator, bool v1)
{
  lammpsplugin_t plugin;
  plugin.version = LAMMPS_VERSION;
  plugin.style = style;
  plugin.name = name;
  plugin.info = info;
  plugin.author = "GRANFRIC developers";
  if (v1)
    plugin.creator.v1 = (lammpsplugin_factory1 *) creator;
  else
    plugin.creator.v2 = (lammpsplugin_factory2 *) creator;
  plugin.handle = handle;
  (*reg)(&plugin, lmp);
}

}    // namespace

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto reg = (lammpsplugin_regfunc) regfunc;
  add(reg, lmp, handle, "pair", "hardsphere/rough",
      "GRANFRIC rough hard spheres: constant restitution r and beta",
      (void *) &pair_creator<PairHardsphereRough>, true);
  add(reg, lmp, handle, "pair", "hardsphere/walton",
      "GRANFRIC hard spheres with Coulomb friction (Walton: r, mu, rtmax)",
      (void *) &pair_creator<PairHardsphereWalton>, true);
  add(reg, lmp, handle, "pair", "hardsphere/jz",
      "GRANFRIC hard discs/spheres, Jenkins-Zhang rule (qn, qt, kappa_s, kappa_d)",
      (void *) &pair_creator<PairHardsphereJZ>, true);
  add(reg, lmp, handle, "fix", "hardsphere/ed",
      "GRANFRIC exact event-driven integrator for hard spheres and discs",
      (void *) &style_creator<FixHardsphereED>, false);
  add(reg, lmp, handle, "fix", "hardsphere/kick",
      "GRANFRIC homogeneous stochastic driving (Gaussian kicks at exact times)",
      (void *) &style_creator<FixHardsphereKick>, false);
  add(reg, lmp, handle, "fix", "hardsphere/wall",
      "GRANFRIC plane wall for fix hardsphere/ed (exact wall collisions)",
      (void *) &style_creator<FixHardsphereWall>, false);
  add(reg, lmp, handle, "compute", "hardsphere/temp",
      "GRANFRIC translational and rotational temperatures of hard spheres and discs",
      (void *) &style_creator<ComputeHardsphereTemp>, false);
  add(reg, lmp, handle, "compute", "hardsphere/convection",
      "GRANFRIC convection order parameters Psi1, Psi2 (Risso et al. 2005)",
      (void *) &style_creator<ComputeHardsphereConvection>, false);
  add(reg, lmp, handle, "compute", "hardsphere/collisions",
      "GRANFRIC collision statistics of fix hardsphere/ed",
      (void *) &style_creator<ComputeHardsphereCollisions>, false);
  add(reg, lmp, handle, "compute", "hardsphere/atom",
      "GRANFRIC per-atom collisions and energy changes of the last step of fix hardsphere/ed",
      (void *) &style_creator<ComputeHardsphereAtom>, false);
  add(reg, lmp, handle, "compute", "hardsphere/collisions/local",
      "GRANFRIC one row per collision of the last step of fix hardsphere/ed",
      (void *) &style_creator<ComputeHardsphereCollisionsLocal>, false);
}
