// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the search for collision candidates (see event_driven.h): pair contact times against
// the particles of neighbouring cells or of a neighbour list, all at once at a start, and the
// overlap check.
#include "event_driven.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace granfric {

// collision candidates of i among the particles of the cells at offsets dlo..dhi (inclusive)
// around its cell; periodic images by integer offsets
void EDCore::scan(int i, const int dlo[3], const int dhi[3])
{
  scan_in<false>(i, dlo, dhi);
}

void EDCore::scan_full(int i)
{
  static const int lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};    // (in 2d z is not scanned)
  scan_in<true>(i, lo, hi);
}

template <bool FULL>
void EDCore::scan_in(int i, const int dlo[3], const int dhi[3])
{
  if (opt.shear) {    // (a sheared box: its cells move with the flow, see shear.cpp)
    scan_shear_in<FULL>(i, dlo, dhi);
    return;
  }
  if (opt.dim == 2) {
    if (has_gravity)
      scan_at<2, true, FULL>(i, dlo, dhi);
    else
      scan_at<2, false, FULL>(i, dlo, dhi);
  } else {
    if (has_gravity)
      scan_at<3, true, FULL>(i, dlo, dhi);
    else
      scan_at<3, false, FULL>(i, dlo, dhi);
  }
}

// (out of line: the unsheared scans stay small enough to be inlined where they are called)
template <bool FULL>
__attribute__((noinline)) void EDCore::scan_shear_in(int i, const int dlo[3], const int dhi[3])
{
  const bool done = opt.dim == 2 ? (has_gravity ? scan_rows_at<2, true, FULL>(i, dlo, dhi)
                                                : scan_rows_at<2, false, FULL>(i, dlo, dhi))
                                 : (has_gravity ? scan_rows_at<3, true, FULL>(i, dlo, dhi)
                                                : scan_rows_at<3, false, FULL>(i, dlo, dhi));
  if (!done) scan_sheared(i, FULL, dlo, dhi);
}

// A seeker at the present (as after its collision) is at least as late as every candidate
// (at_present()): its scan knows that at compile time (LATEST)
template <int DIM, bool GRAV, bool FULL>
inline void EDCore::scan_at(int i, const int dlo[3], const int dhi[3])
{
  if (at_present(i))
    scan_t<DIM, GRAV, FULL, true>(i, dlo, dhi);
  else
    scan_t<DIM, GRAV, FULL, false>(i, dlo, dhi);
}

// The candidates of a sheared box in the rows of cells next to i (sheared_spans)
template <int DIM, bool GRAV, bool LATEST>
void EDCore::scan_spans_t(int i, const RowSpan *s, int n)
{
  Seek k = seek(i);
  if (DIM == 3 && !GRAV && lanes && offer_spans_lanes<LATEST>(k, s, n)) {
    settle(k);
    return;
  }
  const CellImage *IM = images.data();
  const int n0 = nc[0];
  // the occupied cells of every row, in order, gathered first without a branch per cell (which
  // cells are empty is random), as scan_t() does: each with its x image and row
  int first[9 * 4], qs[9 * 4], rs[9 * 4], nf = 0;
  for (int r = 0; r < n; r++) {
    const RowSpan &w = s[r];
    const int *row = head.data() + w.row;
    int q = w.q, u = w.u;
    for (long a = w.a0; a <= w.a1; a++) {
      const int j = row[u];
      first[nf] = j, qs[nf] = q, rs[nf] = r;
      nf += j >= 0;
      if (++u == n0) u = 0, q++;
    }
  }
  for (int f = 0; f < nf; f++) {
    const RowSpan &w = s[rs[f]];
    for (int j = first[f]; j >= 0; j = IM[j].next)
      if (j != i)
        offer<DIM, GRAV, LATEST, true>(k, j, qs[f] - IM[j].k[0], w.ky - IM[j].k[1], DIM == 3 ? w.kz - IM[j].k[2] : 0);
  }
  settle(k);
}

