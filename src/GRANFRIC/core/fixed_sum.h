// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: sums that do not depend on the order of their terms.
//
// A floating-point sum depends on the order of its terms in the last bits, so a sum over atoms
// differs with the atoms' storage order and with how they are split among MPI ranks. Here each
// term is rounded to a grid of spacing 1 / scale, and the grid counts (integers) are summed
// exactly: the result is a function of the set of terms alone. With scale from fixed_scale(b,
// n), n terms of magnitude at most b sum without overflow, each rounded by at most 2^-62 b n.
#ifndef GRANFRIC_CORE_FIXED_SUM_H
#define GRANFRIC_CORE_FIXED_SUM_H

#include <cmath>
#include <cstdint>

namespace granfric {

// the grid scale (a power of two) for at most n terms of magnitude at most b: |sum| < 2^62
inline double fixed_scale(double b, double n)
{
  if (!(b > 0.0) || !(n >= 1.0) || !std::isfinite(b * n)) return 1.0;
  int e;
  std::frexp(b * n, &e);    // b n < 2^e
  return std::ldexp(1.0, 62 - e);
}

// a term in grid counts, and a sum of grid counts back as a number
inline int64_t to_fixed(double x, double scale)
{
  return (int64_t) std::llround(x * scale);
}
inline double from_fixed(int64_t s, double scale)
{
  return (double) s / scale;
}

}    // namespace granfric

#endif
