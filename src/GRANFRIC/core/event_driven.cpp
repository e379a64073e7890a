// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the exact event-driven loop (see event_driven.h).
#include "event_driven.h"

#include "counter_rng.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

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

// the shape factor of every type (index 0 unused): the options', or 0.4 (solid spheres)
static std::vector<double> shape_table(const EDOptions &o, int nt)
{
  return o.shape.empty() ? std::vector<double>(nt + 1, 0.4) : o.shape;
}

void EventDriven::configure(const EDOptions &o, int nt, const std::vector<LawParams> &table)
{
  if (o.dim != 2 && o.dim != 3) throw std::invalid_argument("dimension must be 2 or 3");
  if ((int) table.size() != (nt + 1) * (nt + 1))
    throw std::invalid_argument("law table must have (ntypes+1)^2 entries");
  if (nt > 32767) throw std::invalid_argument("at most 32767 particle types");
  opt = o;
  // the last collision times exist only with the TC model
  if (o.tc > 0.0 && TL.size() != H.size()) TL.assign(H.size(), -INF);
  if (!(o.tc > 0.0)) TL.clear();
  has_gravity = norm2(o.gravity) != 0.0;
  if (!o.shape.empty() && (int) o.shape.size() != nt + 1)
    throw std::invalid_argument("shape table must have ntypes+1 entries");
  for (int k = 1; k < (int) o.shape.size(); k++)
    if (!(o.shape[k] > 0.0 && o.shape[k] <= 1.0))
      throw std::invalid_argument("shape factor I/(m a^2) must be in (0, 1]");
  ntypes = nt;
  laws = table;
  qt = shape_table(o, nt);
  L = Vec3(o.hi[0] - o.lo[0], o.hi[1] - o.lo[1], o.hi[2] - o.lo[2]);
  if (o.dim == 2 && o.gravity.z != 0.0)
    throw std::invalid_argument("gravity must lie in the x-y plane in 2d");
  bool walled[3] = {false, false, false};
  for (const auto &w : o.walls) {
    if (o.periodic[w.dim]) throw std::invalid_argument("walls must be in non-periodic dimensions");
    if ((int) w.laws.size() != nt + 1)
      throw std::invalid_argument("wall law table must have ntypes+1 entries");
    walled[w.dim] = true;
  }
  if (o.walls.size() > 100) throw std::invalid_argument("at most 100 walls");
  if (o.neighbours < EDOptions::AUTO || o.neighbours > EDOptions::LISTS)
    throw std::invalid_argument("neighbours must be AUTO, CELLS or LISTS");
  if (o.neighbours == EDOptions::LISTS && norm2(o.gravity) != 0.0)
    throw std::invalid_argument("neighbour lists do not work with gravity: use cells");
  if (!(o.list_skin >= 0.0)) throw std::invalid_argument("the list skin must be >= 0");
  if (o.max_collisions < 1 || o.max_collisions > 2000000000L)
    throw std::invalid_argument("the collision cap per particle and window must be 1 to 2e9");
  for (int d = 0; d < o.dim; d++)
    if (!o.periodic[d] && !walled[d] && !o.open[d])
      throw std::invalid_argument("a non-periodic dimension needs at least one wall");
}

static bool same_law(const LawParams &a, const LawParams &b)
{
  return a.kind == b.kind && a.r == b.r && a.rt_max == b.rt_max && a.mu_s == b.mu_s && a.mu_d == b.mu_d;
}

static bool same_laws(const std::vector<LawParams> &a, const std::vector<LawParams> &b)
{
  if (a.size() != b.size()) return false;
  for (size_t k = 0; k < a.size(); k++)
    if (!same_law(a[k], b[k])) return false;
  return true;
}

bool EventDriven::configured_as(const EDOptions &o, int nt, const std::vector<LawParams> &table) const
{
  if (o.dim != opt.dim || nt != ntypes || !same_laws(table, laws) ||
      o.gravity.x != opt.gravity.x || o.gravity.y != opt.gravity.y || o.gravity.z != opt.gravity.z ||
      o.tc != opt.tc || o.max_collisions != opt.max_collisions || o.gamma_bins != opt.gamma_bins ||
      o.cell_width != opt.cell_width || o.neighbours != opt.neighbours ||
      o.list_skin != opt.list_skin ||
      o.walls.size() != opt.walls.size() ||
      shape_table(o, nt) != qt)
    return false;
  for (int d = 0; d < 3; d++)
    if (o.lo[d] != opt.lo[d] || o.hi[d] != opt.hi[d] || o.periodic[d] != opt.periodic[d] ||
        o.open[d] != opt.open[d])
      return false;
  for (size_t k = 0; k < o.walls.size(); k++) {
    const EDWall &a = o.walls[k], &b = opt.walls[k];
    if (a.dim != b.dim || a.side != b.side || a.pos != b.pos || a.T != b.T || a.seed != b.seed ||
        a.A != b.A || a.omega != b.omega || a.sine != b.sine || !same_laws(a.laws, b.laws))
      return false;
  }
  return true;
}

void EventDriven::advance(int i, double t)
{
  Hot &p = H[i];
  if (p.t == t) return;
  const double dt = t - p.t;
  if (has_gravity) {
    p.x += dt * p.v + (0.5 * dt * dt) * opt.gravity;
    p.v += dt * opt.gravity;
  } else {
    p.x += dt * p.v;
  }
  p.t = t;
}

void EventDriven::resize(int n)
{
  fast.clear();
  acct = EDAccounting();
  H.assign(n, Hot());
  C.assign(n, Cold());
  TL.assign(opt.tc > 0.0 ? n : 0, -INF);
  S.assign(n, Sched());
  WT.clear();
  img.assign(n, Image{{0, 0, 0}, -1});
  lists = false;
  XN.clear();
  NB.clear();
  NN.clear();
  ext.resize(n);
  loc.resize(n);
  for (int i = 0; i < n; i++) ext[i] = loc[i] = i;
  started = false;
  dirty.clear();
}

// Renumber the particles in cell order, so that neighbours sit close in memory (the cost of a
// collision then stays flat with N). Partner references, cell lists and the queue follow; the
// external numbering (ext / loc) does not change. Deterministic: a stable sort by cell.
void EventDriven::reorder()
{
  const std::vector<int> order = cell_order();
  std::vector<double> times(order.size());    // event times in the new numbering
  for (size_t k = 0; k < order.size(); k++) times[k] = queue.time(order[k]);
  renumber(order);
  queue.build(times);
}

// particles by cell (stable: by index within a cell)
std::vector<int> EventDriven::cell_order() const
{
  const int n = (int) H.size();
  const int ncell = (int) head.size();
  // (empty slots after every cell)
  auto bin = [&](int i) { return S[i].gone ? ncell : cell_of(i); };
  std::vector<int> count(ncell + 2, 0), order(n);
  for (int i = 0; i < n; i++) count[bin(i) + 1]++;
  for (int c = 0; c <= ncell; c++) count[c + 1] += count[c];
  for (int i = 0; i < n; i++) order[count[bin(i)]++] = i;
  return order;
}