void EDCore::scan_spans(int i, const RowSpan *s, int n)
{
  const bool latest = at_present(i);
  if (opt.dim == 2) {
    if (has_gravity)
      latest ? scan_spans_t<2, true, true>(i, s, n) : scan_spans_t<2, true, false>(i, s, n);
    else
      latest ? scan_spans_t<2, false, true>(i, s, n) : scan_spans_t<2, false, false>(i, s, n);
  } else {
    if (has_gravity)
      latest ? scan_spans_t<3, true, true>(i, s, n) : scan_spans_t<3, true, false>(i, s, n);
    else
      latest ? scan_spans_t<3, false, true>(i, s, n) : scan_spans_t<3, false, false>(i, s, n);
  }
}

// The contact time of a particle in stored state p and one in stored state q at the image shift
// o (q's position + o P), canonical: from both stored states at tr = max(t_p, t_q) (the
// arithmetic of pos() and vel()), whoever predicts the pair and whenever; not before now.
// Usually p is the later one (it has just collided): its stored state is then its state at tr.
// Seen from q (shift -o) it is the same number: the differences change sign exactly. NEVER also
// for a contact that certainly comes at or after before (see pair_contact_time's horizon).
template <int DIM, bool GRAV, bool SHEARED>
inline __attribute__((always_inline)) double EDCore::contact(const Flight &p, const Flight &q, int o0,
                                                                  int o1, int o2, double before) const
{
  if (q.t <= p.t)
    return contact_at<DIM, GRAV, SHEARED>(p, p.t, p.x, p.v, q, o0, o1, o2, horizon_limit(before - p.t, before));
  const double tr = q.t, dt = tr - p.t;
  const Vec3 g = opt.gravity;
  const Vec3 xa = flight_x(p.x, p.v, dt, g, GRAV), va = flight_v(p.v, dt, g);
  return contact_at<DIM, GRAV, SHEARED>(p, tr, xa, va, q, o0, o1, o2, horizon_limit(before - tr, before));
}

// contact() with p's state at tr >= q.t given (position a, velocity u) and the horizon as its
// limit h. The x and y components go in pairs (one SSE2 operation for both): each is the
// scalar arithmetic of pos() and vel() and of the contact time, operation by operation, so the
// numbers are the same bit for bit.
typedef double v2d __attribute__((vector_size(16)));
static inline v2d xy(const Vec3 &a)
{
  v2d r;
  std::memcpy(&r, &a.x, sizeof r);
  return r;
}

// SHEARED: a sheared box (Lees-Edwards: the image o1 periods up lies o1 s(tr) further in x and
// moves o1 times the shear rate faster; at o1 = 0 the terms are exact zeros, which leave every
// number as it is); either partner computes the same numbers (the negated shift gives the
// negated differences). The scans of a sheared box are instances of their own (scan_spans_t), so
// that those of an unsheared one test nothing.
template <int DIM, bool GRAV, bool SHEARED>
inline __attribute__((always_inline)) double EDCore::contact_at(const Flight &p, double tr, const Vec3 &a,
                                                                     const Vec3 &u, const Flight &q, int o0,
                                                                     int o1, int o2, double h) const
{
  const double dtj = tr - q.t;    // q at tr
  const v2d dt = {dtj, dtj};
  v2d bxy = xy(q.x) + dt * xy(q.v), wxy = xy(q.v);
  double b2 = DIM == 3 ? q.x.z + dtj * q.v.z : q.x.z, w2 = DIM == 3 ? q.v.z : 0.0;
  if (GRAV) {
    const Vec3 g = opt.gravity;
    const double h = 0.5 * dtj * dtj;
    const v2d hh = {h, h};
    bxy += hh * xy(g);
    wxy += dt * xy(g);
    if (DIM == 3) {
      b2 += h * g.z;
      w2 += dtj * g.z;
    }
  }
  v2d r = xy(a) - bxy;
  double r2 = a.z - b2;
  v2d v = xy(u) - wxy;
  if (o0 | o1 | o2) {
    const v2d s = {o0 * P.x, o1 * P.y};
    r -= s;
    if (DIM == 3) r2 -= o2 * P.z;
    if (SHEARED) r[0] -= o1 * shift_at(tr), v[0] -= image_speed(o1);
  }
  const double v2 = DIM == 3 ? u.z - w2 : 0.0;
  const v2d rv = r * v, rr = r * r;
  const double b = DIM == 3 ? (rv[0] + rv[1]) + r2 * v2 : rv[0] + rv[1];
  const double sigma = p.a + q.a;
  const double c = ((rr[0] + rr[1]) + r2 * r2) - sigma * sigma;
  const double tau = contact_root<DIM>(b, c, v[0], v[1], v2, h);
  if (tau == NEVER) return NEVER;
  return at_least_now(tr + tau);
}

