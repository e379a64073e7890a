// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC benchmarks: one periodic test system of the event-driven core (shared by bench_core
// and bench_kick)
#pragma once

#include "core/event_driven.h"

#include <cmath>
#include <cstdlib>
#include <random>
#include <vector>

namespace granfric {
namespace bench {
constexpr double RADIUS = 0.5;    // (diameter 1)

// the side of the cubic (square) periodic box that holds n particles at fraction phi
inline double box_side(int dim, long n, double phi)
{
  const double a = RADIUS;
  const double vol1 = dim == 2 ? M_PI * a * a : 4.0 / 3.0 * M_PI * a * a * a;
  return std::pow(n * vol1 / phi, 1.0 / dim);
}

// the Enskog mean free time at T = 1 (2D Henderson, 3D Carnahan-Starling) of that system
inline double mean_free_time(int dim, long n, double phi)
{
  const double dens = n / std::pow(box_side(dim, n, phi), dim);
  const double g = dim == 2 ? (1 - 7 * phi / 16) / ((1 - phi) * (1 - phi))
                            : (1 - phi / 2) / std::pow(1 - phi, 3);
  const double nu = dim == 2 ? 2 * dens * g * std::sqrt(M_PI) : 4 * dens * g * std::sqrt(M_PI);
  return 1.0 / nu;
}

// one periodic system of n equal discs/spheres (diameter 1, mass 1) at fraction phi: lattice start,
// Maxwellian velocities, T = 1; returns its mean free time at T = 1 (mean_free_time)
inline double build(EventDriven &ed, int dim, long n, double phi, double cell, unsigned seed)
{
  const double side = box_side(dim, n, phi);
  const int m = (int) std::ceil(std::pow((double) n, 1.0 / dim) - 1e-9);
  const double h = side / m;
  EDOptions o;
  o.dim = dim;
  o.cell_width = cell;    // (diameter 1)
  // how candidates are found, for measurements of either way (EDOptions::neighbours, list_skin):
  // GRANFRIC_NEIGHBOURS = 0 (automatic, the default), 1 (cells), 2 (neighbour lists);
  // GRANFRIC_SKIN = the lists' skin in diameters (0: automatic); GRANFRIC_SIMD = 0: candidates
  // one at a time, not in AVX2 lanes; GRANFRIC_PREFETCH_BYTES = the core's records from which
  // the event loop prefetches (EDOptions::prefetch_bytes)
  if (const char *nm = std::getenv("GRANFRIC_NEIGHBOURS")) o.neighbours = std::atoi(nm);
  if (const char *sk = std::getenv("GRANFRIC_SKIN")) o.list_skin = std::atof(sk);
  if (const char *sd = std::getenv("GRANFRIC_SIMD")) o.simd = std::atoi(sd) != 0;
  if (const char *pb = std::getenv("GRANFRIC_PREFETCH_BYTES")) o.prefetch_bytes = std::atol(pb);
  for (int d = 0; d < 3; d++) {
    o.lo[d] = 0.0;
    o.hi[d] = (d < dim) ? side : 1.0;
  }
  o.shape.assign(2, dim == 2 ? 0.5 : 0.4);
  ed.configure(o, 1, std::vector<LawParams>(4, LawParams::rough(1.0, -1.0)));
  ed.resize((int) n);
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> G(0, 1);
  for (long i = 0; i < n; i++) {
    auto p = ed.particle((int) i);
    const long ix = i % m, iy = (i / m) % m, iz = i / ((long) m * m);
    p.x = Vec3((ix + 0.5) * h, (iy + 0.5) * h, dim == 3 ? (iz + 0.5) * h : 0.5);
    p.v = Vec3(G(gen), G(gen), dim == 3 ? G(gen) : 0.0);
    p.a = RADIUS;
    p.m = 1.0;
  }
  return mean_free_time(dim, n, phi);
}
}    // namespace bench
}    // namespace granfric
