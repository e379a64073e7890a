// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the cell grid (see event_driven.h): cell width, placing particles, cell lists,
// storage in cell order, and the cell-crossing events that keep the grid exact.
#include "event_driven.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <sstream>

namespace granfric {

// Renumber the particles in cell order, so that neighbours sit close in memory (the cost of a
// collision then stays flat with N). Partner references, cell lists and the queue follow; the
// external numbering (ext / loc) does not change. Deterministic: a stable sort by cell.
void EDCore::reorder()
{
  const std::vector<int> order = cell_order();
  std::vector<double> times(order.size());    // event times in the new numbering
  for (size_t k = 0; k < order.size(); k++) times[k] = queue.time(order[k]);
  renumber(order);
  queue.build(times);
}

// particles by cell (stable: by index within a cell)
std::vector<int> EDCore::cell_order() const
{
  const int n = (int) flights.size();
  const int ncell = (int) head.size();
  // (empty slots after every cell)
  auto bin = [&](int i) { return schedules[i].gone ? ncell : cell_of(i); };
  std::vector<int> count(ncell + 2, 0), order(n);
  for (int i = 0; i < n; i++) count[bin(i) + 1]++;
  for (int c = 0; c <= ncell; c++) count[c + 1] += count[c];
  for (int i = 0; i < n; i++) order[count[bin(i)]++] = i;
  return order;
}

// v in the new order (v[order[k]] becomes element k, then fix(element)), in place: each cycle
// of the permutation is followed once (element k takes the one at order[k], the first of the
// cycle kept aside), so that a renumbering needs no second copy of the particles' records
// (in a large system that copy would be the peak of the whole run's memory)
template <class V, class F>
static void permute(V &v, const std::vector<int> &order, F &&fix)
{
  const size_t n = order.size();
  std::vector<bool> placed(n, false);
  for (size_t s = 0; s < n; s++) {
    if (placed[s]) continue;
    const auto first = v[s];
    size_t k = s;
    for (;;) {
      placed[k] = true;
      const size_t o = (size_t) order[k];
      if (o == s) {
        v[k] = first;
        fix(v[k]);
        break;
      }
      v[k] = v[o];
      fix(v[k]);
      k = o;
    }
  }
}

// new internal index k for the particle order[k]: records, partner references, index maps and
// cell lists follow (the queue is the caller's)
void EDCore::renumber(const std::vector<int> &order)
{
  const int n = (int) flights.size();
  std::vector<int> newloc(n);
  for (int k = 0; k < n; k++) newloc[order[k]] = k;
  auto same = [](auto &) {};
  {
    permute(flights, order, same);
    permute(colliders, order, [&](Collider &c) {
      if (c.last_partner >= 0) c.last_partner = newloc[c.last_partner];
    });
    permute(schedules, order, [&](Schedule &s) {
      if (s.cpartner >= 0) s.cpartner = newloc[s.cpartner];
    });
    permute(images, order, same);
    permute(ext, order, same);
    if (!wall_times.empty()) permute(wall_times, order, same);
    if (!last_collision.empty()) permute(last_collision, order, same);
    if (!frames.empty()) permute(frames, order, same);
    if (lists) {
      permute(list_centres, order, same);
      permute(list_counts, order, same);
      // (the lists through a second copy: lists are for systems small enough to afford it)
      big_vector<ListEntry> B((size_t) n * LCAP);
      for (int k = 0; k < n; k++) {
        const ListEntry *e = &list_entries[(size_t) order[k] * LCAP];
        ListEntry *f = &B[(size_t) k * LCAP];
        for (int m = 0; m < list_counts[k]; m++) {
          f[m] = e[m];
          f[m].j = newloc[e[m].j];
        }
      }
      list_entries.swap(B);
    }
  }
  for (int k = 0; k < n; k++) loc[ext[k]] = k;
  std::fill(head.begin(), head.end(), -1);
  for (int i = n - 1; i >= 0; i--)
    if (!schedules[i].gone) cell_insert(i);
  crossings_since_reorder = 0;
}

// Cell width: at least the largest contact distance sigma. In 2d a dilute system gets wider
// cells: a particle then crosses fewer cells per free path, for a few more candidates per scan;
// w = 0.52 sigma (n sigma^2)^(-2/3) balances the two (the fit of bench/cell_width.sh), i.e. sigma
// from area fraction 0.3 up, 3.3 sigma at 0.05. In 3d a wider cell adds candidates in three
// dimensions for the crossings it saves, so the cells are as narrow as they may be.
double EDCore::auto_cell_width(int dim, double sigma, double n)
{
  if (dim != 2 || !(sigma > 0.0) || !(n > 0.0)) return sigma;
  return std::max(sigma, 0.52 * sigma * std::pow(n * sigma * sigma, -2.0 / 3.0));
}

void EDCore::setup_cells()
{
  double amax = 0.0;
  long present = 0;
  for (size_t i = 0; i < flights.size(); i++)
    if (!schedules[i].gone) {
      amax = std::max(amax, flights[i].a);
      present++;
    }
  const double sigma = 2.0 * amax * (1.0 + 1e-10);
  double width = sigma;
  if (lists) {
    width = std::max(std::sqrt(lrad2), opt.cell_width);    // (cells only build the lists)
  } else if (opt.cell_width > 0.0) {
    width = std::max(sigma, opt.cell_width);
  } else if (opt.dim == 2 && L[0] * L[1] > 0.0) {
    width = auto_cell_width(2, sigma, present / (L[0] * L[1]));
  }
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
    // (cell coordinates are 16-bit: a longer box gets wider cells)
    nc[d] = sigma > 0.0 ? (int) std::min(std::floor(L[d] / width), 32767.0) : 1;
    nc[d] = std::max(1, nc[d]);
    cw[d] = L[d] / nc[d];
  }
  // bound the number of cells by the number of particles (beyond that cells only cost memory
  // and empty cells for the scans to pass; up to 8 per particle in 3d, so that a dilute gas keeps
  // its narrow cells, see auto_cell_width)
  const long maxcells = std::max<long>(27, (opt.dim == 3 ? 8L : 4L) * (long) flights.size());
  while ((long) nc[0] * nc[1] * nc[2] > maxcells) {
    int d = 0;
    for (int k = 1; k < opt.dim; k++)
      if (nc[k] > nc[d]) d = k;
    nc[d] = std::max(1, nc[d] / 2);
    cw[d] = L[d] / nc[d];
  }
  // (Lees-Edwards: the top and the bottom row must be different rows, each next to one face)
  if (opt.shear && nc[1] < 3 && L[1] >= 3.0 * sigma) {
    nc[1] = 3;
    cw[1] = L[1] / 3;
  }
  if (opt.shear && nc[1] < 3)
    throw std::invalid_argument("shear (Lees-Edwards) needs a box at least 3 cells (3 times the largest "
                                "contact distance) long in y; it is " + std::to_string(L[1]));
  for (int d = 0; d < 3; d++) {
    kcells[d] = opt.periodic[d] ? (double) nc[d] : 0.0;
    kper[d] = opt.periodic[d] ? 0.0 : P[d];
  }
  if (opt.shear) shear_bands();
  head.assign((size_t) nc[0] * nc[1] * nc[2], -1);
  for (auto &m : images) m.next = -1;
  cell_amax = amax;
  for (size_t i = 0; i < flights.size(); i++) {
    if (schedules[i].gone) continue;
    place((int) i);
    cell_insert((int) i);
  }
}