template <int DIM, bool GRAV, bool SHEARED>
double EDCore::pair_time(int i, int j, int o0, int o1, int o2) const
{
  return contact<DIM, GRAV, SHEARED>(flights[i], flights[j], o0, o1, o2, NEVER);
}

// One candidate j at the image shift o (j's position + o P): kept as the seeker's best when its
// contact time is the earliest so far. LATEST: the seeker's stored time is the latest (no
// candidate's is later), so that its state and horizon limit are the scan's for every one.
template <int DIM, bool GRAV, bool LATEST, bool SHEARED>
inline __attribute__((always_inline)) void EDCore::offer(Seek &k, int j, int o0, int o1, int o2)
{
  const Flight &q = flights[j];
  const double t = LATEST ? contact_at<DIM, GRAV, SHEARED>(k.p, k.p.t, k.p.x, k.p.v, q, o0, o1, o2, k.h)
                          : contact<DIM, GRAV, SHEARED>(k.p, q, o0, o1, o2, k.t);
  // two particles whose last collisions were with each other (same periodic image)
  // separate in free flight: relative motion is a straight line, they are no candidates
  // (tested only here, for a would-be candidate: the same outcome as skipping them)
  if (t < k.t && !separating(k.i, j, o0, o1, o2)) take(k, t, j, o0, o1, o2);
}

// a scan of i from its schedule's candidate so far, and the scan's best candidate back into it
inline EDCore::Seek EDCore::seek(int i) const
{
  const Schedule &s = schedules[i];
  return Seek{flights[i], s.ct, horizon_limit(s.ct - flights[i].t, s.ct), i, -1, {0, 0, 0}};
}

inline void EDCore::settle(const Seek &k)
{
  if (k.j < 0) return;
  Schedule &s = schedules[k.i];
  s.ct = k.t;
  s.cpartner = k.j;
  s.ctick = tick;
  s.coff[0] = k.o[0], s.coff[1] = k.o[1], s.coff[2] = k.o[2];
}

// The particles of the cell list headed by j0, reached at image (k0, k1, k2) (their image shifts
// that less their own images), as list entries into buf, offered in lanes whenever it fills;
// false: a shift beyond an entry's range (wide gathers the shifts' range bits)
template <bool LATEST, bool SHEARED>
inline __attribute__((always_inline)) bool EDCore::buffer_cell(Seek &k, int j0, int k0, int k1, int k2,
                                                                   ListEntry *buf, int &nb, int &wide)
{
  const CellImage *IM = images.data();
  for (int j = j0; j >= 0; j = IM[j].next) {
    const int o0 = k0 - IM[j].k[0], o1 = k1 - IM[j].k[1], o2 = k2 - IM[j].k[2];
    wide |= (o0 + 128) | (o1 + 128) | (o2 + 128);    // (bits above 8: out of range)
    buf[nb] = ListEntry{j, {(int8_t) o0, (int8_t) o1, (int8_t) o2}, 0};
    nb += j != k.i;
    if (nb == LANE_BUFFER) {
      if (wide & ~255) return false;
      offer_lanes<LATEST, false, SHEARED>(k, buf, nullptr, nb);
      nb = 0;
    }
  }
  return !(wide & ~255);
}

