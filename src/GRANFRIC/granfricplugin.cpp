// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC plugin: registers every GRANFRIC style (granfric_styles.h) with LAMMPS
------------------------------------------------------------------------- */

#include "lammpsplugin.h"
#include "version.h"

#include "granfric_styles.h"

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
  // (pair styles have LAMMPS's creator of one argument, fixes and computes that of three)
#define GRANFRIC_PAIR(name, Class, header, info) \
  add(reg, lmp, handle, "pair", name, info, (void *) &pair_creator<Class>, true);
#define GRANFRIC_FIX(name, Class, header, info) \
  add(reg, lmp, handle, "fix", name, info, (void *) &style_creator<Class>, false);
#define GRANFRIC_COMPUTE(name, Class, header, info) \
  add(reg, lmp, handle, "compute", name, info, (void *) &style_creator<Class>, false);
  GRANFRIC_STYLES(GRANFRIC_PAIR, GRANFRIC_FIX, GRANFRIC_COMPUTE)
#undef GRANFRIC_PAIR
#undef GRANFRIC_FIX
#undef GRANFRIC_COMPUTE
}
