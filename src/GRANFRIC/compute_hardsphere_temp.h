/* -*- c++ -*- ----------------------------------------------------------
   SPDX-License-Identifier: GPL-2.0-or-later
   Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
   GRANFRIC: compute ID group hardsphere/temp [inertia sphere|disc|<q>]
   global vector: T_tr, T_rot, R = T_rot/T_tr, E_tr, E_rot
   global scalar: T_tr, with dof = dim N: a temperature for thermo_modify temp, velocity temp
   and compute pressure
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(hardsphere/temp,ComputeHardsphereTemp);
// clang-format on
#else

#ifndef LMP_GRANFRIC_COMPUTE_HARDSPHERE_TEMP_H
#define LMP_GRANFRIC_COMPUTE_HARDSPHERE_TEMP_H

#include "compute.h"
#include "host_compat.h"

#include <vector>

namespace LAMMPS_NS {

class ComputeHardsphereTemp : public Compute {
 protected:
  GRANFRIC_HOST_ERROR    // (under LIGGGHTS: LAMMPS's error calls)

 public:
  ComputeHardsphereTemp(class LAMMPS *, int, char **);
  ~ComputeHardsphereTemp() override;
  void init() override;
  void setup() override;
  void compute_vector() override;
  double compute_scalar() override;

 private:
  double qshape;                // I/(m a^2) for all types; < 0: from the hardsphere pair style
  std::vector<double> qused;    // per type (index 0 unused)
  void sums(double *all);    // sum m v^2, sum I w^2, atoms: over the group and all ranks
};

}    // namespace LAMMPS_NS

#endif
#endif