// offer_cells() in 3d without gravity: the candidates as list entries, offered in lanes (as
// many at a time as a buffer holds). False (k as it was): a shift beyond an entry's range.
template <bool LATEST, bool SHEARED>
bool EDCore::offer_cells_lanes(Seek &k, const int *first, int nfirst, const int8_t (*shift)[3], const int *of)
{
  const int i = k.i;
  const CellImage *IM = images.data();
  int nb = 0;
  if (!shift) {
    // (every cell at i's own image: the shifts follow from the images in the lanes)
    int buf[LANE_BUFFER];
    for (int f = 0; f < nfirst; f++)
      for (int j = first[f]; j >= 0; j = IM[j].next) {
        buf[nb] = j;
        nb += j != i;
        if (nb == LANE_BUFFER) {
          offer_lanes<LATEST, true, SHEARED>(k, nullptr, buf, nb);
          nb = 0;
        }
      }
    offer_lanes<LATEST, true, SHEARED>(k, nullptr, buf, nb);
    return true;
  }
  const int pk[3] = {images[i].k[0], images[i].k[1], images[i].k[2]};
  const Seek start = k;
  ListEntry buf[LANE_BUFFER];
  int wide = 0;
  for (int f = 0; f < nfirst; f++) {
    const int8_t *u = shift[of[f]];
    if (!buffer_cell<LATEST, SHEARED>(k, first[f], pk[0] + u[0], pk[1] + u[1], pk[2] + u[2], buf, nb, wide)) {
      k = start;
      return false;
    }
  }
  offer_lanes<LATEST, false, SHEARED>(k, buf, nullptr, nb);
  return true;
}

// scan_spans_t() in 3d without gravity, in lanes (as many candidates at a time as a buffer
// holds). A row at i's own y and z image whose cells do not wrap in x holds candidates at the
// image shifts their labels give (i's less theirs), as an unsheared scan's cells do: those go
// to the lanes as particles; the others (across a face, or wrapping) as list entries with their
// shifts. False (k as it was): a shift beyond an entry's range.
template <bool LATEST>
bool EDCore::offer_spans_lanes(Seek &k, const RowSpan *s, int n)
{
  const int i = k.i;
  const int *pk = images[i].k;
  const CellImage *IM = images.data();
  const Seek start = k;
  const long n0 = nc[0], lo = n0 * pk[0];
  int js[LANE_BUFFER], nj = 0;
  ListEntry buf[LANE_BUFFER];
  int nb = 0, wide = 0;
  // (the occupied cells of every row, in order, gathered first without a branch per cell, as
  // scan_t() does: of the rows at i's own image, whose candidates go to the lanes after the
  // other rows', and of the others, with their x image and row)
  int first[9 * 4], nf = 0, other[9 * 4], oq[9 * 4], orow[9 * 4], no = 0;
  for (int r = 0; r < n; r++) {
    const RowSpan &w = s[r];
    const int *row = head.data() + w.row;
    if (w.ky == pk[1] && w.kz == pk[2] && w.a0 >= lo && w.a1 < lo + n0) {
      for (long a = w.a0; a <= w.a1; a++) {
        const int j = row[a - lo];
        first[nf] = j;
        nf += j >= 0;
      }
      continue;
    }
    int q = w.q, u = w.u;
    for (long a = w.a0; a <= w.a1; a++) {
      const int j = row[u];
      other[no] = j, oq[no] = q, orow[no] = r;
      no += j >= 0;
      if (++u == n0) u = 0, q++;
    }
  }
  for (int f = 0; f < no; f++) {
    const RowSpan &w = s[orow[f]];
    if (!buffer_cell<LATEST, true>(k, other[f], oq[f], w.ky, w.kz, buf, nb, wide)) {
      k = start;
      return false;
    }
  }
  for (int f = 0; f < nf; f++)
    for (int j = first[f]; j >= 0; j = IM[j].next) {
      js[nj] = j;
      nj += j != i;
      if (nj == LANE_BUFFER) {
        offer_lanes<LATEST, true, true>(k, nullptr, js, nj);
        nj = 0;
      }
    }
  offer_lanes<LATEST, true, true>(k, nullptr, js, nj);
  offer_lanes<LATEST, false, true>(k, buf, nullptr, nb);
  return true;
}

// The candidates in gathered cells, in order: first[f] heads the list of a cell reached at the
// image shift shift[of[f]] (shift null: every shift 0)
template <int DIM, bool GRAV, bool LATEST, bool SHEARED>
inline __attribute__((always_inline)) void EDCore::offer_cells(Seek &k, const int *first, int nfirst,
                                                                   const int8_t (*shift)[3], const int *of)
{
  const int i = k.i;
  const int pk[3] = {images[i].k[0], images[i].k[1], images[i].k[2]};
  const CellImage *IM = images.data();
  if (DIM == 3 && !GRAV && lanes && offer_cells_lanes<LATEST, SHEARED>(k, first, nfirst, shift, of)) return;
  for (int f = 0; f < nfirst; f++) {
    const int8_t *u = shift ? shift[of[f]] : nullptr;
    const int k0 = u ? pk[0] + u[0] : pk[0], k1 = u ? pk[1] + u[1] : pk[1], k2 = u ? pk[2] + u[2] : pk[2];
    for (int j = first[f]; j >= 0; j = IM[j].next)
      if (j != i)
        offer<DIM, GRAV, LATEST, SHEARED>(k, j, k0 - IM[j].k[0], k1 - IM[j].k[1], DIM == 3 ? k2 - IM[j].k[2] : 0);
  }
}