// new internal index k for the particle order[k]: records, partner references, index maps and
// cell lists follow (the queue is the caller's)
void EventDriven::renumber(const std::vector<int> &order)
{
  const int n = (int) H.size();
  std::vector<int> newloc(n);
  for (int k = 0; k < n; k++) newloc[order[k]] = k;
  {
    big_vector<Hot> Q(n);
    big_vector<Cold> K(n);
    big_vector<Sched> T(n);
    big_vector<Image> M(n);
    big_vector<int> newext(n);
    for (int k = 0; k < n; k++) {
      const int o = order[k];
      Q[k] = H[o];
      K[k] = C[o];
      T[k] = S[o];
      M[k] = img[o];
      if (T[k].cpartner >= 0) T[k].cpartner = newloc[T[k].cpartner];
      if (K[k].last_partner >= 0) K[k].last_partner = newloc[K[k].last_partner];
      newext[k] = ext[o];
    }
    if (!WT.empty()) {
      big_vector<double> W(n);
      for (int k = 0; k < n; k++) W[k] = WT[order[k]];
      WT.swap(W);
    }
    if (!TL.empty()) {
      big_vector<double> W(n);
      for (int k = 0; k < n; k++) W[k] = TL[order[k]];
      TL.swap(W);
    }
    if (lists) {
      big_vector<Vec3> X(n);
      big_vector<Entry> B((size_t) n * LCAP);
      big_vector<uint8_t> N(n);
      for (int k = 0; k < n; k++) {
        const int o = order[k];
        X[k] = XN[o];
        N[k] = NN[o];
        for (int m = 0; m < NN[o]; m++) {
          const Entry e = NB[(size_t) o * LCAP + m];
          B[(size_t) k * LCAP + m] = (Entry) newloc[entry_j(e)] << 5 | (e & 31);
        }
      }
      XN.swap(X);
      NB.swap(B);
      NN.swap(N);
    }
    H.swap(Q);
    C.swap(K);
    S.swap(T);
    img.swap(M);
    ext.swap(newext);
  }
  for (int k = 0; k < n; k++) loc[ext[k]] = k;
  std::fill(head.begin(), head.end(), -1);
  for (int i = n - 1; i >= 0; i--)
    if (!S[i].gone) cell_insert(i);
  crossings_since_reorder = 0;
}

// ---------------------------------------------------------------- cells

// Cell width: at least the largest contact distance sigma. In 2d a dilute system gets wider
// cells: a particle then crosses fewer cells per free path, for a few more candidates per scan.
// Measured optimum (callgrind, elastic discs, area fractions 0.05-0.3, bench/cell_width.sh):
// w = 0.52 sigma (n sigma^2)^(-2/3), i.e. sigma from area fraction 0.3 up (there 0.99 sigma),
// 3.3 sigma at 0.05. In 3d the narrowest cells were best, or within 2 %, at every fraction measured.
double EventDriven::auto_cell_width(int dim, double sigma, double n)
{
  if (dim != 2 || !(sigma > 0.0) || !(n > 0.0)) return sigma;
  return std::max(sigma, 0.52 * sigma * std::pow(n * sigma * sigma, -2.0 / 3.0));
}

void EventDriven::setup_cells()
{
  double amax = 0.0;
  long present = 0;
  for (size_t i = 0; i < H.size(); i++)
    if (!S[i].gone) {
      amax = std::max(amax, H[i].a);
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
  // bound the number of cells by the number of particles (beyond that cells only cost memory;
  // a dilute 3d system gains from up to 8 cells per particle, measured)
  const long maxcells = std::max<long>(27, (opt.dim == 3 ? 8L : 4L) * (long) H.size());
  while ((long) nc[0] * nc[1] * nc[2] > maxcells) {
    int d = 0;
    for (int k = 1; k < opt.dim; k++)
      if (nc[k] > nc[d]) d = k;
    nc[d] = std::max(1, nc[d] / 2);
    cw[d] = L[d] / nc[d];
  }
  head.assign((size_t) nc[0] * nc[1] * nc[2], -1);
  for (auto &m : img) m.next = -1;
  cell_amax = amax;
  for (size_t i = 0; i < H.size(); i++) {
    if (S[i].gone) continue;
    place((int) i);
    cell_insert((int) i);
  }
}

void EventDriven::place(int i)
{
  const Vec3 &x = lists ? XN[i] : H[i].x;    // (with lists: the list centre)
  Sched &s = S[i];
  for (int d = 0; d < 3; d++) {
    if (d >= opt.dim) {
      s.c[d] = 0;
      img[i].k[d] = 0;
      continue;
    }
    int c, k;
    locate(d, x[d], c, k);
    img[i].k[d] = k;
    s.c[d] = (int16_t) c;
  }
}

// cell c (0 .. nc-1) and periodic image k of coordinate xd in dimension d
void EventDriven::locate(int d, double xd, int &c, int &k) const
{
  long u = (long) std::floor((xd - opt.lo[d]) / cw[d]);
  if (!opt.periodic[d]) u = std::min<long>(std::max<long>(u, 0), nc[d] - 1);    // edge cells extend outward
  const long kk = u >= 0 ? u / nc[d] : -((-u + nc[d] - 1) / nc[d]);
  k = (int) kk;
  c = (int) (u - kk * nc[d]);
}

void EventDriven::cell_insert(int i)
{
  const int c = cell_of(i);
  img[i].next = head[c];
  head[c] = i;
}

// singly linked cell lists: a cell holds about one particle, so finding i's predecessor costs
// less than keeping a back link (4 bytes per particle) up to date
void EventDriven::cell_remove(int i)
{
  int *link = &head[cell_of(i)];
  while (*link != i) {
    if (*link < 0) throw std::logic_error("EventDriven: a particle is missing from its cell list");
    link = &img[*link].next;
  }
  *link = img[i].next;
}

// ---------------------------------------------------------------- prediction

void EventDriven::predict_crossing(int i, const Vec3 &xi, const Vec3 &vi)
{
  if (opt.dim == 2) {
    if (has_gravity)
      predict_crossing_t<2, true>(i, xi, vi);
    else
      predict_crossing_t<2, false>(i, xi, vi);
  } else {
    if (has_gravity)
      predict_crossing_t<3, true>(i, xi, vi);
    else
      predict_crossing_t<3, false>(i, xi, vi);
  }
}

// the dimension and whether there is gravity at all known at compile time
template <int DIM, bool GRAV>
void EventDriven::predict_crossing_t(int i, const Vec3 &xi, const Vec3 &vi)
{
  Sched &p = S[i];
  const int *k = img[i].k;
  double xt = NEVER;
  int xdim = 0, xdir = 0;
  auto offer = [&](double t, int d, int dir) {
    if (t < xt) xt = t, xdim = d, xdir = dir;
  };
  for (int d = 0; d < DIM; d++) {
    const double v = vi[d];
    const bool top = !opt.periodic[d] && p.c[d] == nc[d] - 1;    // no boundary beyond an edge cell
    const bool bottom = !opt.periodic[d] && p.c[d] == 0;
    if (!GRAV || opt.gravity[d] == 0.0) {
      // straight flight: only the boundary ahead can be reached
      if (v > 0.0) {
        if (top) continue;
        const double bhi = opt.lo[d] + ((double) p.c[d] + 1.0 + (double) k[d] * nc[d]) * cw[d];
        offer(now + std::max(0.0, (bhi - xi[d]) / v), d, 1);
      } else if (v < 0.0) {
        if (bottom) continue;
        const double blo = opt.lo[d] + ((double) p.c[d] + (double) k[d] * nc[d]) * cw[d];
        offer(now + std::max(0.0, (blo - xi[d]) / v), d, -1);
      }
      continue;
    }
    const double blo = opt.lo[d] + ((double) p.c[d] + (double) k[d] * nc[d]) * cw[d];
    const double bhi = opt.lo[d] + ((double) p.c[d] + 1.0 + (double) k[d] * nc[d]) * cw[d];
    offer(top ? NEVER : now + crossing_time(xi[d], v, opt.gravity[d], bhi, +1), d, 1);
    offer(bottom ? NEVER : now + crossing_time(xi[d], v, opt.gravity[d], blo, -1), d, -1);
  }
  p.xt = xt;
  if (xt < NEVER) p.xdim = (int8_t) xdim, p.xdir = (int8_t) xdir;
}

// collision candidates of i among the particles of the cells at offsets dlo..dhi (inclusive)
// around its cell; periodic images by integer offsets
void EventDriven::scan(int i, const Vec3 &xi, const Vec3 &vi, const int dlo[3], const int dhi[3])
{
  scan_in<false>(i, xi, vi, dlo, dhi);
}

void EventDriven::scan_full(int i, const Vec3 &xi, const Vec3 &vi)
{
  static const int lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};    // (in 2d z is not scanned)
  scan_in<true>(i, xi, vi, lo, hi);
}