void EDCore::place(int i)
{
  Vec3 x = pos(i, now);    // (with lists: the new list centre)
  Schedule &s = schedules[i];
  if (opt.shear) {
    // (Lees-Edwards: the image k1 periods up in y lies k1 s further in x, and the row of cells
    // c1 is shifted by its band's b D: its x cell is that of the position less both)
    int c, k;
    locate(1, x[1], c, k);
    x.x -= k * shift_at(now) + row_shift(c, now);
  }
  for (int d = 0; d < 3; d++) {
    if (d >= opt.dim) {
      s.c[d] = 0;
      images[i].k[d] = 0;
      continue;
    }
    int c, k;
    // (a frame shift f: the grid sees the particle at x + f P, its image is -f)
    const int f = framed ? frames[i].f[d] : 0;
    locate(d, f ? x[d] + f * P[d] : x[d], c, k);
    images[i].k[d] = f ? -f : k;
    s.c[d] = (int16_t) c;
  }
  if (lists) {
    const int *k = images[i].k;
    list_centres[i] = x - periods(k[0], k[1], k[2]);
  }
}

// Lees-Edwards: a particle's x position and velocity as its x cell sees them (x0, v0 given as
// they are): less the shift and the shear rate of its image in y, and less those of its band of
// rows
inline __attribute__((always_inline)) void EDCore::sheared_frame(int i, double &x0, double &v0) const
{
  const int k = images[i].k[1], r = schedules[i].c[1];
  x0 -= k * shift_at(now) + row_shift(r, now);    // (as place() and cross() take it)
  v0 -= image_speed(k) + row_speed(r);
}

// cell c (0 .. nc-1) and periodic image k of coordinate xd in dimension d
void EDCore::locate(int d, double xd, int &c, int &k) const
{
  long u = (long) std::floor((xd - opt.lo[d]) / cw[d]);
  if (!opt.periodic[d]) u = std::min<long>(std::max<long>(u, 0), nc[d] - 1);    // edge cells extend outward
  const long kk = u >= 0 ? u / nc[d] : -((-u + nc[d] - 1) / nc[d]);
  k = (int) kk;
  c = (int) (u - kk * nc[d]);
}

