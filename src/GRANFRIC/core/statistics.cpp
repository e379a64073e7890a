// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: statistics and records of the collisions (see event_driven.h): every pair and wall
// collision is booked here, through one hook each (record_pair, record_wall), into the window's
// statistics, the per-particle tallies, the cross-rank history and the collision log.
#include "event_driven.h"

#include <algorithm>
#include <cmath>

namespace granfric {

// a += b; for vectors elementwise (a grows to b's size)
template <class T>
static void add_into(T &a, const T &b)
{
  a += b;
}
template <class T>
static void add_into(std::vector<T> &a, const std::vector<T> &b)
{
  if (a.size() < b.size()) a.resize(b.size(), T(0));
  for (size_t k = 0; k < b.size(); k++) a[k] += b[k];
}

void EDStats::add(const EDStats &o)
{
  each_sum([](auto &a, const auto &b) { add_into(a, b); }, *this, o);
  max_collisions_one_particle = std::max(max_collisions_one_particle, o.max_collisions_one_particle);
}

namespace {
  // the values of a field appended to the flat array of its kind, or taken from it
  struct Flattener {
    std::vector<long> &counts;
    std::vector<double> &sums;
    void operator()(const long &x) const { counts.push_back(x); }
    void operator()(const double &x) const { sums.push_back(x); }
    void operator()(const std::vector<long> &x) const { counts.insert(counts.end(), x.begin(), x.end()); }
    void operator()(const std::vector<double> &x) const { sums.insert(sums.end(), x.begin(), x.end()); }
  };
  struct Unflattener {
    const long *counts;
    const double *sums;
    void operator()(long &x) { x = *counts++; }
    void operator()(double &x) { x = *sums++; }
    void operator()(std::vector<long> &x) { for (auto &y : x) y = *counts++; }
    void operator()(std::vector<double> &x) { for (auto &y : x) y = *sums++; }
  };
}    // namespace

void EDStats::flatten(std::vector<long> &counts, std::vector<double> &sums) const
{
  counts.clear();
  sums.clear();
  each_sum(Flattener{counts, sums}, *this);
}

void EDStats::unflatten(const long *counts, const double *sums)
{
  Unflattener u{counts, sums};
  each_sum(u, *this);
}

// r_a dP_b into the virial sum (xx, yy, zz, xy, xz, yz)
static void add_virial(double *w, const Vec3 &r, const Vec3 &dP)
{
  w[0] += r.x * dP.x;
  w[1] += r.y * dP.y;
  w[2] += r.z * dP.z;
  w[3] += r.x * dP.y;
  w[4] += r.x * dP.z;
  w[5] += r.y * dP.z;
}

void EDCore::tally(int i, const Vec3 &r, const Vec3 &dP, double t, double dE_tr, double dE_rot,
                        bool wall)
{
  EDParticleTally &p = tallies[ext[i]];
  add_virial(p.virial, r, dP);
  if (wall) {
    p.wall_collisions += 1.0;
    p.dE_wall += dE_tr + dE_rot;
  } else {
    p.collisions += 1.0;
    p.dE_tr += dE_tr;
    p.dE_rot += dE_rot;
  }
  p.t_last = t;
}

// Pair collision of i and j at t, applied already, the pair in its canonical order (i has the
// smaller key): r the contact vector (from j's image to i), n its unit vector, b1 and b2 the
// bodies before, c the law's result, ni and nj their collisions in this window. Tallies of
// both, the history (for domain windows), and, where the collision is booked (where i is
// counted; without an accounting: always), the statistics and the collision log.
void EDCore::record_pair(int i, int j, double t, const Vec3 &r, const Vec3 &n, const Body &b1,
                              const Body &b2, const Collision &c, bool tc_elastic, long ni, long nj)
{
  if (tally_on) {    // (r (x) dP is the same seen from j: -r (x) -dP)
    const Vec3 half = 0.5 * r;
    tally(i, half, c.dP, t, 0.5 * b1.m * (norm2(c.v1) - norm2(b1.v)),
          0.5 * b1.q * b1.m * b1.a * b1.a * (norm2(c.w1) - norm2(b1.w)), false);
    tally(j, half, c.dP, t, 0.5 * b2.m * (norm2(c.v2) - norm2(b2.v)),
          0.5 * b2.q * b2.m * b2.a * b2.a * (norm2(c.w2) - norm2(b2.w)), false);
  }
  if (history && (!record_only || record_only[ext[i]] || record_only[ext[j]]))
    history->push_back({t, ext[i], ext[j], c.v1, c.w1, c.v2, c.w2});
  if (counted(i)) stats.max_collisions_one_particle = std::max(stats.max_collisions_one_particle, ni);
  if (counted(j)) stats.max_collisions_one_particle = std::max(stats.max_collisions_one_particle, nj);
  if (!counted(i)) return;
  stats.collisions++;
  stats.dE += c.dE;
  if (c.sliding) stats.sliding++;
  if (c.energy_created) stats.energy_created++;
  if (tc_elastic) stats.tc_elastic++;
  add_virial(stats.virial, r, c.dP);
  if (collision_log)
    collision_log->push_back({t, ext[i], ext[j], c.gn, c.gt, c.cos_gamma, std::fabs(dot(c.dP, n)), c.dE, c.sliding});
  if (opt.gamma_bins > 0) {
    const int nb = opt.gamma_bins;
    int k = (int) ((c.gamma() - 0.5 * M_PI) / (0.5 * M_PI) * nb);
    stats.gamma_hist[std::min(nb - 1, std::max(0, k))]++;
  }
}

// Collision of particle i with wall k at t, applied already: n the wall's normal, dP the impulse
// on the particle, c the result (c.dE in the lab frame), dE_tr and dE_rot the particle's energy
// changes, ni its collisions in this window. Its tally, the history, and, where the particle is
// counted, the statistics, the wall's own sums and the collision log.
void EDCore::record_wall(int i, int k, double t, const Vec3 &n, const Vec3 &dP,
                              const Collision &c, double dE_tr, double dE_rot, bool tc_elastic, long ni)
{
  const double a = flights[i].a;
  if (tally_on) tally(i, a * n, dP, t, dE_tr, dE_rot, true);
  if (history && (!record_only || record_only[ext[i]]))
    history->push_back({t, ext[i], -1 - k, c.v1, c.w1, Vec3(), Vec3()});
  if (!counted(i)) return;
  const int d = opt.walls[k].dim;
  stats.wall_collisions++;
  stats.dE_wall += c.dE;
  if (c.sliding) stats.sliding++;
  if (c.energy_created) stats.energy_created++;
  if (tc_elastic) stats.tc_elastic++;
  stats.max_collisions_one_particle = std::max(stats.max_collisions_one_particle, ni);
  add_virial(stats.virial, a * n, dP);
  if (collision_log)
    collision_log->push_back({t, ext[i], -1 - k, c.gn, c.gt, c.cos_gamma, std::fabs(dP[d]), c.dE, c.sliding});
  stats.wall_hits[k]++;
  for (int m = 0; m < 3; m++) stats.wall_impulse[3 * k + m] -= dP[m];
  stats.wall_work[k] += dE_tr + dE_rot;
}

}    // namespace granfric