// the candidates of that block of cells (block_inside) at i's own image (k: i's scan): the
// first particle of every occupied cell, in cell order, gathered without branches (which cells
// are empty is random: a branch per cell would be mispredicted often), then offered
template <int DIM, bool GRAV, bool FULL, bool LATEST, bool SHEARED>
inline __attribute__((always_inline)) void EDCore::scan_block(Seek &k, const int dlo[3], const int dhi[3])
{
  const int16_t *c = schedules[k.i].c;
  const int zlo = DIM == 3 ? (FULL ? -1 : dlo[2]) : 0, zhi = DIM == 3 ? (FULL ? 1 : dhi[2]) : 0;
  const int ylo = FULL ? -1 : dlo[1], yhi = FULL ? 1 : dhi[1];
  const int x0 = FULL ? -1 : dlo[0], x1 = FULL ? 1 : dhi[0];
  const int n0 = nc[0], n1 = nc[1];
  const int *base = head.data() + (c[2] * n1 + c[1]) * n0 + c[0];
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
  offer_cells<DIM, GRAV, LATEST, SHEARED>(k, first, nfirst, nullptr, nullptr);
}

// A sheared box, i in a row inside its band (the rows above and below of the same band, none
// across a y face): the rows lie over each other as in an unsheared box, and a block inside the
// grid is scanned as scan_t() scans it, the image shifts taken as contact_at's SHEARED takes
// them (the particles of a band may lie in different y images). False: not inside the grid.
template <int DIM, bool GRAV, bool FULL>
bool EDCore::scan_band_at(int i, const int dlo[3], const int dhi[3])
{
  if (!block_inside<DIM, FULL>(i, dlo, dhi)) return false;
  Seek k = seek(i);
  if (at_present(i))
    scan_block<DIM, GRAV, FULL, true, true>(k, dlo, dhi);
  else
    scan_block<DIM, GRAV, FULL, false, true>(k, dlo, dhi);
  settle(k);
  return true;
}