// The neighbouring cells of i's cell (3^dim of them, fewer at non-periodic edges) as cell
// indices and the image shifts k (-1, 0, 1 per dimension) at which they are reached; returns
// how many (a sheared box: sheared_spans)
int EDCore::around(int i, int cell[AROUND], int8_t shift[AROUND][3]) const
{
  const int16_t *c = schedules[i].c;
  int n = 0;
  if (opt.dim == 3 && c[0] >= 1 && c[0] + 1 < nc[0] && c[1] >= 1 && c[1] + 1 < nc[1] && c[2] >= 1 &&
      c[2] + 1 < nc[2]) {    // (the usual case: no wrapping, no edge)
    const int base = (c[2] * nc[1] + c[1]) * nc[0] + c[0];
    std::memset(shift, 0, 27 * sizeof shift[0]);
    for (int dz = -1; dz <= 1; dz++)
      for (int dy = -1; dy <= 1; dy++) {
        const int row = base + (dz * nc[1] + dy) * nc[0];
        cell[n] = row - 1, cell[n + 1] = row, cell[n + 2] = row + 1;
        n += 3;
      }
    return n;
  }
  // per dimension: the cell coordinates reached (up to 3), their image shifts
  int u[3][3], k[3][3], m[3] = {1, 1, 1};
  for (int d = 0; d < 3; d++) {
    u[d][0] = c[d], k[d][0] = 0;
    if (d >= opt.dim) continue;
    m[d] = 0;
    for (int e = -1; e <= 1; e++) {
      int v = c[d] + e, kk = 0;
      if (v < 0 || v >= nc[d]) {
        if (!opt.periodic[d]) continue;
        kk = v < 0 ? -1 : 1;
        v -= kk * nc[d];
      }
      u[d][m[d]] = v, k[d][m[d]] = kk;
      m[d]++;
    }
  }
  for (int z = 0; z < m[2]; z++)
    for (int y = 0; y < m[1]; y++)
      for (int x = 0; x < m[0]; x++) {
        cell[n] = (u[2][z] * nc[1] + u[1][y]) * nc[0] + u[0][x];
        shift[n][0] = (int8_t) k[0][x], shift[n][1] = (int8_t) k[1][y], shift[n][2] = (int8_t) k[2][z];
        n++;
      }
  return n;
}

void EDCore::cell_insert(int i)
{
  const int c = cell_of(i);
  images[i].next = head[c];
  head[c] = i;
}

// singly linked cell lists: a cell holds about one particle, so finding i's predecessor costs
// less than keeping a back link (4 bytes per particle) up to date
void EDCore::cell_remove(int i)
{
  int *link = &head[cell_of(i)];
  while (*link != i) {
    if (*link < 0) throw std::logic_error("EventDriven: a particle is missing from its cell list");
    link = &images[*link].next;
  }
  *link = images[i].next;
}

template <bool SHEARED>
inline __attribute__((always_inline)) void EDCore::predict_crossing_in(int i, const Vec3 &xi, const Vec3 &vi)
{
  if (opt.dim == 2) {
    if (has_gravity)
      predict_crossing_t<2, true, SHEARED>(i, xi, vi);
    else
      predict_crossing_t<2, false, SHEARED>(i, xi, vi);
  } else {
    if (has_gravity)
      predict_crossing_t<3, true, SHEARED>(i, xi, vi);
    else
      predict_crossing_t<3, false, SHEARED>(i, xi, vi);
  }
}

void EDCore::predict_crossing(int i, const Vec3 &xi, const Vec3 &vi)
{
  if (opt.shear)
    predict_crossing_in<true>(i, xi, vi);
  else
    predict_crossing_in<false>(i, xi, vi);
}

