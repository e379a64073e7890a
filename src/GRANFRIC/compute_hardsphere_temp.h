/* -*- c++ -*- ----------------------------------------------------------
   SPDX-License-Identifier: GPL-2.0-or-later
   Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
   GRANFRIC: compute ID group hardsphere/temp [inertia sphere|disc|<q>]
   global vector: T_tr, T_rot, R = T_rot/T_tr, E_tr, E_rot
------------------------------------------------------------------------- */

#ifndef LMP_GRANFRIC_COMPUTE_HARDSPHERE_TEMP_H
#define LMP_GRANFRIC_COMPUTE_HARDSPHERE_TEMP_H

#include "compute.h"

namespace LAMMPS_NS {

class ComputeHardsphereTemp : public Compute {
 public:
  ComputeHardsphereTemp(class LAMMPS *, int, char **);
  ~ComputeHardsphereTemp() override;
  void init() override;
  void compute_vector() override;

 private:
  double qshape;      // I/(m a^2); < 0: take it from the hardsphere pair style
  double qused;
};

}    // namespace LAMMPS_NS

#endif