// A sheared box, i in a row at the edge of its band (ROW_EDGE_UP or ROW_EDGE_DOWN: one of its
// two boundaries is a band's, and the row across it lies in i's y image): the two rows of i's band as scan_block() takes them,
// and the 4 cells of the row across that sheared_spans() takes, from x offset f on, inside the
// grid all three, so that every cell is at i's own images and all are gathered alike, without
// the spans' wrapping. A crossing in x takes the leading cell of every row (as scan_sheared()),
// one in z the new layer, one in y within the band the row across. False: not so
// (scan_sheared()).
template <int DIM, bool GRAV, bool FULL>
bool EDCore::scan_edge_at(int i, const int dlo[3], const int dhi[3])
{
  const int16_t *c = schedules[i].c;
  const int n0 = nc[0], n1 = nc[1];
  const bool above = row_kind[c[1]] == ROW_EDGE_UP;
  const int ya = above ? 1 : -1;    // the row across
  const int f = above ? -shear_m - 2 : shear_m - 1;
  int x0 = -1, x1 = 1, a0 = f, a1 = f + 3, y0 = -1, y1 = 1, zlo = DIM == 3 ? -1 : 0, zhi = DIM == 3 ? 1 : 0;
  if (!FULL) {
    const bool xfull = dlo[0] == -1 && dhi[0] == 1, zfull = DIM == 2 || (dlo[2] == -1 && dhi[2] == 1);
    if (dlo[1] == dhi[1] && xfull && zfull) {
      if (dlo[1] != ya) return false;
      y0 = y1 = ya;
    } else if (dlo[1] != -1 || dhi[1] != 1) {
      return false;
    } else if (dlo[0] == dhi[0] && zfull) {
      x0 = x1 = dlo[0];
      a0 = a1 = dlo[0] > 0 ? f + 3 : f;
    } else if (DIM == 3 && dlo[2] == dhi[2] && xfull) {
      zlo = zhi = dlo[2];
    } else {
      return false;
    }
  }
  if (c[0] + x0 < 0 || c[0] + x1 >= n0 || c[0] + a0 < 0 || c[0] + a1 >= n0) return false;
  if (DIM == 3 && (c[2] + zlo < 0 || c[2] + zhi >= nc[2])) return false;
  const int *base = head.data() + (c[2] * n1 + c[1]) * n0 + c[0];
  int first[3 * 10], nfirst = 0;
  // (the first particles of the occupied cells of n cells from h on, without a branch per cell;
  // n known at compile time in a full scan)
  auto take = [&](const int *h, int n) __attribute__((always_inline)) {
#pragma GCC unroll 4
    for (int q = 0; q < n; q++) {
      const int j = h[q];
      first[nfirst] = j;
      nfirst += j >= 0;
    }
  };
#pragma GCC unroll 3
  for (int dz = zlo; dz <= zhi; dz++) {
    const int *h = base + dz * n1 * n0;
    if (FULL && ya > 0) {    // (rows in order of y, as scan_block() takes them)
      take(h - n0 - 1, 3), take(h - 1, 3), take(h + n0 + a0, 4);
    } else if (FULL) {
      take(h - n0 + a0, 4), take(h - 1, 3), take(h + n0 - 1, 3);
    } else {
      for (int dy = y0; dy <= y1; dy++)
        dy == ya ? take(h + dy * n0 + a0, a1 - a0 + 1) : take(h + dy * n0 + x0, x1 - x0 + 1);
    }
  }
  Seek k = seek(i);
  if (at_present(i))
    offer_cells<DIM, GRAV, true, true>(k, first, nfirst, nullptr, nullptr);
  else
    offer_cells<DIM, GRAV, false, true>(k, first, nfirst, nullptr, nullptr);
  settle(k);
  return true;
}

// the scans of a sheared box's rows that need no spans: inside a band or at its edge (row_kind)
template <int DIM, bool GRAV, bool FULL>
bool EDCore::scan_rows_at(int i, const int dlo[3], const int dhi[3])
{
  const int kind = row_kind[schedules[i].c[1]];
  return kind == ROW_INSIDE ? scan_band_at<DIM, GRAV, FULL>(i, dlo, dhi)
      : kind != ROW_SPANS   ? scan_edge_at<DIM, GRAV, FULL>(i, dlo, dhi)
                            : false;
}

// scan() for a dimension, with or without gravity, and for the whole neighbourhood (FULL: dlo,
// dhi = -1, +1 in every dimension) or not, known at compile time. In 2d nothing
// moves in z (v.z = 0, g.z = 0): the z terms of the relative motion vanish except the constant
// z distance, and every operation left is the one of the 3d arithmetic in the same order, so
// the contact times are the same numbers bit for bit.
template <int DIM, bool GRAV, bool FULL, bool LATEST>
void EDCore::scan_t(int i, const int dlo[3], const int dhi[3])
{
  Seek k = seek(i);
  const int pk[3] = {images[i].k[0], images[i].k[1], images[i].k[2]};
  const int16_t *c = schedules[i].c;
  const int zlo = DIM == 3 ? (FULL ? -1 : dlo[2]) : 0, zhi = DIM == 3 ? (FULL ? 1 : dhi[2]) : 0;
  const int ylo = FULL ? -1 : dlo[1], yhi = FULL ? 1 : dhi[1];
  const int x0 = FULL ? -1 : dlo[0], x1 = FULL ? 1 : dhi[0];
  if (block_inside<DIM, FULL>(i, dlo, dhi)) {    // (the usual case)
    scan_block<DIM, GRAV, FULL, LATEST, false>(k, dlo, dhi);
    settle(k);
    return;
  }
  if (FULL) {
    // at an edge of the grid: the cells as around() finds them, with their image shifts, and
    // the occupied ones gathered as above
    int cell[AROUND], first[AROUND], of[AROUND], nfirst = 0;
    int8_t shift[AROUND][3];
    const int ncell = around(i, cell, shift);
    for (int f = 0; f < ncell; f++) {
      const int j = head[cell[f]];
      first[nfirst] = j;
      of[nfirst] = f;
      nfirst += j >= 0;
    }
    offer_cells<DIM, GRAV, LATEST>(k, first, nfirst, shift, of);
    settle(k);
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
        for (int j = head[cell]; j >= 0; j = images[j].next)
          if (j != i) offer<DIM, GRAV, LATEST>(k, j, pk[0] + kx - images[j].k[0], pk[1] + ky - images[j].k[1],
                                                DIM == 3 ? pk[2] + kz - images[j].k[2] : 0);
      }
    }
  }
  settle(k);
}

