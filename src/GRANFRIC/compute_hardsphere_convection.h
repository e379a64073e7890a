/* -*- c++ -*- ----------------------------------------------------------
   SPDX-License-Identifier: GPL-2.0-or-later
   Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
   GRANFRIC: compute ID group hardsphere/convection [vertical gravity|x|y|z]

   The convection order parameters of Risso et al. 2005 (eqs 10-11) along each horizontal
   axis h, with v_up the velocity component along the vertical (upward: against gravity) and
   x_h measured from the box's lower edge in h:
     Psi1_h = (1/N) sum v_up sin(2 pi x_h / L_h),  Psi2_h = -(1/N) sum v_up cos(2 pi x_h / L_h)
   A global vector of 2 values in 2d (the one horizontal axis), 4 in 3d (the two horizontal
   axes in the order x, y, z).
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
  void init() override;
  void compute_vector() override;

 private:
  int asked = -1;        // keyword vertical: an axis 0, 1, 2, or -1 (from gravity)
  int up = 1;            // the vertical axis (set by init)
  double sign = 1.0;     // +1: upward is +up, -1: upward is -up
  int horizontal[2] = {0, 2}, nh = 1;    // the horizontal axes of the simulation
};

}    // namespace LAMMPS_NS

#endif
#endif
