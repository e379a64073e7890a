/* -*- c++ -*- ----------------------------------------------------------
   SPDX-License-Identifier: GPL-2.0-or-later
   Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
   GRANFRIC: fix ID group hardsphere/kick f_dr v_dr seed [momentum yes|no] [spin fraction]

   Homogeneous stochastic driving (Herbst et al. 2005, eqs 7-9): at the times k/f_dr every atom
   of the group gets an independent Gaussian velocity increment of standard deviation v_dr per
   translational component. The kicks happen at their exact times inside the event-driven step
   of fix hardsphere/ed, which calls this fix. The kicks themselves are the core's (core/kicks.h);
   this fix holds their parameters, the next kick's index and the shift of the kick times (kept
   in restart files) and the sum of the momentum shift over the ranks.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(hardsphere/kick,FixHardsphereKick);
// clang-format on
#else

#ifndef LMP_GRANFRIC_FIX_HARDSPHERE_KICK_H
#define LMP_GRANFRIC_FIX_HARDSPHERE_KICK_H

#include "fix.h"

#include "hardsphere_window_parts.h"
#include "kicks.h"
#include "host_compat.h"

namespace LAMMPS_NS {

class FixHardsphereKick : public Fix, public HardsphereDriving {
 protected:
  GRANFRIC_HOST_ERROR    // (under LIGGGHTS: LAMMPS's error calls)

 public:
  FixHardsphereKick(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  double compute_scalar() override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  // (HardsphereDriving)
  void kicks_in(double t0, double t1, std::vector<double> &times, std::vector<long> &index) override;
  long kick_counter() const override { return next_kick; }
  void rewind(long k) override { next_kick = k; }
  granfric::Vec3 momentum_shift(long k, int dim) const override;
  double speed_scale(double dt, int dim) const override;
  void apply(granfric::EventDriven &ed, const std::vector<tagint> &tag, const std::vector<int> &mask,
             long k, int dim, const granfric::Vec3 &dvcm) const override;
  // bounds (doc/fix_hardsphere_kick.rst): kicks per step, kicks per step times atoms, the kick
  // index of a run, v_dr, spin
  static constexpr double MAX_KICKS_PER_STEP = 1e6, MAX_ATOM_KICKS_PER_STEP = 1e7;
  static constexpr double MAX_KICK_INDEX = 1e15, MAX_VDR = 1e150, MAX_SPIN = 1e6;

 private:
  granfric::Kicks law;  // f_dr, v_dr, seed, momentum, spin
  long next_kick;      // index of the next kick: the kicks so far (restart)
  long kick_shift;     // kick k happens at time (k - kick_shift) / f_dr (restart)
  void check_kicks_per_step() const;
};

}    // namespace LAMMPS_NS

#endif
#endif