// collision candidates of i among its listed neighbours (no gravity with lists)
template <int DIM, bool LATEST>
void EDCore::scan_list_t(int i)
{
  Seek k = seek(i);
  // i's list rebuild predicts it afresh, so no contact from then on need be found
  if (schedules[i].xt < k.t) {
    k.t = schedules[i].xt;
    k.h = horizon_limit(k.t - k.p.t, k.t);
  }
  const ListEntry *e = &list_entries[(size_t) i * LCAP];
  const int n = list_counts[i];
  if (DIM == 3 && lanes)
    offer_lanes<LATEST, false>(k, e, nullptr, n);
  else
    for (int m = 0; m < n; m++) offer<DIM, false, LATEST>(k, e[m].j, e[m].o[0], e[m].o[1], DIM == 3 ? e[m].o[2] : 0);
  settle(k);
}

void EDCore::scan_list(int i)
{
  const bool latest = at_present(i);
  if (opt.dim == 3)
    latest ? scan_list_t<3, true>(i) : scan_list_t<3, false>(i);
  else
    latest ? scan_list_t<2, true>(i) : scan_list_t<2, false>(i);
}

#if !GRANFRIC_LANES
// (without AVX2 lanes, see candidate_lanes.cpp: one candidate at a time)
bool EDCore::have_lanes()
{
  return false;
}

template <bool LATEST, bool CELLS, bool SHEARED>
void EDCore::offer_lanes(Seek &k, const ListEntry *e, const int *js, int n)
{
  const int *pk = images[k.i].k;
  for (int m = 0; m < n; m++) {
    const int j = CELLS ? js[m] : e[m].j;
    if (CELLS)
      offer<3, false, LATEST, SHEARED>(k, j, pk[0] - images[j].k[0], pk[1] - images[j].k[1], pk[2] - images[j].k[2]);
    else
      offer<3, false, LATEST, SHEARED>(k, j, e[m].o[0], e[m].o[1], e[m].o[2]);
  }
}
#endif

// Every pair that overlaps lies within lrad of each other's list centres, so with lists their
// entries name every candidate (each pair at each image it is listed at); with cells, the
// particles of the cells around each one (with fewer than 3 cells a cell is reached at two or
// three image shifts: each is another image of its particles).
long EventDriven::overlaps(double tol, long &key_i, long &key_j, double &depth) const
{
  long count = 0;
  depth = 0.0;
  key_i = key_j = -1;
  const int n = (int) flights.size();
  for (int i = 0; i < n; i++) {
    if (schedules[i].gone) continue;
    const Vec3 xi = pos(i, now);
    const long ki = key(i);
    // j at the image shift o (j's position + o P next to i), each pair once
    auto test = [&](int j, int o0, int o1, int o2) {
      const long kj = key(j);
      if (ki > kj || (ki == kj && i >= j)) return;
      const Vec3 r = xi - pos(j, now) - image(o0, o1, o2, now);
      const double sigma = flights[i].a + flights[j].a, lim = sigma * (1.0 - tol), r2 = norm2(r);
      // (the root only near contact: a pair is far when r2 exceeds lim^2 by more than the
      // roundings of the two ways of comparing)
      if (r2 > lim * lim * (1.0 + 1e-12) || !counted(ki <= kj ? i : j)) return;
      const double dist = std::sqrt(r2);
      if (dist < lim) {
        count++;
        if (sigma - dist > depth) {
          depth = sigma - dist;
          key_i = ki;
          key_j = kj;
        }
      }
    };
    const int *pk = images[i].k;
    if (lists) {
      const ListEntry *e = &list_entries[(size_t) i * LCAP];
      for (int m = 0; m < list_counts[i]; m++) test(e[m].j, e[m].o[0], e[m].o[1], e[m].o[2]);
      continue;
    }
    if (opt.shear) {
      RowSpan sp[9];
      const int ns = sheared_spans(i, sp);
      for (int r = 0; r < ns; r++)
        for (long a = sp[r].a0; a <= sp[r].a1; a++) {
          const long q = floor_div(a, nc[0]);
          const int cell = sp[r].row + (int) (a - q * nc[0]);
          for (int j = head[cell]; j >= 0; j = images[j].next)
            test(j, (int) q - images[j].k[0], sp[r].ky - images[j].k[1], sp[r].kz - images[j].k[2]);
        }
      continue;
    }
    int cell[AROUND];
    int8_t k[AROUND][3];
    const int ncell = around(i, cell, k);
    for (int f = 0; f < ncell; f++)
      for (int j = head[cell[f]]; j >= 0; j = images[j].next) {
        const int *qk = images[j].k;
        test(j, pk[0] + k[f][0] - qk[0], pk[1] + k[f][1] - qk[1], pk[2] + k[f][2] - qk[2]);
      }
  }
  return count;
}

