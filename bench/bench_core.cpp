// GRANFRIC benchmark of the event-driven core alone (no LAMMPS): collisions per second per core
// for 2D discs / 3D spheres at a given fraction and N, windows of dt mean free times, memory per
// particle. Prints its figures; it is not a test.
//   bench_core [dim] [N] [fraction] [dt_in_mean_free_times] [collisions_per_particle]
//              [cell width in diameters, 0: the core's automatic choice]
#include "core/event_driven.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

using namespace granfric;

int main(int argc, char **argv)
{
  const int dim = argc > 1 ? atoi(argv[1]) : 2;
  const long N = argc > 2 ? atol(argv[2]) : 10000;
  const double phi = argc > 3 ? atof(argv[3]) : 0.3;
  const double dt_mft = argc > 4 ? atof(argv[4]) : 1.0;
  const double cpp = argc > 5 ? atof(argv[5]) : 20.0;
  const double cell = argc > 6 ? atof(argv[6]) : 0.0;

  // lattice start, equal particles of diameter 1 and mass 1, Maxwellian velocities, T = 1
  const double a = 0.5;
  const double vol1 = dim == 2 ? M_PI * a * a : 4.0 / 3.0 * M_PI * a * a * a;
  const double side = std::pow(N * vol1 / phi, 1.0 / dim);
  const int m = (int) std::ceil(std::pow((double) N, 1.0 / dim) - 1e-9);
  const double h = side / m;
  EDOptions o;
  o.dim = dim;
  o.cell_width = cell;    // (diameter 1)
  for (int d = 0; d < 3; d++) {
    o.lo[d] = 0.0;
    o.hi[d] = (d < dim) ? side : 1.0;
  }
  EventDriven ed;
  o.shape.assign(2, dim == 2 ? 0.5 : 0.4);
  ed.configure(o, 1, std::vector<LawParams>(4, LawParams::rough(1.0, -1.0)));
  ed.resize((int) N);
  std::mt19937_64 gen(1);
  std::normal_distribution<double> G(0, 1);
  for (long i = 0; i < N; i++) {
    auto p = ed.particle((int) i);
    const long ix = i % m, iy = (i / m) % m, iz = i / ((long) m * m);
    p.x = Vec3((ix + 0.5) * h, (iy + 0.5) * h, dim == 3 ? (iz + 0.5) * h : 0.5);
    p.v = Vec3(G(gen), G(gen), dim == 3 ? G(gen) : 0.0);
    p.a = a;
    p.m = 1.0;
  }
  // Enskog mean free time at T = 1 (2D Henderson, 3D Carnahan-Starling)
  const double n = N / std::pow(side, dim);
  const double g = dim == 2 ? (1 - 7 * phi / 16) / ((1 - phi) * (1 - phi))
                            : (1 - phi / 2) / std::pow(1 - phi, 3);
  const double nu = dim == 2 ? 2 * n * g * std::sqrt(M_PI) : 4 * n * g * std::sqrt(M_PI);
  const double mft = 1.0 / nu, dt = dt_mft * mft;

  // equilibrate 5 collisions per particle (randomises the lattice), then measure
  ed.start();
  double t = 0;
  long coll = 0;
  while (coll < 5 * N / 2) {
    coll += ed.advance_to(dt).collisions;
    ed.rebase(dt);
  }
  EDStats s;
  const auto t0 = std::chrono::steady_clock::now();
  long windows = 0;
  while (s.collisions < (long) (cpp * N / 2)) {
    s.add(ed.advance_to(dt));
    ed.rebase(dt);
    t += dt;
    windows++;
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double bytes = (double) ed.memory_bytes() / N;
  std::printf("dim %d N %ld fraction %.3f dt %.3g mft | cells %.3g wide | collisions %ld "
              "crossings/collision %.3f windows %ld | %.4g s | %.4g collisions/s | core memory %.0f "
              "B/particle\n",
              dim, N, phi, dt_mft, ed.cell_size(), s.collisions, (double) s.crossings / s.collisions,
              windows, secs, s.collisions / secs, bytes);
  return 0;
}
