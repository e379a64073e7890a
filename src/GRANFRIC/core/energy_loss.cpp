// GRANFRIC physics core: Monte Carlo mean energy change per collision (see energy_loss.h).
#include "energy_loss.h"

#include <cmath>
#include <random>

namespace granfric {

EnergyLossResult mean_energy_loss(const LawParams &law, double q, int dim, double T0, long n,
                                  uint64_t seed)
{
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> G(0.0, 1.0);
  std::uniform_real_distribution<double> U(0.0, 2.0 * M_PI);
  const double m = 1.0, a = 0.5, I = q * m * a * a;
  const double sv = std::sqrt(T0 / m), sw = std::sqrt(T0 / I);
  double wsum = 0.0, w2sum = 0.0, sum = 0.0, w2x = 0.0, w2x2 = 0.0, slide = 0.0;
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
    wsum += w;
    w2sum += w * w;
    sum += w * c.dE;
    w2x += w * w * c.dE;
    w2x2 += w * w * c.dE * c.dE;
    if (c.sliding) slide += w;
    used++;
  }
  EnergyLossResult r;
  r.samples = used;
  r.mean = sum / wsum;
  // standard error of the ratio estimator sum w x / sum w: sum w^2 (x - mean)^2 / (sum w)^2
  const double s2 = w2x2 - 2.0 * r.mean * w2x + r.mean * r.mean * w2sum;
  r.stderr_ = std::sqrt(std::max(0.0, s2)) / wsum;
  r.sliding = slide / wsum;
  return r;
}

}    // namespace granfric