template <bool FULL>
void EventDriven::scan_in(int i, const Vec3 &xi, const Vec3 &vi, const int dlo[3], const int dhi[3])
{
  if (opt.dim == 2) {
    if (has_gravity)
      scan_t<2, true, FULL>(i, xi, vi, dlo, dhi);
    else
      scan_t<2, false, FULL>(i, xi, vi, dlo, dhi);
  } else {
    if (has_gravity)
      scan_t<3, true, FULL>(i, xi, vi, dlo, dhi);
    else
      scan_t<3, false, FULL>(i, xi, vi, dlo, dhi);
  }
}

// one candidate j of i at the image shift o (j's position + o L): its contact time, kept as
// i's collision candidate when it is the earliest so far (i's state xi, vi now, its radius pa)
template <int DIM, bool GRAV>
inline __attribute__((always_inline)) void EventDriven::offer(int i, Sched &s, const Vec3 &xi,
                                                              const Vec3 &vi, double pa, int j,
                                                              int o0, int o1, int o2)
{
  const Hot &q = H[j];
  const Vec3 g = opt.gravity;
  const double dtj = now - q.t;
  double x0 = q.x.x + dtj * q.v.x, x1 = q.x.y + dtj * q.v.y;
  double x2 = DIM == 3 ? q.x.z + dtj * q.v.z : q.x.z;
  double v0 = q.v.x, v1 = q.v.y, v2 = DIM == 3 ? q.v.z : 0.0;
  if (o0 | o1 | o2) {
    x0 += o0 * L.x;
    x1 += o1 * L.y;
    if (DIM == 3) x2 += o2 * L.z;
  }
  if (GRAV) {
    const double h = 0.5 * dtj * dtj;
    x0 += h * g.x;
    x1 += h * g.y;
    v0 += dtj * g.x;
    v1 += dtj * g.y;
    if (DIM == 3) {
      x2 += h * g.z;
      v2 += dtj * g.z;
    }
  }
  const double t = now + pair_contact_time<DIM>(xi.x - x0, xi.y - x1, xi.z - x2, vi.x - v0,
                                                vi.y - v1, DIM == 3 ? vi.z - v2 : 0.0, pa + q.a);
  if (t < s.ct) {
    // two particles whose last collisions were with each other (same periodic image)
    // separate in free flight: relative motion is a straight line, they are no candidates
    // (tested only here, for a would-be candidate: the same outcome as skipping them)
    if (C[i].last_partner == j && C[j].last_partner == i && o0 == s.last_off[0] &&
        o1 == s.last_off[1] && o2 == s.last_off[2])
      return;
    s.ct = t;
    s.cpartner = j;
    s.ccount = C[j].ncoll;
    s.coff[0] = o0;
    s.coff[1] = o1;
    s.coff[2] = o2;
  }
}

// scan() for a dimension, with or without gravity, and for the whole neighbourhood (FULL: dlo,
// dhi = -1, +1 in every dimension) or not, known at compile time. In 2d nothing
// moves in z (v.z = 0, g.z = 0): the z terms of the relative motion vanish except the constant
// z distance, and every operation left is the one of the 3d arithmetic in the same order, so
// the contact times are the same numbers bit for bit.
template <int DIM, bool GRAV, bool FULL>
void EventDriven::scan_t(int i, const Vec3 &xi, const Vec3 &vi, const int dlo[3], const int dhi[3])
{
  Sched &s = S[i];
  const double pa = H[i].a;
  const int pk[3] = {img[i].k[0], img[i].k[1], img[i].k[2]};
  const int16_t *c = s.c;
  const int zlo = DIM == 3 ? (FULL ? -1 : dlo[2]) : 0, zhi = DIM == 3 ? (FULL ? 1 : dhi[2]) : 0;
  const int ylo = FULL ? -1 : dlo[1], yhi = FULL ? 1 : dhi[1];
  const int x0 = FULL ? -1 : dlo[0], x1 = FULL ? 1 : dhi[0];
  // the usual case: the block of cells lies inside the grid (no wrapping, no edges)
  bool inside = c[0] + x0 >= 0 && c[0] + x1 < nc[0] && c[1] + ylo >= 0 && c[1] + yhi < nc[1];
  if (DIM == 3) inside = inside && c[2] + zlo >= 0 && c[2] + zhi < nc[2];
  if (inside) {
    const int n0 = nc[0], n1 = nc[1];
    const Image *IM = img.data();
    const int *base = head.data() + (c[2] * n1 + c[1]) * n0 + c[0];
    // the first particle of every occupied cell, in cell order, gathered without branches
    // (which cells are empty is random: a branch per cell would be mispredicted often)
    int first[27], nfirst = 0;
#pragma GCC unroll 3
    for (int dz = zlo; dz <= zhi; dz++)
#pragma GCC unroll 3
      for (int dy = ylo; dy <= yhi; dy++) {
        const int *h = base + (dz * n1 + dy) * n0;
#pragma GCC unroll 3
        for (int dx = x0; dx <= x1; dx++) {
          const int j = h[dx];
          first[nfirst] = j;
          nfirst += j >= 0;
        }
      }
    for (int f = 0; f < nfirst; f++)
      for (int j = first[f]; j >= 0; j = IM[j].next)
        if (j != i) offer<DIM, GRAV>(i, s, xi, vi, pa, j, pk[0] - IM[j].k[0], pk[1] - IM[j].k[1],
                                     DIM == 3 ? pk[2] - IM[j].k[2] : 0);
    return;
  }
  for (int dz = zlo; dz <= zhi; dz++) {
    int uz = c[2] + dz, kz = 0;
    if (uz < 0) { if (!opt.periodic[2]) continue; uz += nc[2]; kz = -1; }
    else if (uz >= nc[2]) { if (!opt.periodic[2]) continue; uz -= nc[2]; kz = 1; }
    for (int dy = ylo; dy <= yhi; dy++) {
      int uy = c[1] + dy, ky = 0;
      if (uy < 0) { if (!opt.periodic[1]) continue; uy += nc[1]; ky = -1; }
      else if (uy >= nc[1]) { if (!opt.periodic[1]) continue; uy -= nc[1]; ky = 1; }
      for (int dx = x0; dx <= x1; dx++) {
        int ux = c[0] + dx, kx = 0;
        if (ux < 0) { if (!opt.periodic[0]) continue; ux += nc[0]; kx = -1; }
        else if (ux >= nc[0]) { if (!opt.periodic[0]) continue; ux -= nc[0]; kx = 1; }
        const int cell = (uz * nc[1] + uy) * nc[0] + ux;
        for (int j = head[cell]; j >= 0; j = img[j].next)
          if (j != i) offer<DIM, GRAV>(i, s, xi, vi, pa, j, pk[0] + kx - img[j].k[0], pk[1] + ky - img[j].k[1],
                                       DIM == 3 ? pk[2] + kz - img[j].k[2] : 0);
      }
    }
  }
}

