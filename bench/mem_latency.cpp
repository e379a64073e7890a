// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC benchmark: what one cache miss costs on this machine, to set against the misses per
// collision of the event loop (bench/cache_profile.sh). For buffers from 16 KiB to 512 MiB
// (allocated like the core's large arrays: 2 MiB aligned, transparent huge pages): the time of
// one dependent random load (a pointer chase through a random cycle of 64-byte lines: the
// latency), and of one load when 8 independent chases run interleaved (what the memory system
// overlaps, as out-of-order execution does for the independent misses of one event).
//   build/mem_latency [largest MiB]
#include "core/huge_alloc.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <random>
#include <vector>

namespace {

struct alignas(64) Line {
  uint32_t next;
  char pad[60];
};

// a random cyclic permutation of n lines (Sattolo), as next indices
void make_cycle(granfric::big_vector<Line> &a, std::mt19937_64 &rng)
{
  const uint32_t n = (uint32_t) a.size();
  std::vector<uint32_t> p(n);
  std::iota(p.begin(), p.end(), 0u);
  for (uint32_t i = n - 1; i > 0; i--) {
    const uint32_t j = (uint32_t) (rng() % i);
    std::swap(p[i], p[j]);
  }
  for (uint32_t i = 0; i < n; i++) a[p[i]].next = p[(i + 1) % n];
}

double ns_per_load(const granfric::big_vector<Line> &a, int chains, long loads)
{
  uint32_t c[8];
  for (int k = 0; k < chains; k++) c[k] = (uint32_t) ((uint64_t) k * a.size() / chains);
  const long steps = loads / chains;
  const auto t0 = std::chrono::steady_clock::now();
  for (long s = 0; s < steps; s++)
    for (int k = 0; k < chains; k++) c[k] = a[c[k]].next;
  const auto t1 = std::chrono::steady_clock::now();
  uint32_t sink = 0;
  for (int k = 0; k < chains; k++) sink ^= c[k];
  if (sink == 0xffffffffu) std::printf(" ");    // keeps the chases
  return std::chrono::duration<double, std::nano>(t1 - t0).count() / (double) (steps * chains);
}

}    // namespace

int main(int argc, char **argv)
{
  const double maxmib = argc > 1 ? std::atof(argv[1]) : 512.0;
  std::mt19937_64 rng(12345);
  std::printf("%12s %16s %22s\n", "buffer", "latency (ns)", "8 interleaved (ns)");
  for (double kib = 16; kib <= maxmib * 1024.0; kib *= 2) {
    const size_t n = (size_t) (kib * 1024.0 / sizeof(Line));
    granfric::big_vector<Line> a(n);
    make_cycle(a, rng);
    const long loads = std::max<long>(2000000, (long) (4 * n));
    ns_per_load(a, 1, std::min<long>(loads, (long) n));    // touch every page once
    const double one = ns_per_load(a, 1, loads), eight = ns_per_load(a, 8, loads);
    if (kib < 1024)
      std::printf("%9.0f KiB %16.2f %22.2f\n", kib, one, eight);
    else
      std::printf("%9.0f MiB %16.2f %22.2f\n", kib / 1024, one, eight);
    std::fflush(stdout);
  }
  return 0;
}
