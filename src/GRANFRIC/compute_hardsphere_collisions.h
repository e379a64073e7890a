/* -*- c++ -*- ----------------------------------------------------------
   SPDX-License-Identifier: GPL-2.0-or-later
   Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
   GRANFRIC: compute ID group hardsphere/collisions fixID [bins N]
   Statistics of the collisions processed by fix hardsphere/ed fixID over a window (the time
   since this compute was last invoked, or since the run began):
   vector: 1 collision frequency per particle, 2 <dE> per particle-particle collision,
           3 sliding fraction, 4 particle-particle collisions in the window, 5 window length,
           6 <dE> per particle-wall collision (lab frame), 7 particle-wall collisions
   array (N x 2): impact angle gamma at the bin centre, probability density P(gamma)
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(hardsphere/collisions,ComputeHardsphereCollisions);
// clang-format on
#else

#ifndef LMP_GRANFRIC_COMPUTE_HARDSPHERE_COLLISIONS_H
#define LMP_GRANFRIC_COMPUTE_HARDSPHERE_COLLISIONS_H

#include "compute.h"

#include "event_driven.h"
#include "host_compat.h"

#include <string>

namespace LAMMPS_NS {

class ComputeHardsphereCollisions : public Compute {
 protected:
  GRANFRIC_HOST_ERROR    // (under LIGGGHTS: LAMMPS's error calls)

 public:
  ComputeHardsphereCollisions(class LAMMPS *, int, char **);
  ~ComputeHardsphereCollisions() override;
  void init() override;
  void compute_vector() override;
  void compute_array() override;

 private:
  std::string fixid;
  class FixHardsphereED *fix;
  int nbins;
  granfric::EDStats seen;     // cumulative statistics at the start of the window
  double seen_time;
  bigint computed_step;
  void update_window();
};

}    // namespace LAMMPS_NS

#endif
#endif