// collision candidates of i among its listed neighbours (no gravity with lists)
void EventDriven::scan_list(int i, const Vec3 &xi, const Vec3 &vi)
{
  // the cell shift of an entry's code, one per component
  static constexpr int8_t KX[27] = {-1, 0, 1, -1, 0, 1, -1, 0, 1, -1, 0, 1, -1, 0, 1, -1, 0, 1, -1, 0, 1, -1, 0, 1, -1, 0, 1};
  static constexpr int8_t KY[27] = {-1, -1, -1, 0, 0, 0, 1, 1, 1, -1, -1, -1, 0, 0, 0, 1, 1, 1, -1, -1, -1, 0, 0, 0, 1, 1, 1};
  static constexpr int8_t KZ[27] = {-1, -1, -1, -1, -1, -1, -1, -1, -1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1};
  Sched &s = S[i];
  const double pa = H[i].a;
  const int pk[3] = {img[i].k[0], img[i].k[1], img[i].k[2]};
  const Entry *e = &NB[(size_t) i * LCAP];
  const int n = NN[i];
  const Image *IM = img.data();
  for (int m = 0; m < n; m++) {
    const int j = entry_j(e[m]), c = (int) (e[m] & 31);
    const int *qk = IM[j].k;
    if (opt.dim == 3)
      offer<3, false>(i, s, xi, vi, pa, j, pk[0] + KX[c] - qk[0], pk[1] + KY[c] - qk[1], pk[2] + KZ[c] - qk[2]);
    else
      offer<2, false>(i, s, xi, vi, pa, j, pk[0] + KX[c] - qk[0], pk[1] + KY[c] - qk[1], 0);
  }
}

long EventDriven::overlaps(double tol, long &key_i, long &key_j, double &depth) const
{
  long count = 0;
  depth = 0.0;
  key_i = key_j = -1;
  const int n = (int) H.size();
  const int reach[3] = {1, opt.dim > 1 ? 1 : 0, opt.dim > 2 ? 1 : 0};
  for (int i = 0; i < n; i++) {
    if (S[i].gone) continue;
    const Hot &p = H[i];
    const Vec3 xi = pos(i, now);
    for (int dz = -reach[2]; dz <= reach[2]; dz++)
      for (int dy = -reach[1]; dy <= reach[1]; dy++)
        for (int dx = -reach[0]; dx <= reach[0]; dx++) {
          const int d[3] = {dx, dy, dz};
          int u[3], k[3];
          bool skip = false;
          for (int m = 0; m < 3 && !skip; m++) {
            u[m] = S[i].c[m] + d[m];
            k[m] = 0;
            if (u[m] < 0 || u[m] >= nc[m]) {
              // (with fewer than 3 cells a cell is reached at two or three image shifts: each
              // is another image of its particles)
              if (!opt.periodic[m]) skip = true;
              k[m] = u[m] < 0 ? -1 : 1;
              u[m] -= k[m] * nc[m];
            }
          }
          if (skip) continue;
          const int cell = (u[2] * nc[1] + u[1]) * nc[0] + u[0];
          for (int j = head[cell]; j >= 0; j = img[j].next) {
            if (j == i) continue;
            const Hot &q = H[j];
            const long ki = key(i), kj = key(j);
            if (ki > kj || (ki == kj && i > j)) continue;    // each pair once
            if (!counted(ki <= kj ? i : j)) continue;
            const int *pk = img[i].k, *qk = img[j].k;
            const Vec3 shift((pk[0] + k[0] - qk[0]) * L.x, (pk[1] + k[1] - qk[1]) * L.y,
                             (pk[2] + k[2] - qk[2]) * L.z);
            const double dist = norm(xi - pos(j, now) - shift), sigma = p.a + q.a;
            if (dist < sigma * (1.0 - tol)) {
              count++;
              if (sigma - dist > depth) {
                depth = sigma - dist;
                key_i = ki;
                key_j = kj;
              }
            }
          }
        }
  }
  return count;
}

// predict() for every particle at once, all at time now (start of a window, after a global
// event; no last partners): crossings and walls per particle, and each pair contact time
// computed once and offered to both partners (the same time: both see one number). With fewer
// than three cells in a dimension a neighbour cell can be reached at two image shifts, and every
// particle scans its neighbourhood itself, as predict() does.
// the contact time of i and j seen from i at the image shift o (j's position + o L), offered to
// both as their collision candidate; every particle is at time now (its x and v are current)
void EventDriven::offer_both(int i, int j, int o0, int o1, int o2)
{
  const Hot &p = H[i], &q = H[j];
  Vec3 xj = q.x;
  if (o0 | o1 | o2) xj += Vec3(o0 * L.x, o1 * L.y, o2 * L.z);
  const double t = now + pair_contact_time(p.x - xj, p.v - q.v, p.a + q.a);
  Sched &si = S[i], &sj = S[j];
  if (t < si.ct) {
    si.ct = t;
    si.cpartner = j;
    si.ccount = C[j].ncoll;
    si.coff[0] = o0, si.coff[1] = o1, si.coff[2] = o2;
  }
  if (t < sj.ct) {
    sj.ct = t;
    sj.cpartner = i;
    sj.ccount = C[i].ncoll;
    sj.coff[0] = -o0, sj.coff[1] = -o1, sj.coff[2] = -o2;
  }
}

