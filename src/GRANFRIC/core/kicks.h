// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: homogeneous stochastic driving by random kicks.
//
// Herbst et al. 2005, eqs 7-9: at the times k / f_dr every driven particle gets an independent
// Gaussian velocity increment of standard deviation v_dr per translational component (and, with
// spin > 0, a Gaussian spin increment carrying spin times the translational power). With
// momentum on, the increments' mass-weighted mean over the driven particles is taken off again,
// so the total momentum stays what it was. A particle's numbers depend only on (seed, its ID,
// k): the kicks are the same on any number of MPI ranks. The momentum shift is a fixed-point sum
// (fixed_sum.h): the same bits whatever the particles' order and split among ranks. The kicks
// act inside a window as the core's global events (EventDriven::set_global_events).
#ifndef GRANFRIC_CORE_KICKS_H
#define GRANFRIC_CORE_KICKS_H

#include "event_driven.h"

#include <cstdint>
#include <vector>

namespace granfric {

struct Kicks {
  double fdr = 1.0;       // kicks per unit time (> 0)
  double vdr = 0.0;       // standard deviation of a velocity component's increment (>= 0)
  double spin = 0.0;      // rotational power / translational power (>= 0)
  long seed = 1;          // > 0
  bool momentum = true;   // keep the total momentum of the driven particles

  // the Gaussian number n (0..5: 3 velocity and 3 spin components) of the particle with ID tag
  // at kick k
  static double gaussian(long seed, long tag, long k, int n);

  // the kicks with (k - shift) / f_dr in [t0, t1) from kick `next` on: their times (never
  // before t0) and indices appended; next moves past them. Kick k (its random numbers) happens
  // at time (k - shift) / f_dr.
  void kicks_in(double t0, double t1, long &next, std::vector<double> &times,
                std::vector<long> &index, long shift = 0) const;
  // The shift for a run that starts at time t with kick `next` to come: `shift` if kick
  // next - 1 came before t and kick next does not (up to the rounding of t: the windows of a
  // run that went on to t left it so), else the shift that makes kick next the first on the
  // grid k / f_dr at or after t (the time was moved, e.g. by LAMMPS's reset_timestep). The
  // kicks keep their rate and times on that grid, and no kick's random numbers come twice.
  long shift_at(double t, long next, long shift) const;

  // The momentum shift of kick k as partial sums: a caller adds every driven particle it holds
  // (add), sums the four counts over all its parts (ranks), and takes the shift (shift). The
  // scales come from the largest mass of a driven particle and their number, the same
  // everywhere.
  struct MomentumSums {
    int64_t count[4] = {0, 0, 0, 0};    // momentum x, y, z, and mass, in grid counts
    double sp = 1.0, sm = 1.0;          // grid scales of momentum and mass
  };
  MomentumSums momentum_sums(double mmax, double n) const;
  void add(MomentumSums &s, long tag, double m, long k, int dim) const;
  Vec3 shift(const MomentumSums &s) const;
  // the shift of kick k over n particles held by one process: IDs tags, masses m, the driven
  // ones flagged (driven null: all)
  Vec3 local_shift(long n, const long *tags, const double *m, const uint8_t *driven, long k,
                   int dim) const;

  // kick k of particle p with ID tag (dim: 2 or 3), less the momentum shift dvcm
  void apply(EDParticle p, long tag, long k, int dim, const Vec3 &dvcm) const;
};

// The kicks in window time [0, dt) of a window that starts at absolute time t0, for a system
// held whole by one process: each scheduled as a global event of ed that kicks the particles
// flagged in `driven` (by external index, kept alive by the caller) with IDs tags (likewise),
// with the momentum shift over them. next: the next kick's index (advanced).
void schedule_kicks(EventDriven &ed, const Kicks &kicks, double t0, double dt, long &next,
                    const long *tags, const uint8_t *driven);

}    // namespace granfric

#endif
