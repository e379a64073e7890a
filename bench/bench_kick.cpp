// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC benchmark: what a random kick of every particle (the core's kicks, core/kicks.h, as
// fix hardsphere/kick uses them) costs the event-driven core, per particle. A kick changes every
// velocity, so every particle's next event must be predicted afresh: the core brings all
// particles to the kick time, draws their Gaussian numbers, sums the momentum shift, applies the
// kick, runs predict_all() (each pair of neighbouring cells once) and rebuilds the queue. By
// default the kicks have v_dr = 0: every step of a kick is done, but no velocity changes, so the
// trajectory is the same with and without them and the difference of the two timings is the
// kicks' cost alone. Rounds alternate without and with kicks; prints the fastest of each. It is
// not a test.
//   bench_kick [dim] [N] [fraction] [kicks per mean free time] [mean free times per round]
//              [rounds] [v_dr]
#include "bench_system.h"

#include "core/kicks.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

using namespace granfric;

int main(int argc, char **argv)
{
  const int dim = argc > 1 ? atoi(argv[1]) : 2;
  const long N = argc > 2 ? atol(argv[2]) : 4096;
  const double phi = argc > 3 ? atof(argv[3]) : 0.05;
  const int kpm = argc > 4 ? std::max(1, atoi(argv[4])) : 10;
  const int mfts = argc > 5 ? std::max(1, atoi(argv[5])) : 20;
  const int rounds = argc > 6 ? std::max(1, atoi(argv[6])) : 5;
  const double vdr = argc > 7 ? atof(argv[7]) : 0.0;

  EventDriven ed;
  const double mft = bench::build(ed, dim, N, phi, 0.0, 1);
  ed.start();
  for (int w = 0; w < 5; w++) {    // equilibrate 5 mean free times
    ed.advance_to(mft);
    ed.rebase(mft);
  }
  Kicks kick;
  kick.fdr = kpm / mft;
  kick.vdr = vdr;
  std::vector<long> tags(N);
  for (long e = 0; e < N; e++) tags[e] = e + 1;
  const std::vector<uint8_t> driven(N, 1);
  double clock = 5.0 * mft;    // (absolute time of the next window)
  long next = (long) std::ceil(clock * kick.fdr);
  // one round: mfts windows of one mean free time, with kpm kicks in each or none
  auto round = [&](bool kicks, EDStats &s) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int w = 0; w < mfts; w++) {
      if (kicks) schedule_kicks(ed, kick, clock, mft, next, tags.data(), driven.data());
      s.add(ed.advance_to(mft));
      ed.rebase(mft);
      clock += mft;
      next = std::max(next, (long) std::ceil(clock * kick.fdr));    // (no kicks: none owed)
    }
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  double best[2] = {1e300, 1e300};
  EDStats st[2];
  for (int r = 0; r < rounds; r++)
    for (int k = 0; k < 2; k++) {
      EDStats s;
      const double secs = round(k == 1, s);
      if (secs < best[k]) best[k] = secs, st[k] = s;    // (the fastest round, with its counts)
    }
  const double per_coll = best[0] / (double) st[0].collisions;
  // (with v_dr > 0 the kicked rounds have other collisions: their cost at the unkicked rate is
  // taken off)
  const double extra = (double) (st[1].collisions - st[0].collisions) * per_coll;
  const double per_kick = (best[1] - best[0] - extra) / ((double) kpm * mfts * N);
  std::printf("dim %d N %ld fraction %.3f | %d mean free times per round, fastest of %d | "
              "no kicks: %ld collisions, %.3g us per collision | %d kicks per mean free "
              "time (v_dr %g, %ld global events): %ld collisions, +%.3g s | one kick costs %.3g us per "
              "particle = %.3g collisions\n",
              dim, N, phi, mfts, rounds, st[0].collisions, 1e6 * per_coll, kpm, vdr,
              st[1].global_events, st[1].collisions, best[1] - best[0], 1e6 * per_kick,
              per_kick / per_coll);
  return 0;
}