void EventDriven::predict_all()
{
  if (lists) {
    predict_all_lists();
    return;
  }
  const int n = (int) H.size();
  bool half = true;
  for (int d = 0; d < opt.dim; d++) half = half && nc[d] >= 3;
  for (int i = 0; i < n; i++) {
    if (S[i].gone) {
      no_events(i);
      continue;
    }
    predict(i, !half);
  }
  if (!half) return;
  // the forward half of the neighbourhood: 4 cells in 2d, 13 in 3d
  int fwd[13][3], nfwd = 0;
  for (int dz = 0; dz <= (opt.dim == 3 ? 1 : 0); dz++)
    for (int dy = -1; dy <= 1; dy++)
      for (int dx = -1; dx <= 1; dx++)
        if (dz > 0 || dy > 0 || (dy == 0 && dx > 0)) {
          fwd[nfwd][0] = dx, fwd[nfwd][1] = dy, fwd[nfwd][2] = dz;
          nfwd++;
        }
  for (int i = 0; i < n; i++) {
    if (S[i].gone) continue;
    const int *pk = img[i].k;
    const int16_t *c = S[i].c;
    for (int j = img[i].next; j >= 0; j = img[j].next) {    // the rest of its own cell
      const int *qk = img[j].k;
      offer_both(i, j, pk[0] - qk[0], pk[1] - qk[1], pk[2] - qk[2]);
    }
    bool inside = true;
    for (int d = 0; d < opt.dim; d++) inside = inside && c[d] >= 1 && c[d] + 1 < nc[d];
    for (int f = 0; f < nfwd; f++) {
      int u[3], k[3] = {0, 0, 0};
      bool skip = false;
      for (int d = 0; d < 3; d++) {
        u[d] = c[d] + fwd[f][d];
        if (inside || (u[d] >= 0 && u[d] < nc[d])) continue;
        if (!opt.periodic[d]) skip = true;
        k[d] = u[d] < 0 ? -1 : 1;
        u[d] -= k[d] * nc[d];
      }
      if (skip) continue;
      for (int j = head[(u[2] * nc[1] + u[1]) * nc[0] + u[0]]; j >= 0; j = img[j].next) {
        const int *qk = img[j].k;
        offer_both(i, j, pk[0] + k[0] - qk[0], pk[1] + k[1] - qk[1], pk[2] + k[2] - qk[2]);
      }
    }
  }
}

double EventDriven::schedule(int i)
{
  Sched &p = S[i];
  double et;
  if (p.ct <= p.xt) {
    et = p.ct;
    p.ekind = p.ct < NEVER ? COLLISION : NONE;
  } else {
    et = p.xt;
    p.ekind = CROSSING;
  }
  if (!WT.empty() && WT[i] < et) {
    et = WT[i];
    p.ekind = WALL;
  }
  return et;
}

// next contact of the particle's surface with a wall, moving toward it
void EDWall::motion(double s, double &w, double &vw, double &aw) const
{
  if (!vibrating()) {
    w = pos;
    vw = aw = 0.0;
    return;
  }
  if (sine) {
    const double ph = omega * s;
    w = pos + A * std::sin(ph);
    vw = A * omega * std::cos(ph);
    aw = -A * omega * omega * std::sin(ph);
    return;
  }
  const double H = M_PI / omega, a = 8.0 * A * omega * omega / (M_PI * M_PI), v0 = 0.5 * a * H;
  const double k = std::floor(s / H), u = s - k * H;
  const bool up = std::fmod(k, 2.0) == 0.0 || std::fmod(k, 2.0) == -0.0;
  const double sg = up ? 1.0 : -1.0;
  w = pos + sg * (v0 * u - 0.5 * a * u * u);
  vw = sg * (v0 - a * u);
  aw = -sg * a;
}

// Time (from now) during which a particle cannot touch a vibrating lower wall because its
// surface stays above the wall's highest point pos + A: until its downward crossing of that
// level (NEVER if it never comes down), 0 if it is at or below the level now. Searching for a
// contact only from there on keeps the cost independent of how long the flight is.
static double time_above_wall(const EDWall &w, double x, double v, double g, double a)
{
  const double top = w.pos + w.A + a;
  if (x <= top) return 0.0;
  return crossing_time(x, v, g, top, -1);
}

// First contact, at window time >= now, with a sinusoidally vibrating lower wall. The gap
// f(t) = x(t) - a - w(t) has |f''| <= M = |g| + A omega^2, so on [t0, t0 + h] it stays above
// f(t0) + f'(t0) s - M s^2 / 2: where that bound is positive there is no contact, elsewhere the
// interval is halved; a sign change is refined by bisection. Grazing contacts (f touching 0
// within round-off without changing sign) are not collisions. Several contacts in one step are
// found one after the other, each from the state after the previous one.
static double sine_contact(const EDWall &w, double clock, double now, double x, double v, double g,
                           double a)
{
  const double M = std::fabs(g) + w.A * w.omega * w.omega;
  auto gap = [&](double t, double &df) {
    const double dt = t - now, s = clock + t;
    df = v + g * dt - w.A * w.omega * std::cos(w.omega * s);
    return x + v * dt + 0.5 * g * dt * dt - a - (w.pos + w.A * std::sin(w.omega * s));
  };
  // the last time a contact is possible: the particle falls for ever below the lowest wall point
  // (it hits before), or flies for ever above the highest
  double horizon;
  if (g < 0.0) {
    horizon = crossing_time(x, v, g, w.pos - w.A + a, -1);
  } else {
    if (v >= w.A * w.omega && x - a > w.pos + w.A) return NEVER;
    horizon = crossing_time(x, v, g, w.pos + w.A + a, +1);
    if (horizon == NEVER && v < 0.0) horizon = crossing_time(x, v, g, w.pos - w.A + a, -1);
  }
  const double tmax = horizon == NEVER ? NEVER : now + horizon + 1e-9 * (1.0 + horizon);
  const double start = now + time_above_wall(w, x, v, g, a);
  if (start >= NEVER) return NEVER;
  double df0;
  double f0 = gap(start, df0);
  if (f0 <= 0.0 && df0 < 0.0) return start;    // overlapping and approaching: now
  const double hmax = 0.25 * 2.0 * M_PI / w.omega;
  double t0 = start, h = hmax;
  const double tiny = 1e-13 * (1.0 + std::fabs(now));
  long guard = 0;
  while (t0 < tmax && ++guard < 100000000L) {
    double t1 = t0 + h;
    if (f0 <= 0.0) {
      // at (or a hair inside) the wall, as after a contact: approaching means a contact now;
      // moving away, f' >= f'(t0) - M s stays >= 0 for s <= f'(t0)/M, so no downward crossing
      // can happen before that (the wall may catch up right after: checked from there)
      if (df0 < 0.0) return t0;
      t1 = t0 + std::min(h, std::max(tiny, df0 / M));
      if (tmax < NEVER && t1 > tmax) t1 = tmax;
      t0 = t1;
      f0 = gap(t1, df0);
      continue;
    }
    if (tmax < NEVER && t1 > tmax) t1 = tmax;
    double df1;
    const double f1 = gap(t1, df1);
    if (f0 > 0.0 && f1 <= 0.0) {
      // a downward zero in (t0, t1]: bisect
      double lo = t0, hi = t1;
      for (int it = 0; it < 200 && hi - lo > 1e-15 * (1.0 + std::fabs(hi)); it++) {
        const double mid = 0.5 * (lo + hi);
        double dm;
        (gap(mid, dm) > 0.0 ? lo : hi) = mid;
      }
      return hi;
    }
    // no sign change: f >= f0 + f'(t0) s - M s^2 / 2 (concave, least at the ends), so a dip
    // below zero inside is impossible when that bound is positive at s = t1 - t0
    const double s = t1 - t0;
    const double bound = f0 + df0 * s - 0.5 * M * s * s;
    if (bound > 0.0 || s < tiny) {
      t0 = t1;    // safe (or a graze within round-off): advance
      f0 = f1;
      df0 = df1;
      h = std::min(hmax, 2.0 * h);
    } else {
      h = 0.5 * s;    // inconclusive: look closer
    }
  }
  return NEVER;
}

