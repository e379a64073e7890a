// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: counter-based random numbers.
//
// Every random number the core draws (thermal walls, kicks) is a pure function of a key built
// from a seed, the particle's identity and the event (a collision time, a kick index), never
// of a generator's state: a particle draws the same numbers on any number of MPI ranks and in
// any order of processing. The mixing function is splitmix64's finaliser.
#ifndef GRANFRIC_CORE_COUNTER_RNG_H
#define GRANFRIC_CORE_COUNTER_RNG_H

#include <cmath>
#include <cstdint>

namespace granfric {

// a bijective scramble of 64 bits (splitmix64)
inline uint64_t mix64(uint64_t z)
{
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// uniform numbers from 64 random bits (their top 53): in (0, 1), never 0 (a logarithm's
// argument), and in [0, 1)
inline double open_uniform(uint64_t bits)
{
  return ((bits >> 11) + 0.5) * 0x1.0p-53;
}
inline double unit_uniform(uint64_t bits)
{
  return (bits >> 11) * 0x1.0p-53;
}

// a stream of uniform numbers in (0, 1) from a key: each call scrambles the key once more
struct CounterStream {
  uint64_t key;
  double uniform()
  {
    key = mix64(key);
    return open_uniform(key);
  }
};

// Box-Muller: the radius sqrt(-2 ln u1) of a pair of standard Gaussians from u1 in (0, 1)
inline double gauss_radius(double u1)
{
  return std::sqrt(-2.0 * std::log(u1));
}

}    // namespace granfric

#endif
