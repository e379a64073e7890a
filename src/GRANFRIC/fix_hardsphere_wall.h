/* -*- c++ -*- ----------------------------------------------------------
   SPDX-License-Identifier: GPL-2.0-or-later
   Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
   GRANFRIC: plane walls.

   fix ID group hardsphere/wall face pos [coeffs c1 ...] [thermal T seed]
                                          [vibrate sine|parabolic A omega] [slide vx vy vz]
                                          [shake x|y|z A omega]

   A static plane wall for fix hardsphere/ed: face xlo|xhi|ylo|yhi|zlo|zhi in a non-periodic
   dimension, at position pos (a number or EDGE = the box boundary). Collisions with it are
   processed exactly by the event loop, with the wall limit of the hardsphere pair style's law:
   its own coefficients after the keyword coeffs (the values pair_coeff takes), or by default
   those of pair_coeff I I for particles of type I. A wall may vibrate along its normal, slide
   within its plane at a constant velocity (a sheared or Couette cell) and oscillate within its
   plane (a bed shaken sideways).
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(hardsphere/wall,FixHardsphereWall);
// clang-format on
#else

#ifndef LMP_GRANFRIC_FIX_HARDSPHERE_WALL_H
#define LMP_GRANFRIC_FIX_HARDSPHERE_WALL_H

#include "fix.h"

#include "hardsphere_window_parts.h"
#include "host_compat.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class FixHardsphereWall : public Fix, public HardsphereWallPart {
 protected:
  GRANFRIC_HOST_ERROR    // (under LIGGGHTS: LAMMPS's error calls)

 public:
  FixHardsphereWall(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  // (HardsphereWallPart; the wall at the current box, after init() validated the coefficients)
  const char *wall_id() const override { return id; }
  granfric::EDWall wall() const override;
  int dimension() const override { return dim; }
  std::string face() const override { return std::string(1, "xyz"[dim]) + (side < 0 ? "lo" : "hi"); }
  granfric::EDWall geometry() const override;
  void tally(long hits, const double *impulse, double work, double dt) override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

 private:
  int dim, side;
  bool edge;
  double pos;
  std::vector<std::string> coeffs;    // own law coefficients (empty: the pair style's I,I)
  granfric::LawParams own_law;        // coeffs, parsed by init()
  double temperature;                 // thermal wall temperature (< 0: not thermal)
  long seed;
  double amplitude, omega;            // vibration, 0: static
  bool sine;                          // sinusoidal (else piecewise parabolic)
  double slide[3] = {0, 0, 0};        // velocity within the wall's plane
  int shake_dim = -1;                 // oscillation within the plane along this dimension
  double shake_A = 0.0, shake_omega = 0.0;
  void check_slide(const std::string &face) const;
  void parse_shake(const std::string &face, const std::string &d, const char *A, const char *w);
  double step_force[3] = {0, 0, 0};   // force on the wall, averaged over the last step
  // since the fix was defined (kept in restart files): collisions, momentum given to the wall,
  // energy given to the particles, time
  double total_hits = 0.0, total_impulse[3] = {0, 0, 0}, total_work = 0.0, total_time = 0.0;
};

}    // namespace LAMMPS_NS

#endif
#endif