// first contact, at window time >= now, of particle i (state xi, vi now) with a vibrating lower
// wall: on each half period the relative motion is a parabola, solved exactly
static double vibrating_contact(const EDWall &w, double clock, double now, double x, double v,
                                double g, double a)
{
  const double H = M_PI / w.omega, vmax = 0.5 * 8.0 * w.A * w.omega * w.omega / (M_PI * M_PI) * H;
  // past this time no contact is possible: the particle is for ever above the wall's highest
  // point (upward flight without gravity) or has gone below its lowest (then it hit before)
  double horizon;
  if (g < 0.0) {
    horizon = crossing_time(x, v, g, w.pos - w.A + a, -1);
  } else {
    if (v >= vmax && x - a > w.pos + w.A) return NEVER;
    horizon = crossing_time(x, v, g, w.pos + w.A + a, +1);
    if (horizon == NEVER && v < 0.0) horizon = crossing_time(x, v, g, w.pos - w.A + a, -1);
  }
  double t = now + time_above_wall(w, x, v, g, a);
  for (long iter = 0; t < NEVER && iter < 100000000L; iter++) {
    const double s = clock + t;
    const double k = std::floor(s / H);
    const double tend = (k + 1.0) * H - clock;
    double ww, vw, aw;
    w.motion(s, ww, vw, aw);
    const double dt = t - now;
    const double xp = x + v * dt + 0.5 * g * dt * dt, vp = v + g * dt;
    const double tau = crossing_time(xp - a - ww, vp - vw, g - aw, 0.0, -1);
    if (tau < NEVER && t + tau <= tend) return t + tau;
    if (horizon < NEVER && tend > now + horizon + H) return NEVER;
    t = tend > t ? tend : std::nextafter(t, NEVER);
  }
  return NEVER;
}

