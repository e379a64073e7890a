// GRANFRIC physics core: the exact event-driven loop (see event_driven.h).
#include "event_driven.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace granfric {

void EDStats::add(const EDStats &o)
{
  collisions += o.collisions;
  sliding += o.sliding;
  tc_elastic += o.tc_elastic;
  energy_created += o.energy_created;
  crossings += o.crossings;
  max_collisions_one_particle = std::max(max_collisions_one_particle, o.max_collisions_one_particle);
  dE += o.dE;
  if (gamma_hist.size() < o.gamma_hist.size()) gamma_hist.resize(o.gamma_hist.size(), 0);
  for (size_t k = 0; k < o.gamma_hist.size(); k++) gamma_hist[k] += o.gamma_hist[k];
}

void EventDriven::configure(const EDOptions &o, int nt, const std::vector<LawParams> &table)
{
  if (o.dim != 2 && o.dim != 3) throw std::invalid_argument("dimension must be 2 or 3");
  if ((int) table.size() != (nt + 1) * (nt + 1))
    throw std::invalid_argument("law table must have (ntypes+1)^2 entries");
  opt = o;
  ntypes = nt;
  laws = table;
  L = Vec3(o.hi[0] - o.lo[0], o.hi[1] - o.lo[1], o.hi[2] - o.lo[2]);
  if (o.dim == 2 && o.gravity.z != 0.0)
    throw std::invalid_argument("gravity must lie in the x-y plane in 2d");
  for (int d = 0; d < o.dim; d++)
    if (!o.periodic[d])
      throw std::invalid_argument("non-periodic boundaries need walls (not available yet)");
}

Vec3 EventDriven::position(int i, double t) const
{
  const EDParticle &p = particles[i];
  const double dt = t - p.t;
  return p.x + dt * p.v + (0.5 * dt * dt) * opt.gravity;
}

Vec3 EventDriven::velocity(int i, double t) const
{
  const EDParticle &p = particles[i];
  return p.v + (t - p.t) * opt.gravity;
}

void EventDriven::advance(int i, double t)
{
  EDParticle &p = particles[i];
  if (p.t == t) return;
  const double dt = t - p.t;
  p.x += dt * p.v + (0.5 * dt * dt) * opt.gravity;
  p.v += dt * opt.gravity;
  p.t = t;
}

// ---------------------------------------------------------------- cells

void EventDriven::setup_cells()
{
  double amax = 0.0;
  for (const auto &p : particles) amax = std::max(amax, p.a);
  const double sigma = 2.0 * amax * (1.0 + 1e-10);
  for (int d = 0; d < 3; d++) {
    if (d >= opt.dim) {
      nc[d] = 1;
      cw[d] = L[d] > 0.0 ? L[d] : 1.0;
      continue;
    }
    if (!(L[d] >= sigma))
      throw std::invalid_argument("box length " + std::to_string(L[d]) +
                                  " is smaller than the largest contact distance " +
                                  std::to_string(2.0 * amax));
    nc[d] = sigma > 0.0 ? (int) std::min(std::floor(L[d] / sigma), double(1 << 20)) : 1;
    nc[d] = std::max(1, nc[d]);
    cw[d] = L[d] / nc[d];
  }
  // bound the number of cells by the number of particles (beyond that cells only cost memory)
  const long maxcells = std::max<long>(27, 4L * (long) particles.size());
  while ((long) nc[0] * nc[1] * nc[2] > maxcells) {
    int d = 0;
    for (int k = 1; k < opt.dim; k++)
      if (nc[k] > nc[d]) d = k;
    nc[d] = std::max(1, nc[d] / 2);
    cw[d] = L[d] / nc[d];
  }
  head.assign((size_t) nc[0] * nc[1] * nc[2], -1);
  next.assign(particles.size(), -1);
  prev.assign(particles.size(), -1);
  for (size_t i = 0; i < particles.size(); i++) {
    EDParticle &p = particles[i];
    for (int d = 0; d < 3; d++) {
      if (d >= opt.dim) {
        p.c[d] = 0;
        p.img[d] = 0;
        continue;
      }
      const long u = (long) std::floor((p.x[d] - opt.lo[d]) / cw[d]);
      long img = u >= 0 ? u / nc[d] : -((-u + nc[d] - 1) / nc[d]);
      p.img[d] = (int) img;
      p.c[d] = (int) (u - img * nc[d]);
    }
    cell_insert((int) i);
  }
}

void EventDriven::cell_insert(int i)
{
  EDParticle &p = particles[i];
  p.cell = (p.c[2] * nc[1] + p.c[1]) * nc[0] + p.c[0];
  const int h = head[p.cell];
  next[i] = h;
  prev[i] = -1;
  if (h >= 0) prev[h] = i;
  head[p.cell] = i;
}

