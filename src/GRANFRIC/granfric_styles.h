// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: the list of GRANFRIC's styles, for the hosts that register them by hand: the LAMMPS
   plugin (granfricplugin.cpp) and the LIGGGHTS host (src/liggghts/granfric_liggghts.cpp).

   GRANFRIC_STYLES(PAIR, FIX, COMPUTE) expands to one call per style, in the order the plugin
   registers them:
     PAIR(name, Class, header, info)   FIX(...)   COMPUTE(...)
   name: the style name as a string literal; Class: the class in LAMMPS_NS; header: the header
   that declares it (included below) as a string literal; info: one line on the style, shown by
   LAMMPS's `plugin list`.

   A LAMMPS built with GRANFRIC as an in-tree package takes its styles from the PairStyle(),
   FixStyle() and ComputeStyle() lines of those headers instead (LAMMPS's generated style_*.h).
   Those lines and this list must name the same styles; unittest/scripts/style_list.py (the test
   package.style_list) checks that they do.
------------------------------------------------------------------------- */

#ifndef GRANFRIC_STYLES_H
#define GRANFRIC_STYLES_H

#include "compute_hardsphere_atom.h"
#include "compute_hardsphere_collisions.h"
#include "compute_hardsphere_collisions_local.h"
#include "compute_hardsphere_convection.h"
#include "compute_hardsphere_temp.h"
#include "fix_hardsphere_ed.h"
#include "fix_hardsphere_kick.h"
#include "fix_hardsphere_wall.h"
#include "pair_hardsphere.h"

// clang-format off
#define GRANFRIC_STYLES(PAIR, FIX, COMPUTE)                                                       \
  PAIR("hardsphere/rough", PairHardsphereRough, "pair_hardsphere.h",                              \
       "GRANFRIC rough hard spheres: constant restitution r and beta")                            \
  PAIR("hardsphere/walton", PairHardsphereWalton, "pair_hardsphere.h",                            \
       "GRANFRIC hard spheres with Coulomb friction (Walton: r, mu, rtmax)")                      \
  PAIR("hardsphere/jz", PairHardsphereJZ, "pair_hardsphere.h",                                    \
       "GRANFRIC hard discs/spheres, Jenkins-Zhang rule (qn, qt, kappa_s, kappa_d)")              \
  FIX("hardsphere/ed", FixHardsphereED, "fix_hardsphere_ed.h",                                    \
      "GRANFRIC exact event-driven integrator for hard spheres and discs")                        \
  FIX("hardsphere/kick", FixHardsphereKick, "fix_hardsphere_kick.h",                              \
      "GRANFRIC homogeneous stochastic driving (Gaussian kicks at exact times)")                  \
  FIX("hardsphere/wall", FixHardsphereWall, "fix_hardsphere_wall.h",                              \
      "GRANFRIC plane wall for fix hardsphere/ed (exact wall collisions)")                        \
  COMPUTE("hardsphere/temp", ComputeHardsphereTemp, "compute_hardsphere_temp.h",                  \
          "GRANFRIC translational and rotational temperatures of hard spheres and discs")         \
  COMPUTE("hardsphere/convection", ComputeHardsphereConvection,                                   \
          "compute_hardsphere_convection.h",                                                      \
          "GRANFRIC convection order parameters Psi1, Psi2 (Risso et al. 2005)")                  \
  COMPUTE("hardsphere/collisions", ComputeHardsphereCollisions,                                   \
          "compute_hardsphere_collisions.h",                                                      \
          "GRANFRIC collision statistics of fix hardsphere/ed")                                   \
  COMPUTE("hardsphere/atom", ComputeHardsphereAtom, "compute_hardsphere_atom.h",                  \
          "GRANFRIC per-atom collisions and energy changes of the last step of fix "              \
          "hardsphere/ed")                                                                        \
  COMPUTE("hardsphere/collisions/local", ComputeHardsphereCollisionsLocal,                        \
          "compute_hardsphere_collisions_local.h",                                                \
          "GRANFRIC one row per collision of the last step of fix hardsphere/ed")
// clang-format on

#endif
