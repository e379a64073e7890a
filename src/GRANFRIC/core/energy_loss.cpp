// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: Monte Carlo mean energy change per collision (see energy_loss.h).
#include "energy_loss.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace granfric {

namespace {
// weighted mean sum w x / sum w and its standard error sqrt(sum w^2 (x - mean)^2) / sum w
struct WeightedMean {
  double w = 0.0, w2 = 0.0, wx = 0.0, w2x = 0.0, w2x2 = 0.0;
  void add(double weight, double x)
  {
    w += weight;
    w2 += weight * weight;
    wx += weight * x;
    w2x += weight * weight * x;
    w2x2 += weight * weight * x * x;
  }
  double mean() const { return wx / w; }
  double stderr_() const
  {
    const double m = mean();
    return std::sqrt(std::max(0.0, w2x2 - 2.0 * m * w2x + m * m * w2)) / w;
  }
};
}    // namespace

EnergyLossResult mean_energy_changes(const LawParams &law, double q, int dim, double Ttr,
                                     double Trot, long n, uint64_t seed)
{
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> G(0.0, 1.0);
  std::uniform_real_distribution<double> U(0.0, 2.0 * M_PI);
  const double m = 1.0, a = 0.5, I = q * m * a * a;
  const double sv = std::sqrt(Ttr / m), sw = std::sqrt(Trot / I);
  WeightedMean tot, tr, rot;
  double slide = 0.0;
  long used = 0;
  while (used < n) {
    Body b1, b2;
    b1.m = b2.m = m;
    b1.a = b2.a = a;
    b1.q = b2.q = q;
    b1.v = sv * Vec3(G(gen), G(gen), dim == 3 ? G(gen) : 0.0);
    b2.v = sv * Vec3(G(gen), G(gen), dim == 3 ? G(gen) : 0.0);
    if (dim == 2) {
      b1.w = Vec3(0.0, 0.0, sw * G(gen));
      b2.w = Vec3(0.0, 0.0, sw * G(gen));
    } else {
      b1.w = sw * Vec3(G(gen), G(gen), G(gen));
      b2.w = sw * Vec3(G(gen), G(gen), G(gen));
    }
    Vec3 nrm;
    if (dim == 2) {
      const double th = U(gen);
      nrm = Vec3(std::cos(th), std::sin(th), 0.0);
    } else {
      nrm = Vec3(G(gen), G(gen), G(gen));
      nrm = (1.0 / norm(nrm)) * nrm;
    }
    const double gn = dot(b1.v - b2.v, nrm);
    if (gn >= 0.0) continue;    // not approaching: no collision
    const Collision c = collide(law, b1, b2, nrm);
    const double w = -gn;       // collision rate is proportional to the normal relative speed
    const double dEtr = 0.5 * m * (norm2(c.v1) + norm2(c.v2) - norm2(b1.v) - norm2(b2.v));
    const double dErot = 0.5 * I * (norm2(c.w1) + norm2(c.w2) - norm2(b1.w) - norm2(b2.w));
    tot.add(w, c.dE);
    tr.add(w, dEtr);
    rot.add(w, dErot);
    if (c.sliding) slide += w;
    used++;
  }
  EnergyLossResult r;
  r.samples = used;
  r.mean = tot.mean();
  r.stderr_ = tot.stderr_();
  r.mean_tr = tr.mean();
  r.stderr_tr = tr.stderr_();
  r.mean_rot = rot.mean();
  r.stderr_rot = rot.stderr_();
  r.sliding = slide / tot.w;
  return r;
}

}    // namespace granfric
