/* -*- c++ -*- ----------------------------------------------------------
   SPDX-License-Identifier: GPL-2.0-or-later
   Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
   GRANFRIC: compute ID group hardsphere/atom fixID
   Per atom, over the last step of fix hardsphere/ed fixID: 1 collisions with other atoms,
   2 collisions with walls, 3 - 4 translational and rotational kinetic energy change in the
   collisions with other atoms, 5 kinetic energy change in wall collisions, 6 time of the atom's
   last collision (-1: none since the fix began to keep these). For dumps, compute chunk/atom
   with fix ave/chunk, and fix ave/atom.
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(hardsphere/atom,ComputeHardsphereAtom);
// clang-format on
#else

#ifndef LMP_GRANFRIC_COMPUTE_HARDSPHERE_ATOM_H
#define LMP_GRANFRIC_COMPUTE_HARDSPHERE_ATOM_H

#include "compute.h"
#include "host_compat.h"

#include <string>

namespace LAMMPS_NS {

class ComputeHardsphereAtom : public Compute {
 protected:
  GRANFRIC_HOST_ERROR    // (under LIGGGHTS: LAMMPS's error calls)

 public:
  enum { NCOL = 6 };
  ComputeHardsphereAtom(class LAMMPS *, int, char **);
  ~ComputeHardsphereAtom() override;
  void init() override;
  void compute_peratom() override;
  double memory_usage() override;

 private:
  std::string fixid;
  class FixHardsphereED *fix;
  int nmax;
};

}    // namespace LAMMPS_NS

#endif
#endif