void EventDriven::cell_remove(int i)
{
  const int c = particles[i].cell;
  if (prev[i] >= 0)
    next[prev[i]] = next[i];
  else
    head[c] = next[i];
  if (next[i] >= 0) prev[next[i]] = prev[i];
}

// ---------------------------------------------------------------- prediction

void EventDriven::predict(int i)
{
  EDParticle &p = particles[i];
  p.et = NEVER;
  p.ekind = NONE;

  // next cell crossing
  const Vec3 xi = position(i, now), vi = velocity(i, now);
  for (int d = 0; d < opt.dim; d++) {
    const double blo = opt.lo[d] + ((double) p.c[d] + (double) p.img[d] * nc[d]) * cw[d];
    const double bhi = opt.lo[d] + ((double) p.c[d] + 1.0 + (double) p.img[d] * nc[d]) * cw[d];
    const double tup = crossing_time(xi[d], vi[d], opt.gravity[d], bhi, +1);
    const double tdn = crossing_time(xi[d], vi[d], opt.gravity[d], blo, -1);
    if (now + tup < p.et) {
      p.et = now + tup;
      p.ekind = CROSSING;
      p.epartner = d;
      p.ecount = 1;
    }
    if (now + tdn < p.et) {
      p.et = now + tdn;
      p.ekind = CROSSING;
      p.epartner = d;
      p.ecount = 0;
    }
  }

  // collisions with particles in the neighbouring cells (periodic images by offsets)
  const int zr = opt.dim == 3 ? 1 : 0;
  for (int dz = -zr; dz <= zr; dz++) {
    int uz = p.c[2] + dz, kz = 0;
    if (uz < 0) { uz += nc[2]; kz = -1; } else if (uz >= nc[2]) { uz -= nc[2]; kz = 1; }
    for (int dy = -1; dy <= 1; dy++) {
      int uy = p.c[1] + dy, ky = 0;
      if (uy < 0) { uy += nc[1]; ky = -1; } else if (uy >= nc[1]) { uy -= nc[1]; ky = 1; }
      for (int dx = -1; dx <= 1; dx++) {
        int ux = p.c[0] + dx, kx = 0;
        if (ux < 0) { ux += nc[0]; kx = -1; } else if (ux >= nc[0]) { ux -= nc[0]; kx = 1; }
        const int cell = (uz * nc[1] + uy) * nc[0] + ux;
        for (int j = head[cell]; j >= 0; j = next[j]) {
          if (j == i) continue;
          const EDParticle &q = particles[j];
          const int off[3] = {p.img[0] + kx - q.img[0], p.img[1] + ky - q.img[1],
                              p.img[2] + kz - q.img[2]};
          // two particles whose last collisions were with each other (same periodic image)
          // separate in free flight: relative motion is a straight line
          if (p.last_partner == j && q.last_partner == i && off[0] == p.last_off[0] &&
              off[1] == p.last_off[1] && off[2] == p.last_off[2])
            continue;
          const Vec3 shift(off[0] * L.x, off[1] * L.y, off[2] * L.z);
          const double dtj = now - q.t;
          const Vec3 xj = q.x + dtj * q.v + (0.5 * dtj * dtj) * opt.gravity + shift;
          const Vec3 vj = q.v + dtj * opt.gravity;
          const double tau = pair_contact_time(xi - xj, vi - vj, p.a + q.a);
          if (now + tau < p.et) {
            p.et = now + tau;
            p.ekind = COLLISION;
            p.epartner = j;
            p.ecount = q.ncoll;
            for (int d = 0; d < 3; d++) p.eoff[d] = off[d];
          }
        }
      }
    }
  }
}

// ---------------------------------------------------------------- events

void EventDriven::collide_pair(int i)
{
  EDParticle &p = particles[i];
  const int j = p.epartner;
  EDParticle &q = particles[j];
  const double t = p.et;
  advance(i, t);
  advance(j, t);
  const Vec3 r = p.x - q.x - Vec3(p.eoff[0] * L.x, p.eoff[1] * L.y, p.eoff[2] * L.z);
  const Vec3 n = (1.0 / norm(r)) * r;

  LawParams law = laws[p.type * (ntypes + 1) + q.type];
  // (a last collision 'in the future' after a clock reset does not count)
  const double since_p = t - p.t_last, since_q = t - q.t_last;
  if (opt.tc > 0.0 && ((since_p >= 0.0 && since_p < opt.tc) || (since_q >= 0.0 && since_q < opt.tc))) {
    law = law.elastic();
    stats.tc_elastic++;
  }
  Body b1{p.v, p.w, p.m, p.a, p.q}, b2{q.v, q.w, q.m, q.a, q.q};
  const Collision c = collide(law, b1, b2, n);
  p.v = c.v1;
  p.w = c.w1;
  q.v = c.v2;
  q.w = c.w2;
  p.t_last = q.t_last = t;
  p.ncoll++;
  q.ncoll++;
  p.last_partner = j;
  q.last_partner = i;
  for (int d = 0; d < 3; d++) {
    p.last_off[d] = p.eoff[d];
    q.last_off[d] = -p.eoff[d];
  }
  stats.collisions++;
  stats.dE += c.dE;
  if (c.sliding) stats.sliding++;
  if (c.energy_created) stats.energy_created++;
  if (opt.gamma_bins > 0) {
    const int nb = opt.gamma_bins;
    int k = (int) ((c.gamma() - 0.5 * M_PI) / (0.5 * M_PI) * nb);
    stats.gamma_hist[std::min(nb - 1, std::max(0, k))]++;
  }
  const long ni = ++p.ncollisions, nj = ++q.ncollisions;
  stats.max_collisions_one_particle = std::max(stats.max_collisions_one_particle, std::max(ni, nj));
  if (ni > opt.max_collisions || nj > opt.max_collisions) {
    std::ostringstream s;
    s << "particles " << i << " and " << j << " collided " << std::max(ni, nj)
      << " times within one window (cap " << opt.max_collisions
      << "): inelastic collapse; use the TC model (tc) or a larger cap";
    throw EventCapError(s.str(), ni >= nj ? i : j, ni >= nj ? j : i, t, std::max(ni, nj));
  }
  predict(i);
  heap_update(i);
  predict(j);
  heap_update(j);
}