void EventDriven::predict_walls(int i, const Vec3 &xi, const Vec3 &vi)
{
  Sched &p = S[i];
  const double a = H[i].a;
  for (int k = 0; k < (int) opt.walls.size(); k++) {
    const EDWall &w = opt.walls[k];
    const int d = w.dim;
    double t;
    if (w.vibrating() && w.sine)
      t = sine_contact(w, clock, now, xi[d], vi[d], opt.gravity[d], a);
    else if (w.vibrating())
      t = vibrating_contact(w, clock, now, xi[d], vi[d], opt.gravity[d], a);
    else
      t = now + (w.side < 0 ? crossing_time(xi[d], vi[d], opt.gravity[d], w.pos + a, -1)
                            : crossing_time(xi[d], vi[d], opt.gravity[d], w.pos - a, +1));
    if (t < WT[i]) {
      WT[i] = t;
      p.wall = (int8_t) k;
    }
  }
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

Collision EventDriven::thermal_reemission(const EDWall &w, int i, const Vec3 &n, double t)
{
  const EDParticleView p = view(i);
  uint64_t tbits;
  std::memcpy(&tbits, &t, sizeof(tbits));
  CounterStream rng{mix64(mix64(w.seed) ^ (uint64_t) this->key(i)) ^ tbits};
  auto uniform = [&rng]() { return rng.uniform(); };
  auto gauss = [&]() { return gauss_radius(uniform()) * std::cos(2.0 * M_PI * uniform()); };
  const double sv = std::sqrt(w.T / p.m), sw = std::sqrt(w.T / (p.q * p.m * p.a * p.a));
  Collision c;
  Vec3 v;
  for (int d = 0; d < 3; d++)
    if (d != w.dim && d < opt.dim) v[d] = sv * gauss();
  v[w.dim] = n[w.dim] * sv * gauss_radius(uniform());    // flux: v_n exp(-v_n^2/2)
  Vec3 wv;
  if (opt.dim == 2)
    wv.z = sw * gauss();
  else
    wv = sw * Vec3(gauss(), gauss(), gauss());
  c.v1 = v;
  c.w1 = wv;
  c.dE = 0.5 * p.m * (norm2(v) - norm2(p.v)) + 0.5 * p.q * p.m * p.a * p.a * (norm2(wv) - norm2(p.w));
  c.gn = dot(p.v, n);
  return c;
}

void EventDriven::tally(int i, const Vec3 &r, const Vec3 &dP, double t, double dE_tr, double dE_rot,
                        bool wall)
{
  ParticleTally &p = PT[ext[i]];
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

void EventDriven::collide_wall(int i)
{
  Hot &h = H[i];
  Cold &p = C[i];
  Sched &s = S[i];
  const double t = WT[i];
  advance(i, t);
  const EDWall &w = opt.walls[s.wall];
  Vec3 n;
  n[w.dim] = w.side < 0 ? 1.0 : -1.0;
  LawParams law = w.laws[s.type];
  const bool tc_elastic = tc_recent(i, t);
  if (tc_elastic) law = law.elastic();
  const double q = qt[s.type];
  Body b{h.v, p.w, p.m, h.a, q};
  Collision c;    // (its dE is set below for moving walls)
  if (w.T >= 0.0) {
    c = thermal_reemission(w, i, n, t);
  } else {
    double ww, vw, aw;
    w.motion(clock + t, ww, vw, aw);
    Vec3 vwall;
    vwall[w.dim] = vw;
    c = collide(law, b, Body::wall(vwall), n);
  }
  // kinetic energy change in the lab frame: a moving wall does work on the particle, so this is
  // not the law's dissipation (equal to it for a wall at rest)
  const double dE_tr = 0.5 * p.m * (norm2(c.v1) - norm2(h.v));
  const double dE_rot = 0.5 * q * p.m * h.a * h.a * (norm2(c.w1) - norm2(p.w));
  const double dE = dE_tr + dE_rot;
  c.dE = w.vibrating() ? dE : c.dE;
  const Vec3 dP = p.m * (c.v1 - h.v);    // (a thermal wall's too)
  if (tally_on) tally(i, h.a * n, dP, t, dE_tr, dE_rot, true);
  h.v = c.v1;
  p.w = c.w1;
  if (!TL.empty()) TL[i] = t;
  if (tracking_fast()) note_speed(i, h.v);
  p.ncoll++;
  p.last_partner = -1;
  if (history && (!record_only || record_only[ext[i]]))
    history->push_back({t, ext[i], -1 - s.wall, h.v, p.w, Vec3(), Vec3()});
  const long ni = ++s.ncollisions;
  if (counted(i)) {
    stats.wall_collisions++;
    stats.dE_wall += c.dE;
    if (c.sliding) stats.sliding++;
    if (c.energy_created) stats.energy_created++;
    if (tc_elastic) stats.tc_elastic++;
    stats.max_collisions_one_particle = std::max(stats.max_collisions_one_particle, ni);
    add_virial(stats.virial, h.a * n, dP);
    const int k = s.wall;
    if (collision_log)
      collision_log->push_back({t, ext[i], -1 - k, c.gn, c.gt, c.cos_gamma, std::fabs(dP[w.dim]), c.dE, c.sliding});
    stats.wall_hits[k]++;
    for (int d = 0; d < 3; d++) stats.wall_impulse[3 * k + d] -= dP[d];
    stats.wall_work[k] += dE;
  }
  if (ni > opt.max_collisions) {
    std::ostringstream s;
    s << "particle " << ext[i] << " collided " << ni << " times within one window (cap "
      << opt.max_collisions << "), the last time with a wall: inelastic collapse; use the TC "
      << "model (tc) or a larger cap";
    throw EventCapError(s.str(), ext[i], ext[i], t, ni);
  }
  predict(i);
  reschedule(i);
}

void EventDriven::predict(int i, bool pairs)
{
  Sched &p = S[i];
  const Vec3 xi = pos(i, now), vi = vel(i, now);
  if (lists)
    predict_rebuild(i, xi, vi);
  else
    predict_crossing(i, xi, vi);
  predict_wall(i, xi, vi);
  p.ct = NEVER;
  p.cpartner = -1;
  if (!pairs) return;
  if (lists)
    scan_list(i, xi, vi);
  else
    scan_full(i, xi, vi);
}

// ---------------------------------------------------------------- events

void EventDriven::collide_pair(int i)
{
  Hot &hp = H[i];
  Cold &p = C[i];
  Sched &s = S[i];
  const int j = s.cpartner;
  Hot &hq = H[j];
  Cold &q = C[j];
  const double t = s.ct;
  advance(i, t);
  advance(j, t);
  const Vec3 r = hp.x - hq.x - Vec3(s.coff[0] * L.x, s.coff[1] * L.y, s.coff[2] * L.z);
  const Vec3 n = (1.0 / norm(r)) * r;

  LawParams law = laws[s.type * (ntypes + 1) + S[j].type];
  const bool tc_elastic = tc_recent(i, t) || tc_recent(j, t);
  if (!TL.empty()) TL[i] = TL[j] = t;
  if (tc_elastic) law = law.elastic();
  Body b1{hp.v, p.w, p.m, hp.a, qt[s.type]}, b2{hq.v, q.w, q.m, hq.a, qt[S[j].type]};
  const Collision c = collide(law, b1, b2, n);
  if (tally_on) {    // (r (x) dP is the same seen from j: -r (x) -dP)
    const Vec3 half = 0.5 * r;
    tally(i, half, c.dP, t, 0.5 * p.m * (norm2(c.v1) - norm2(hp.v)),
          0.5 * b1.q * p.m * hp.a * hp.a * (norm2(c.w1) - norm2(p.w)), false);
    tally(j, half, c.dP, t, 0.5 * q.m * (norm2(c.v2) - norm2(hq.v)),
          0.5 * b2.q * q.m * hq.a * hq.a * (norm2(c.w2) - norm2(q.w)), false);
  }
  hp.v = c.v1;
  p.w = c.w1;
  hq.v = c.v2;
  q.w = c.w2;
  if (tracking_fast()) {
    note_speed(i, hp.v);
    note_speed(j, hq.v);
  }
  p.ncoll++;
  q.ncoll++;
  p.last_partner = j;
  q.last_partner = i;
  for (int d = 0; d < 3; d++) {
    s.last_off[d] = s.coff[d];
    S[j].last_off[d] = -s.coff[d];
  }
  // (without an accounting every collision is booked: the keys, another array, are not read)
  const bool book = !acct.counted || counted(key(i) <= key(j) ? i : j);
  if (history && (!record_only || record_only[ext[i]] || record_only[ext[j]]))
    history->push_back({t, ext[i], ext[j], hp.v, p.w, hq.v, q.w});
  const long ni = ++s.ncollisions, nj = ++S[j].ncollisions;
  if (counted(i)) stats.max_collisions_one_particle = std::max(stats.max_collisions_one_particle, ni);
  if (counted(j)) stats.max_collisions_one_particle = std::max(stats.max_collisions_one_particle, nj);
  if (book) {
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
  if (ni > opt.max_collisions || nj > opt.max_collisions) {
    std::ostringstream s;
    s << "particles " << ext[i] << " and " << ext[j] << " collided " << std::max(ni, nj)
      << " times within one window (cap " << opt.max_collisions
      << "): inelastic collapse; use the TC model (tc) or a larger cap";
    throw EventCapError(s.str(), ni >= nj ? ext[i] : ext[j], ni >= nj ? ext[j] : ext[i], t,
                        std::max(ni, nj));
  }
  predict(i);
  reschedule(i);
  predict(j);
  reschedule(j);
}

// one more crossing (or list rebuild) of particle i in this window, within the cap
void EventDriven::count_crossing(int i)
{
  if (++window_crossings <= crossing_cap) return;
  const double speed = norm(vel(i, now));
  std::ostringstream s;
  s << "cell crossings in one window exceed the cap (" << crossing_cap
    << " = the collision cap times the number of particles); particle " << ext[i]
    << " was crossing at speed " << speed;
  throw EventCapError(s.str(), ext[i], ext[i], now, window_crossings, EventCapError::CROSSINGS, speed);
}

void EventDriven::cross(int i)
{
  if (lists) {
    list_rebuild(i);
    return;
  }
  count_crossing(i);
  const Hot &q = H[i];
  Sched &p = S[i];
  const int d = p.xdim, dir = p.xdir;
  advance(i, p.xt);
  cell_remove(i);
  p.c[d] += dir;
  if (p.c[d] == nc[d]) {
    p.c[d] = 0;
    img[i].k[d]++;
  } else if (p.c[d] < 0) {
    p.c[d] = nc[d] - 1;
    img[i].k[d]--;
  }
  cell_insert(i);
  stats.crossings++;
  crossings_since_reorder++;
  const Vec3 xi = q.x, vi = q.v;    // advanced to now above
  predict_crossing(i, xi, vi);
  if (p.ct < NEVER && C[p.cpartner].ncoll != p.ccount) {
    // the stored collision candidate went stale: look at every neighbouring cell
    p.ct = NEVER;
    p.cpartner = -1;
    scan_full(i, xi, vi);
  } else {
    // trajectory unchanged: only the layer of cells that just became adjacent is new
    const int zr = opt.dim == 3 ? 1 : 0;
    int dlo[3] = {-1, -1, -zr}, dhi[3] = {1, 1, zr};
    dlo[d] = dhi[d] = dir;
    if (nc[d] < 3) dlo[d] = -1, dhi[d] = 1;    // with fewer than 3 cells every cell is new
    scan(i, xi, vi, dlo, dhi);
  }
  reschedule(i);
}

void EventDriven::start()
{
  now = 0.0;
  const int n = (int) H.size();
  for (auto &s : S) s.ncollisions = 0;
  WT.assign(opt.walls.empty() ? 0 : n, NEVER);
  for (int i = 0; i < n; i++) {
    H[i].t = 0.0;
    C[i].ncoll = 0;
    C[i].last_partner = -1;
    if (opt.dim == 2) {
      H[i].v.z = 0.0;
      C[i].w.x = C[i].w.y = 0.0;
    }
  }
  double amax = 0.0;
  for (int i = 0; i < n; i++)
    if (!S[i].gone) amax = std::max(amax, H[i].a);
  setup_lists(2.0 * amax * (1.0 + 1e-10));
  setup_cells();
  renumber(cell_order());
  if (lists && !build_all_lists()) lists_to_cells();
  predict_all();
  std::vector<double> times(n);
  for (int i = 0; i < n; i++) times[i] = schedule(i);
  queue.build(times);
  started = true;
  dirty.clear();
}

void EventDriven::remove(int e)
{
  const int i = loc[e];
  Sched &s = S[i];
  if (s.gone) return;
  if (started) {
    if (lists) list_drop(i);
    cell_remove(i);
    queue.update(i, NEVER);
  }
  s.gone = 1;
  no_events(i);
  s.ekind = NONE;
  C[i].ncoll++;    // predictions that involved it are stale
  C[i].last_partner = -1;
}

void EventDriven::changed(int e)
{
  const int i = loc[e];
  Hot &p = H[i];
  Cold &c = C[i];
  Sched &s = S[i];
  if (!started) throw std::logic_error("EventDriven::changed() before start()");
  if (!(p.a <= cell_amax))
    throw std::invalid_argument("a changed particle's radius exceeds what the cell grid admits");
  if (!s.gone) {
    if (lists) list_drop(i);
    cell_remove(i);
  }
  s.gone = 0;
  p.t = now;
  c.ncoll++;    // every prediction that involved it is stale
  c.last_partner = -1;
  if (opt.dim == 2) {
    p.v.z = 0.0;
    c.w.x = c.w.y = 0.0;
  }
  if (lists) XN[i] = p.x;
  place(i);
  cell_insert(i);
  no_events(i);
  queue.update(i, NEVER);    // until refresh() predicts it
  dirty.push_back(e);
  if (lists && !list_build(i, false)) lists_to_cells();
}

bool EventDriven::nudge(int e, const double *x, const double *v, const double *w)
{
  const int i = loc[e];
  Hot &p = H[i];
  const Sched &s = S[i];
  if (!started) throw std::logic_error("EventDriven::nudge() before start()");
  if (s.gone || lists) return false;
  for (int d = 0; d < opt.dim; d++) {    // the cell (and image) place() would give
    int c, k;
    locate(d, x[d], c, k);
    if (k != img[i].k[d] || c != s.c[d]) return false;
  }
  p.x = Vec3(x[0], x[1], x[2]);
  p.v = Vec3(v[0], v[1], v[2]);
  p.t = now;
  Cold &c = C[i];
  c.w = Vec3(w[0], w[1], w[2]);
  if (opt.dim == 2) {
    p.v.z = 0.0;
    c.w.x = c.w.y = 0.0;
  }
  return true;
}

void EventDriven::refresh()
{
  for (int e : dirty) {
    const int i = loc[e];
    if (S[i].gone) continue;    // (changed, then removed)
    predict(i);
    reschedule(i);
  }
  dirty.clear();
}

EDStats EventDriven::advance_to(double t_end)
{
  stats = EDStats();
  stats.gamma_hist.assign(std::max(0, opt.gamma_bins), 0);
  stats.wall_hits.assign(opt.walls.size(), 0);
  stats.wall_impulse.assign(3 * opt.walls.size(), 0.0);
  stats.wall_work.assign(opt.walls.size(), 0.0);
  if (tally_on) PT.assign(H.size(), ParticleTally{{0, 0, 0, 0, 0, 0}, 0, 0, 0, 0, 0, -INF});
  for (auto &s : S) s.ncollisions = 0;
  const int n = (int) H.size();
  window_crossings = 0;
  crossing_cap = opt.max_collisions * (long) std::max(1, n);
  refresh();
  if (crossings_since_reorder > 4L * n) reorder();
  size_t g = 0;
  while (n > 0) {
    const int i = queue.top();
    const double et = queue.top_time();
    const Sched &p = S[i];
    if (g < gtimes.size() && gtimes[g] < t_end && !(et < gtimes[g])) {
      global_event((int) g++);
      continue;
    }
    if (!(et < t_end)) break;
    now = et;
    if (p.ekind == COLLISION) {
      if (C[p.cpartner].ncoll != p.ccount) {
        predict(i);    // the partner changed course: stale prediction
        reschedule(i);
      } else {
        collide_pair(i);
      }
    } else if (p.ekind == CROSSING) {
      cross(i);
    } else if (p.ekind == WALL) {
      collide_wall(i);
    } else {
      break;
    }
  }
  gtimes.clear();
  now = t_end;
  return stats;
}

void EventDriven::set_global_events(const std::vector<double> &times, std::function<void(int)> apply)
{
  gtimes = times;
  gapply = std::move(apply);
}

void EventDriven::global_event(int k)
{
  now = gtimes[k];
  const int n = (int) H.size();
  auto energy = [&]() {
    double e = 0.0;
    for (int i = 0; i < n; i++) {
      const Cold &p = C[i];
      if (counted(i)) e += 0.5 * p.m * (norm2(H[i].v) + qt[S[i].type] * H[i].a * H[i].a * norm2(p.w));
    }
    return e;
  };
  for (int i = 0; i < n; i++) advance(i, now);
  const double before = energy();
  gapply(k);
  stats.injected += energy() - before;
  stats.global_events++;
  for (int i = 0; i < n; i++) {
    Hot &h = H[i];
    Cold &p = C[i];
    p.ncoll++;    // every trajectory changed: all stored predictions are stale
    p.last_partner = -1;
    if (opt.dim == 2) {
      h.v.z = 0.0;
      p.w.x = p.w.y = 0.0;
    }
    if (tracking_fast()) note_speed(i, h.v);
  }
  predict_all();
  std::vector<double> times(n);
  for (int i = 0; i < n; i++) times[i] = schedule(i);
  queue.build(times);
}

void EventDriven::rebase(double dt)
{
  // the same shift for every time keeps the heap ordered (rounding is monotone)
  for (auto &p : H) p.t -= dt;
  for (auto &t : TL) t -= dt;
  for (auto &s : S) {
    s.ct -= dt;
    s.xt -= dt;
  }
  for (auto &t : WT) t -= dt;
  queue.shift(dt);
  now -= dt;
  clock += dt;
}

EDStats EventDriven::run(double t_end)
{
  start();
  const EDStats s = advance_to(t_end);
  for (int i = 0; i < (int) H.size(); i++) advance(i, t_end);
  return s;
}

}    // namespace granfric
