// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: Monte Carlo mean energy change per collision over a Maxwellian,
// through the same collision law the simulations use (Risso et al. 2005, Sec. II; the
// doc/conventions.rst, correction 9): equal particles, velocities Gaussian at T0 per
// component, spins Gaussian with I <w^2> = T0 per spin component, collisions weighted by the
// normal relative speed (only approaching pairs).
#ifndef GRANFRIC_CORE_ENERGY_LOSS_H
#define GRANFRIC_CORE_ENERGY_LOSS_H

#include "collision.h"

#include <cstdint>

namespace granfric {

struct EnergyLossResult {
  double mean = 0.0;       // <dE> per collision (m = 1)
  double stderr_ = 0.0;    // its standard error (ratio estimator of the weighted mean)
  double mean_tr = 0.0, stderr_tr = 0.0;      // translational part
  double mean_rot = 0.0, stderr_rot = 0.0;    // rotational part
  double sliding = 0.0;    // weighted fraction of sliding collisions
  long samples = 0;        // approaching pairs used
};

// velocities Gaussian at Ttr per component, spins with I <w^2> = Trot per spin component
EnergyLossResult mean_energy_changes(const LawParams &law, double q, int dim, double Ttr,
                                     double Trot, long n, uint64_t seed);

// Risso's convention: one temperature T0 for both
inline EnergyLossResult mean_energy_loss(const LawParams &law, double q, int dim, double T0,
                                         long n, uint64_t seed)
{
  return mean_energy_changes(law, q, dim, T0, T0, n, seed);
}

}    // namespace granfric

#endif