void EventDriven::cross(int i)
{
  EDParticle &p = particles[i];
  const int d = p.epartner;
  advance(i, p.et);
  cell_remove(i);
  if (p.ecount) {
    if (++p.c[d] == nc[d]) {
      p.c[d] = 0;
      p.img[d]++;
    }
  } else {
    if (--p.c[d] < 0) {
      p.c[d] = nc[d] - 1;
      p.img[d]--;
    }
  }
  cell_insert(i);
  stats.crossings++;
  predict(i);
  heap_update(i);
}

void EventDriven::start()
{
  now = 0.0;
  const int n = (int) particles.size();
  for (auto &p : particles) {
    p.t = 0.0;
    p.ncoll = 0;
    p.last_partner = -1;
    p.ncollisions = 0;
    if (opt.dim == 2) {
      p.v.z = 0.0;
      p.w.x = p.w.y = 0.0;
    }
  }
  setup_cells();
  heap.resize(n);
  hpos.resize(n);
  for (int i = 0; i < n; i++) {
    predict(i);
    heap[i] = i;
    hpos[i] = i;
  }
  for (int k = n / 2 - 1; k >= 0; k--) heap_down(k);
}

EDStats EventDriven::advance_to(double t_end)
{
  stats = EDStats();
  stats.gamma_hist.assign(std::max(0, opt.gamma_bins), 0);
  for (auto &p : particles) p.ncollisions = 0;
  const int n = (int) particles.size();
  while (n > 0) {
    const int i = heap[0];
    EDParticle &p = particles[i];
    if (!(p.et < t_end)) break;
    now = p.et;
    if (p.ekind == COLLISION) {
      if (particles[p.epartner].ncoll != p.ecount) {
        predict(i);    // the partner changed course: stale prediction
        heap_update(i);
      } else {
        collide_pair(i);
      }
    } else if (p.ekind == CROSSING) {
      cross(i);
    } else {
      break;
    }
  }
  now = t_end;
  return stats;
}

void EventDriven::rebase(double dt)
{
  // the same shift for every time keeps the heap ordered (rounding is monotone)
  for (auto &p : particles) {
    p.t -= dt;
    p.et -= dt;
    p.t_last -= dt;
  }
  now -= dt;
}

EDStats EventDriven::run(double t_end)
{
  start();
  const EDStats s = advance_to(t_end);
  for (int i = 0; i < (int) particles.size(); i++) advance(i, t_end);
  return s;
}

// ---------------------------------------------------------------- heap

bool EventDriven::before(int i, int j) const
{
  const double a = particles[i].et, b = particles[j].et;
  return a < b || (a == b && i < j);
}

void EventDriven::heap_up(int k)
{
  const int i = heap[k];
  while (k > 0) {
    const int parent = (k - 1) / 2;
    if (!before(i, heap[parent])) break;
    heap[k] = heap[parent];
    hpos[heap[k]] = k;
    k = parent;
  }
  heap[k] = i;
  hpos[i] = k;
}

void EventDriven::heap_down(int k)
{
  const int n = (int) heap.size();
  const int i = heap[k];
  while (true) {
    int child = 2 * k + 1;
    if (child >= n) break;
    if (child + 1 < n && before(heap[child + 1], heap[child])) child++;
    if (!before(heap[child], i)) break;
    heap[k] = heap[child];
    hpos[heap[k]] = k;
    k = child;
  }
  heap[k] = i;
  hpos[i] = k;
}

void EventDriven::heap_update(int i)
{
  const int k = hpos[i];
  heap_up(k);
  heap_down(hpos[i]);
}

}    // namespace granfric
