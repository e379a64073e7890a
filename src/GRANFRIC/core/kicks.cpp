// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: random kicks (see kicks.h).
#include "kicks.h"

#include "counter_rng.h"
#include "fixed_sum.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace granfric {

// (seed, tag, k) -> a key; the pair (2 (n / 2), 2 (n / 2) + 1) of numbers from one Box-Muller
// draw of two uniforms
double Kicks::gaussian(long seed, long tag, long k, int n)
{
  const uint64_t base = mix64(mix64(mix64((uint64_t) seed) ^ (uint64_t) tag) ^ (uint64_t) k);
  const uint64_t a = mix64(base ^ (uint64_t) (2 * (n / 2) + 1));
  const uint64_t b = mix64(a);
  const double r = gauss_radius(open_uniform(a));
  const double u2 = unit_uniform(b);
  return (n % 2 == 0) ? r * std::cos(2.0 * M_PI * u2) : r * std::sin(2.0 * M_PI * u2);
}

void Kicks::kicks_in(double t0, double t1, long &next, std::vector<double> &times,
                     std::vector<long> &index, long shift) const
{
  while ((next - shift) / fdr < t1) {
    times.push_back(std::max((next - shift) / fdr, t0));
    index.push_back(next);
    next++;
  }
}

long Kicks::shift_at(double t, long next, long shift) const
{
  const double eps = 1e-9 * (std::fabs(t) + 1.0 / fdr);
  if ((next - 1 - shift) / fdr < t + eps && (next - shift) / fdr >= t - eps) return shift;
  long k = (long) std::ceil(t * fdr);    // (the first grid index at or after t)
  while ((k - 1) / fdr >= t) k--;
  while (k / fdr < t) k++;
  return next - k;
}

// Gaussians from Box-Muller with 53-bit uniforms stay below 9 in magnitude
Kicks::MomentumSums Kicks::momentum_sums(double mmax, double n) const
{
  MomentumSums s;
  s.sp = fixed_scale(9.0 * vdr * mmax, n);
  s.sm = fixed_scale(mmax, n);
  return s;
}

void Kicks::add(MomentumSums &s, long tag, double m, long k, int dim) const
{
  for (int d = 0; d < dim; d++) s.count[d] += to_fixed(m * vdr * gaussian(seed, tag, k, d), s.sp);
  s.count[3] += to_fixed(m, s.sm);
}

Vec3 Kicks::shift(const MomentumSums &s) const
{
  if (!momentum || s.count[3] <= 0) return Vec3();
  const double M = from_fixed(s.count[3], s.sm);
  return (1.0 / M) * Vec3(from_fixed(s.count[0], s.sp), from_fixed(s.count[1], s.sp),
                          from_fixed(s.count[2], s.sp));
}

Vec3 Kicks::local_shift(long n, const long *tags, const double *m, const uint8_t *driven, long k,
                        int dim) const
{
  if (!momentum) return Vec3();
  double mmax = 0.0, count = 0.0;
  for (long i = 0; i < n; i++)
    if (!driven || driven[i]) mmax = std::max(mmax, m[i]), count += 1.0;
  MomentumSums s = momentum_sums(mmax, count);
  for (long i = 0; i < n; i++)
    if (!driven || driven[i]) add(s, tags[i], m[i], k, dim);
  return shift(s);
}

void Kicks::apply(EDParticle p, long tag, long k, int dim, const Vec3 &dvcm) const
{
  p.v += vdr * Vec3(gaussian(seed, tag, k, 0), gaussian(seed, tag, k, 1),
                    dim == 3 ? gaussian(seed, tag, k, 2) : 0.0) - dvcm;
  if (spin > 0.0) {
    // rotational power = spin x translational power: d_tr v_dr^2 m / 2 per kick against
    // d_rot w^2 I / 2 with I = q m a^2
    const int dtr = dim, drot = dim == 2 ? 1 : 3;
    const double w = vdr * std::sqrt(spin * dtr / (p.q * p.a * p.a * drot));
    if (dim == 2)
      p.w.z += w * gaussian(seed, tag, k, 3);
    else
      p.w += w * Vec3(gaussian(seed, tag, k, 3), gaussian(seed, tag, k, 4), gaussian(seed, tag, k, 5));
  }
}

void schedule_kicks(EventDriven &ed, const Kicks &kicks, double t0, double dt, long &next,
                    const long *tags, const uint8_t *driven)
{
  std::vector<double> times;
  std::vector<long> index;
  kicks.kicks_in(t0, t0 + dt, next, times, index);
  if (times.empty()) return;
  const int n = ed.size(), dim = ed.options().dim;
  std::vector<double> mass(n);
  for (int e = 0; e < n; e++) mass[e] = std::as_const(ed).particle(e).m;
  std::vector<Vec3> dvcm(times.size());
  for (size_t m = 0; m < times.size(); m++) {
    dvcm[m] = kicks.local_shift(n, tags, mass.data(), driven, index[m], dim);
    times[m] -= t0;
  }
  ed.set_global_events(times, [&ed, kicks, index, dvcm, tags, driven, n, dim](int g) {
    for (int e = 0; e < n; e++)
      if (driven[e]) kicks.apply(ed.particle(e), tags[e], index[g], dim, dvcm[g]);
  });
}

}    // namespace granfric
