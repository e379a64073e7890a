/* -*- c++ -*- ----------------------------------------------------------
   SPDX-License-Identifier: GPL-2.0-or-later
   Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
   GRANFRIC: compute ID group hardsphere/collisions/local fixID
   One row per collision of the last step of fix hardsphere/ed fixID (pairs with an atom in
   the group, wall collisions of atoms in the group), 10 columns: time, atom ID 1, atom ID 2
   (0: a wall), wall (0: a pair, k: the k-th hardsphere/wall fix), normal and tangential
   relative speed before, impact angle gamma, sliding (1) or sticking (0), normal impulse,
   energy change. For dump local and compute reduce.
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(hardsphere/collisions/local,ComputeHardsphereCollisionsLocal);
// clang-format on
#else

#ifndef LMP_GRANFRIC_COMPUTE_HARDSPHERE_COLLISIONS_LOCAL_H
#define LMP_GRANFRIC_COMPUTE_HARDSPHERE_COLLISIONS_LOCAL_H

#include "compute.h"
#include "host_compat.h"

#include <string>

namespace LAMMPS_NS {

class ComputeHardsphereCollisionsLocal : public Compute {
 protected:
  GRANFRIC_HOST_ERROR    // (under LIGGGHTS: LAMMPS's error calls)

 public:
  enum { NCOL = 10 };
  ComputeHardsphereCollisionsLocal(class LAMMPS *, int, char **);
  ~ComputeHardsphereCollisionsLocal() override;
  void init() override;
  void compute_local() override;
  double memory_usage() override;

 private:
  std::string fixid;
  class FixHardsphereED *fix;
  int nmax;    // rows allocated
};

}    // namespace LAMMPS_NS

#endif
#endif
