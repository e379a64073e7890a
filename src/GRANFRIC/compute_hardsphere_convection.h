/* -*- c++ -*- ----------------------------------------------------------
   SPDX-License-Identifier: GPL-2.0-or-later
   Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
   GRANFRIC: compute ID group hardsphere/convection
   global vector (Risso et al. 2005, eqs 10-11), x measured from the lower box edge:
     Psi1 = (1/N) sum v_y sin(2 pi x / L_x),  Psi2 = -(1/N) sum v_y cos(2 pi x / L_x)
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(hardsphere/convection,ComputeHardsphereConvection);
// clang-format on
#else

#ifndef LMP_GRANFRIC_COMPUTE_HARDSPHERE_CONVECTION_H
#define LMP_GRANFRIC_COMPUTE_HARDSPHERE_CONVECTION_H

#include "compute.h"
#include "host_compat.h"

namespace LAMMPS_NS {

class ComputeHardsphereConvection : public Compute {
 protected:
  GRANFRIC_HOST_ERROR    // (under LIGGGHTS: LAMMPS's error calls)

 public:
  ComputeHardsphereConvection(class LAMMPS *, int, char **);
  ~ComputeHardsphereConvection() override;
  void init() override {}
  void compute_vector() override;
};

}    // namespace LAMMPS_NS

#endif
#endif