// the dimension, whether there is gravity at all and whether the box is sheared known at
// compile time (SHEARED: x as its sheared row of cells sees it)
template <int DIM, bool GRAV, bool SHEARED>
void EDCore::predict_crossing_t(int i, const Vec3 &xi, const Vec3 &vi)
{
  Schedule &p = schedules[i];
  const int *k = images[i].k;
  double xs = 0.0, vs = 0.0;
  if (SHEARED) xs = xi.x, vs = vi.x, sheared_frame(i, xs, vs);
  double xt = NEVER;
  int xdim = 0, xdir = 0;
  auto offer = [&](double t, int d, int dir) {    // (selections by masks, not branches)
    const int e = -(int) (t < xt);
    xt = t < xt ? t : xt;
    xdim = (d & e) | (xdim & ~e);
    xdir = (dir & e) | (xdir & ~e);
  };
  // the lower boundary of cell c + u in the particle's frame (k: its image, in a non-periodic
  // dimension minus its frame shift): lo + (c + u + k nc) cw in a periodic dimension, and
  // lo + (c + u) cw + k P in another (one expression for both, no branch)
  auto bound = [&](int d, double u) {
    return opt.lo[d] + ((double) p.c[d] + u + (double) k[d] * kcells[d]) * cw[d] +
        (double) k[d] * kper[d];
  };
  for (int d = 0; d < DIM; d++) {
    const double v = SHEARED && d == 0 ? vs : vi[d], x = SHEARED && d == 0 ? xs : xi[d];
    const bool top = !opt.periodic[d] && p.c[d] == nc[d] - 1;    // no boundary beyond an edge cell
    const bool bottom = !opt.periodic[d] && p.c[d] == 0;
    if (!GRAV || opt.gravity[d] == 0.0) {
      // straight flight: only the boundary ahead can be reached (whether it lies up or down
      // is a coin toss: selected, not branched on; at v = 0 the time is computed and dropped)
      const int up = v > 0.0, ahead = (up & !top) | ((v < 0.0) & !bottom);
      const double dt = (bound(d, (double) up) - x) / v;
      const double t[2] = {NEVER, now + (dt > 0.0 ? dt : 0.0)};
      offer(t[ahead], d, 2 * up - 1);
      continue;
    }
    const double blo = bound(d, 0.0), bhi = bound(d, 1.0);
    offer(top ? NEVER : now + crossing_time(x, v, opt.gravity[d], bhi, +1), d, 1);
    offer(bottom ? NEVER : now + crossing_time(x, v, opt.gravity[d], blo, -1), d, -1);
  }
  p.xt = xt;
  if (xt < NEVER) p.xdim = (int8_t) xdim, p.xdir = (int8_t) xdir;
  if (far) queue.prefetch_time(xt);
}

// one more crossing (or list rebuild) of particle i in this window, within the cap
void EDCore::count_crossing(int i)
{
  if (++window_crossings <= crossing_cap) return;
  const double speed = norm(vel(i, now));
  std::ostringstream s;
  s << "cell crossings in one window exceed the cap (" << crossing_cap
    << " = the crossing cap per particle times the number of particles); particle " << ext[i]
    << " was crossing at speed " << speed;
  throw EventCapError(s.str(), ext[i], ext[i], now, window_crossings, EventCapError::CROSSINGS, speed);
}

void EDCore::cross(int i)
{
  if (lists) {
    list_rebuild(i);
    return;
  }
  count_crossing(i);
  Schedule &p = schedules[i];
  const int d = p.xdim, dir = p.xdir;
  // (Lees-Edwards: through a band boundary into another band, which is shifted in x, or
  // through a y face into an image shifted in x: there the x cell is found afresh; the rows next
  // to the particle are compared before and after. Into another row of the particle's band, whose
  // rows lie over each other, none of that: as in an unsheared box.)
  const bool row_change = opt.shear && d == 1 && boundary_sheared(p.c[1], dir);
  RowSpan before[9];
  const int nbefore = row_change ? sheared_spans(i, before) : 0;
  const int band = row_change ? row_band[p.c[1]] : 0, k1 = images[i].k[1];
  cell_remove(i);
  p.c[d] += dir;
  if (p.c[d] == nc[d]) {
    p.c[d] = 0;
    images[i].k[d]++;
  } else if (p.c[d] < 0) {
    p.c[d] = nc[d] - 1;
    images[i].k[d]--;
  }
  if (row_change && (row_band[p.c[1]] != band || images[i].k[1] != k1)) {
    int c, k;
    locate(0, pos(i, now).x - (images[i].k[1] * shift_at(now) + row_shift(p.c[1], now)), c, k);
    p.c[0] = (int16_t) c;
    images[i].k[0] = k;
  }
  cell_insert(i);
  stats.crossings++;
  crossings_since_reorder++;
  const Vec3 xi = pos(i, now), vi = vel(i, now);    // (the stored state is not re-rounded)
  predict_crossing(i, xi, vi);
  if (p.ct < NEVER && stale(p)) {
    // the stored collision candidate went stale: look at every neighbouring cell
    p.ct = NEVER;
    p.cpartner = -1;
    scan_full(i);
  } else if (row_change) {
    scan_new_spans(i, before, nbefore);
  } else {
    // trajectory unchanged: only the layer of cells that just became adjacent is new
    const int zr = opt.dim == 3 ? 1 : 0;
    int dlo[3] = {-1, -1, -zr}, dhi[3] = {1, 1, zr};
    dlo[d] = dhi[d] = dir;
    if (nc[d] < 3) dlo[d] = -1, dhi[d] = 1;    // with fewer than 3 cells every cell is new
    scan(i, dlo, dhi);
  }
  reschedule(i);
}

}    // namespace granfric
