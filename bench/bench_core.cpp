// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC benchmark of the event-driven core alone (no LAMMPS): collisions per second per core
// for 2D discs / 3D spheres at a given fraction and N, windows of dt mean free times, memory per
// particle. Prints its figures; it is not a test.
//   bench_core [dim] [N] [fraction] [dt_in_mean_free_times] [collisions_per_particle]
//              [cell width in diameters, 0: the core's automatic choice] [blocks K] [shell 0|1]
#include "bench_system.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

using namespace granfric;
using granfric::bench::build;

int main(int argc, char **argv)
{
  const int dim = argc > 1 ? atoi(argv[1]) : 2;
  const long N = argc > 2 ? atol(argv[2]) : 10000;
  const double phi = argc > 3 ? atof(argv[3]) : 0.3;
  const double dt_mft = argc > 4 ? atof(argv[4]) : 1.0;
  const double cpp = argc > 5 ? atof(argv[5]) : 20.0;
  const double cell = argc > 6 ? atof(argv[6]) : 0.0;
  // K > 1: the ideal of spatial blocking. K independent periodic systems of N/K particles each
  // (the memory of N), advanced one window each in turn, so that a block's records stay in cache
  // during its window and are evicted by the others' between windows. No shell of copies, no
  // exchange, no check: a lower bound on what processing one system of N in blocks could cost.
  // shell 1: each block also carries the shell of copies an exact blocked window needs, as
  // fix hardsphere/ed's parallel domain sizes it: W = 2 reach v_max dt + one diameter on every
  // side (reach 1.2; v_max the expected largest speed of the N particles, N P(|v| > v_max) = 1 at
  // T = 1). A block then is a periodic system of the larger side L + 2W at the same fraction,
  // whose collisions count only in the share of its owned particles: still a lower bound (no
  // gather, no exchange, no check, no redo).
  const long K = argc > 7 ? std::max(1L, atol(argv[7])) : 1;
  const bool shell = argc > 8 && atoi(argv[8]) != 0;
  const long nb = N / K;
  long nsys = nb;    // particles per block system (owned + shell)
  double wshell = 0.0;
  if (K > 1 && shell) {
    const double mft1 = bench::mean_free_time(dim, nb, phi);
    double lo = 0.0, hi = 20.0;    // N P(|v| > u) = 1, Maxwell at T = 1 in dim dimensions
    for (int it = 0; it < 100; it++) {
      const double u = 0.5 * (lo + hi);
      const double tail = dim == 2 ? std::exp(-0.5 * u * u)
                                   : std::erfc(u / std::sqrt(2.0)) +
              std::sqrt(2.0 / M_PI) * u * std::exp(-0.5 * u * u);
      (N * tail > 1.0 ? lo : hi) = u;
    }
    wshell = 2.0 * 1.2 * lo * dt_mft * mft1 + 1.0;
    const double side = bench::box_side(dim, nb, phi);
    nsys = std::lround(nb * std::pow((side + 2.0 * wshell) / side, dim));
  }

  std::vector<EventDriven> eds(K);
  double mft = 0.0;
  for (long b = 0; b < K; b++) mft = build(eds[b], dim, nsys, phi, cell, (unsigned) (1 + b));
  const double dt = dt_mft * mft;
  const long ntot = nsys * K;
  const double owned = (double) nb / nsys;    // the owned share of a block's collisions

  // equilibrate 5 collisions per particle (randomises the lattice), then measure
  for (auto &ed : eds) {
    ed.start();
    long coll = 0;
    while (coll < 5 * nsys / 2) {
      coll += ed.advance_to(dt).collisions;
      ed.rebase(dt);
    }
  }
  EDStats s;
  const auto t0 = std::chrono::steady_clock::now();
  long windows = 0;
  while (s.collisions < (long) (cpp * ntot / 2)) {
    for (auto &ed : eds) {
      s.add(ed.advance_to(dt));
      ed.rebase(dt);
    }
    windows++;
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  double mem = 0.0;
  for (const auto &ed : eds) mem += (double) ed.memory_bytes();
  std::printf("dim %d N %ld fraction %.3f dt %.3g mft | cells %.3g wide | collisions %ld "
              "crossings/collision %.3f windows %ld | %.4g s | %.4g collisions/s | core memory %.0f "
              "B/particle",
              dim, nb * K, phi, dt_mft, eds[0].cell_size(), s.collisions,
              (double) s.crossings / s.collisions, windows, secs, s.collisions / secs, mem / ntot);
  if (K > 1) std::printf(" | %ld independent blocks of %ld", K, nb);
  if (nsys > nb)
    std::printf(" with a shell %.3g diameters wide (%ld in all): %.4g owned collisions/s", wshell,
                nsys, owned * s.collisions / secs);
  std::printf("\n");
  return 0;
}