// predict() for every particle at once, all at time now (start of a window, after a global
// event; no last partners): crossings and walls per particle, and each pair contact time
// computed once and offered to both partners (the same time: both see one number). With fewer
// than three cells in a dimension a neighbour cell can be reached at two image shifts, and every
// particle scans its neighbourhood itself, as predict() does.
// the contact time of i and j seen from i at the image shift o (j's position + o P), offered to
// both as their collision candidate (the canonical time of pair_time(): the one number offer()
// gives either of them)
void EDCore::offer_both(int i, int j, int o0, int o1, int o2)
{
  double t;
  if (opt.shear)
    t = opt.dim == 2 ? (has_gravity ? pair_time<2, true, true>(i, j, o0, o1, o2) : pair_time<2, false, true>(i, j, o0, o1, o2))
                     : (has_gravity ? pair_time<3, true, true>(i, j, o0, o1, o2) : pair_time<3, false, true>(i, j, o0, o1, o2));
  else if (opt.dim == 2)
    t = has_gravity ? pair_time<2, true>(i, j, o0, o1, o2) : pair_time<2, false>(i, j, o0, o1, o2);
  else
    t = has_gravity ? pair_time<3, true>(i, j, o0, o1, o2) : pair_time<3, false>(i, j, o0, o1, o2);
  Schedule &si = schedules[i], &sj = schedules[j];
  if (!(t < si.ct) && !(t < sj.ct)) return;
  if (separating(i, j, o0, o1, o2)) return;
  if (t < si.ct) {
    si.ct = t;
    si.cpartner = j;
    si.ctick = tick;
    si.coff[0] = o0, si.coff[1] = o1, si.coff[2] = o2;
  }
  if (t < sj.ct) {
    sj.ct = t;
    sj.cpartner = i;
    sj.ctick = tick;
    sj.coff[0] = -o0, sj.coff[1] = -o1, sj.coff[2] = -o2;
  }
}

void EDCore::predict_all()
{
  if (lists) {
    predict_all_lists();
    return;
  }
  const int n = (int) flights.size();
  bool half = !opt.shear;    // (with shear every particle scans its own neighbourhood)
  for (int d = 0; d < opt.dim; d++) half = half && nc[d] >= 3;
  for (int i = 0; i < n; i++) {
    if (schedules[i].gone) {
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
    if (schedules[i].gone) continue;
    const int *pk = images[i].k;
    const int16_t *c = schedules[i].c;
    for (int j = images[i].next; j >= 0; j = images[j].next) {    // the rest of its own cell
      const int *qk = images[j].k;
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
      for (int j = head[(u[2] * nc[1] + u[1]) * nc[0] + u[0]]; j >= 0; j = images[j].next) {
        const int *qk = images[j].k;
        offer_both(i, j, pk[0] + k[0] - qk[0], pk[1] + k[1] - qk[1], pk[2] + k[2] - qk[2]);
      }
    }
  }
}

}    // namespace granfric
