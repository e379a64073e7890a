// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the search for collision candidates (see event_driven.h): pair contact times against
// the particles of neighbouring cells or of a neighbour list, all at once at a start, and the
// overlap check.
#include "event_driven.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#endif

namespace granfric {

// collision candidates of i among the particles of the cells at offsets dlo..dhi (inclusive)
// around its cell; periodic images by integer offsets
void EventDriven::scan(int i, const int dlo[3], const int dhi[3])
{
  scan_in<false>(i, dlo, dhi);
}

void EventDriven::scan_full(int i)
{
  static const int lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};    // (in 2d z is not scanned)
  scan_in<true>(i, lo, hi);
}

template <bool FULL>
void EventDriven::scan_in(int i, const int dlo[3], const int dhi[3])
{
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

// A seeker at the present (as after its collision) is at least as late as every candidate
// (at_present()): its scan knows that at compile time (LATEST)
template <int DIM, bool GRAV, bool FULL>
inline void EventDriven::scan_at(int i, const int dlo[3], const int dhi[3])
{
  if (at_present(i))
    scan_t<DIM, GRAV, FULL, true>(i, dlo, dhi);
  else
    scan_t<DIM, GRAV, FULL, false>(i, dlo, dhi);
}

// The contact time of a particle in stored state p and one in stored state q at the image shift
// o (q's position + o P), canonical: from both stored states at tr = max(t_p, t_q) (the
// arithmetic of pos() and vel()), whoever predicts the pair and whenever; not before now.
// Usually p is the later one (it has just collided): its stored state is then its state at tr.
// Seen from q (shift -o) it is the same number: the differences change sign exactly. NEVER also
// for a contact that certainly comes at or after before (see pair_contact_time's horizon).
template <int DIM, bool GRAV>
inline __attribute__((always_inline)) double EventDriven::contact(const Hot &p, const Hot &q, int o0,
                                                                  int o1, int o2, double before) const
{
  if (q.t <= p.t) return contact_at<DIM, GRAV>(p, p.t, p.x, p.v, q, o0, o1, o2, horizon_limit(before - p.t, before));
  const double tr = q.t, dt = tr - p.t;
  const Vec3 g = opt.gravity;
  const Vec3 xa = flight_x(p.x, p.v, dt, g, GRAV), va = flight_v(p.v, dt, g);
  return contact_at<DIM, GRAV>(p, tr, xa, va, q, o0, o1, o2, horizon_limit(before - tr, before));
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

template <int DIM, bool GRAV>
inline __attribute__((always_inline)) double EventDriven::contact_at(const Hot &p, double tr, const Vec3 &a,
                                                                     const Vec3 &u, const Hot &q, int o0,
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
  if (o0 | o1 | o2) {
    const v2d s = {o0 * P.x, o1 * P.y};
    r -= s;
    if (DIM == 3) r2 -= o2 * P.z;
  }
  const v2d v = xy(u) - wxy;
  const double v2 = DIM == 3 ? u.z - w2 : 0.0;
  const v2d rv = r * v, rr = r * r;
  const double b = DIM == 3 ? (rv[0] + rv[1]) + r2 * v2 : rv[0] + rv[1];
  const double sigma = p.a + q.a;
  const double c = ((rr[0] + rr[1]) + r2 * r2) - sigma * sigma;
  const double tau = contact_root<DIM>(b, c, v[0], v[1], v2, h);
  if (tau == NEVER) return NEVER;
  return at_least_now(tr + tau);
}

template <int DIM, bool GRAV>
double EventDriven::pair_time(int i, int j, int o0, int o1, int o2) const
{
  return contact<DIM, GRAV>(H[i], H[j], o0, o1, o2, NEVER);
}

// One candidate j at the image shift o (j's position + o P): kept as the seeker's best when its
// contact time is the earliest so far. LATEST: the seeker's stored time is the latest (no
// candidate's is later), so that its state and horizon limit are the scan's for every one.
template <int DIM, bool GRAV, bool LATEST>
inline __attribute__((always_inline)) void EventDriven::offer(Seek &k, int j, int o0, int o1, int o2)
{
  const Hot &q = H[j];
  const double t = LATEST ? contact_at<DIM, GRAV>(k.p, k.p.t, k.p.x, k.p.v, q, o0, o1, o2, k.h)
                          : contact<DIM, GRAV>(k.p, q, o0, o1, o2, k.t);
  // two particles whose last collisions were with each other (same periodic image)
  // separate in free flight: relative motion is a straight line, they are no candidates
  // (tested only here, for a would-be candidate: the same outcome as skipping them)
  if (t < k.t && !separating(k.i, j, o0, o1, o2)) take(k, t, j, o0, o1, o2);
}

// j at the image shift o, at time t, the seeker's best candidate so far
inline void EventDriven::take(Seek &k, double t, int j, int o0, int o1, int o2)
{
  k.t = t;
  k.h = horizon_limit(t - k.p.t, t);
  k.j = j;
  k.o[0] = o0, k.o[1] = o1, k.o[2] = o2;
}

// a scan of i from its schedule's candidate so far, and the scan's best candidate back into it
inline EventDriven::Seek EventDriven::seek(int i) const
{
  const Sched &s = S[i];
  return Seek{H[i], s.ct, horizon_limit(s.ct - H[i].t, s.ct), i, -1, {0, 0, 0}};
}

inline void EventDriven::settle(const Seek &k)
{
  if (k.j < 0) return;
  Sched &s = S[k.i];
  s.ct = k.t;
  s.cpartner = k.j;
  s.ccount = C[k.j].ncoll;
  s.coff[0] = k.o[0], s.coff[1] = k.o[1], s.coff[2] = k.o[2];
}

// offer_cells() in 3d without gravity: the candidates as list entries, offered in lanes (as
// many at a time as a buffer holds). False (k as it was): a shift beyond an entry's range.
template <bool LATEST>
bool EventDriven::offer_cells_lanes(Seek &k, const int *first, int nfirst, const int8_t (*shift)[3], const int *of)
{
  const int i = k.i;
  const Image *IM = img.data();
  int nb = 0;
  if (!shift) {
    // (every cell at i's own image: the shifts follow from the images in the lanes)
    int buf[LANE_BUFFER];
    for (int f = 0; f < nfirst; f++)
      for (int j = first[f]; j >= 0; j = IM[j].next) {
        buf[nb] = j;
        nb += j != i;
        if (nb == LANE_BUFFER) {
          offer_lanes<LATEST, true>(k, nullptr, buf, nb);
          nb = 0;
        }
      }
    offer_lanes<LATEST, true>(k, nullptr, buf, nb);
    return true;
  }
  const int pk[3] = {img[i].k[0], img[i].k[1], img[i].k[2]};
  const Seek start = k;
  Entry buf[LANE_BUFFER];
  int wide = 0;
  for (int f = 0; f < nfirst; f++) {
    const int8_t *u = shift[of[f]];
    const int k0 = pk[0] + u[0], k1 = pk[1] + u[1], k2 = pk[2] + u[2];
    for (int j = first[f]; j >= 0; j = IM[j].next) {
      const int o0 = k0 - IM[j].k[0], o1 = k1 - IM[j].k[1], o2 = k2 - IM[j].k[2];
      wide |= (o0 + 128) | (o1 + 128) | (o2 + 128);    // (bits above 8: out of range)
      buf[nb] = Entry{j, {(int8_t) o0, (int8_t) o1, (int8_t) o2}, 0};
      nb += j != i;
      if (nb == LANE_BUFFER) {
        if (wide & ~255) break;
        offer_lanes<LATEST, false>(k, buf, nullptr, nb);
        nb = 0;
      }
    }
    if (wide & ~255) {
      k = start;
      return false;
    }
  }
  offer_lanes<LATEST, false>(k, buf, nullptr, nb);
  return true;
}

// The candidates in gathered cells, in order: first[f] heads the list of a cell reached at the
// image shift shift[of[f]] (shift null: every shift 0)
template <int DIM, bool GRAV, bool LATEST>
inline __attribute__((always_inline)) void EventDriven::offer_cells(Seek &k, const int *first, int nfirst,
                                                                   const int8_t (*shift)[3], const int *of)
{
  const int i = k.i;
  const int pk[3] = {img[i].k[0], img[i].k[1], img[i].k[2]};
  const Image *IM = img.data();
  if (DIM == 3 && !GRAV && lanes && offer_cells_lanes<LATEST>(k, first, nfirst, shift, of)) return;
  for (int f = 0; f < nfirst; f++) {
    const int8_t *u = shift ? shift[of[f]] : nullptr;
    const int k0 = u ? pk[0] + u[0] : pk[0], k1 = u ? pk[1] + u[1] : pk[1], k2 = u ? pk[2] + u[2] : pk[2];
    for (int j = first[f]; j >= 0; j = IM[j].next)
      if (j != i) offer<DIM, GRAV, LATEST>(k, j, k0 - IM[j].k[0], k1 - IM[j].k[1], DIM == 3 ? k2 - IM[j].k[2] : 0);
  }
}

// scan() for a dimension, with or without gravity, and for the whole neighbourhood (FULL: dlo,
// dhi = -1, +1 in every dimension) or not, known at compile time. In 2d nothing
// moves in z (v.z = 0, g.z = 0): the z terms of the relative motion vanish except the constant
// z distance, and every operation left is the one of the 3d arithmetic in the same order, so
// the contact times are the same numbers bit for bit.
template <int DIM, bool GRAV, bool FULL, bool LATEST>
void EventDriven::scan_t(int i, const int dlo[3], const int dhi[3])
{
  Seek k = seek(i);
  const int pk[3] = {img[i].k[0], img[i].k[1], img[i].k[2]};
  const int16_t *c = S[i].c;
  const int zlo = DIM == 3 ? (FULL ? -1 : dlo[2]) : 0, zhi = DIM == 3 ? (FULL ? 1 : dhi[2]) : 0;
  const int ylo = FULL ? -1 : dlo[1], yhi = FULL ? 1 : dhi[1];
  const int x0 = FULL ? -1 : dlo[0], x1 = FULL ? 1 : dhi[0];
  // the usual case: the block of cells lies inside the grid (no wrapping, no edges)
  bool inside = c[0] + x0 >= 0 && c[0] + x1 < nc[0] && c[1] + ylo >= 0 && c[1] + yhi < nc[1];
  if (DIM == 3) inside = inside && c[2] + zlo >= 0 && c[2] + zhi < nc[2];
  if (inside) {
    const int n0 = nc[0], n1 = nc[1];
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
    offer_cells<DIM, GRAV, LATEST>(k, first, nfirst, nullptr, nullptr);
    settle(k);
    return;
  }
  if (FULL) {
    // at an edge of the grid: the cells as around() finds them, with their image shifts, and
    // the occupied ones gathered as above
    int cell[27], first[27], of[27], nfirst = 0;
    int8_t shift[27][3];
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
        for (int j = head[cell]; j >= 0; j = img[j].next)
          if (j != i) offer<DIM, GRAV, LATEST>(k, j, pk[0] + kx - img[j].k[0], pk[1] + ky - img[j].k[1],
                                      DIM == 3 ? pk[2] + kz - img[j].k[2] : 0);
      }
    }
  }
  settle(k);
}

// collision candidates of i among its listed neighbours (no gravity with lists)
template <int DIM, bool LATEST>
void EventDriven::scan_list_t(int i)
{
  Seek k = seek(i);
  // i's list rebuild predicts it afresh, so no contact from then on need be found
  if (S[i].xt < k.t) {
    k.t = S[i].xt;
    k.h = horizon_limit(k.t - k.p.t, k.t);
  }
  const Entry *e = &NB[(size_t) i * LCAP];
  const int n = NN[i];
  if (DIM == 3 && lanes)
    offer_lanes<LATEST, false>(k, e, nullptr, n);
  else
    for (int m = 0; m < n; m++) offer<DIM, false, LATEST>(k, e[m].j, e[m].o[0], e[m].o[1], DIM == 3 ? e[m].o[2] : 0);
  settle(k);
}

void EventDriven::scan_list(int i)
{
  const bool latest = at_present(i);
  if (opt.dim == 3)
    latest ? scan_list_t<3, true>(i) : scan_list_t<3, false>(i);
  else
    latest ? scan_list_t<2, true>(i) : scan_list_t<2, false>(i);
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
bool EventDriven::have_lanes()
{
  return __builtin_cpu_supports("avx2");
}

// contact_root()'s horizon test in four lanes, from b, c, w2 and -b, -disc, with the horizon
// limits h: bit l set where lane l's contact may come before h
__attribute__((target("avx2"), always_inline)) static inline int within_lanes(__m256d b, __m256d c, __m256d w2,
                                                                             __m256d nb, __m256d nd, __m256d h)
{
  const __m256d wh = _mm256_mul_pd(w2, h);
  const __m256d fh = _mm256_add_pd(c, _mm256_mul_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(2.0), b), wh), h));
  const __m256d mx = _mm256_max_pd(_mm256_max_pd(_mm256_min_pd(_mm256_sub_pd(nb, wh), fh), nd), b);
  return _mm256_movemask_pd(_mm256_cmp_pd(mx, _mm256_setzero_pd(), _CMP_LE_OQ));
}

// horizon_limit(before - tr, before) in four lanes
__attribute__((target("avx2"), always_inline)) static inline __m256d horizon_lanes(double before, __m256d tr)
{
  const __m256d ahead = _mm256_sub_pd(_mm256_set1_pd(before), tr);
  return _mm256_add_pd(_mm256_mul_pd(ahead, _mm256_set1_pd(1.0 + 1e-6)), _mm256_set1_pd(std::fabs(before) * 1e-15));
}

// offer() for the n candidates e[0..n) (3d, no gravity), four at a time. Each AVX2 lane does
// what contact() and contact_root() do up to the horizon test: the same operations on the same
// numbers in the same order (no contraction: AVX2 without FMA; std::max(x, y) is max_pd(y, x),
// std::min(x, y) min_pd(y, x), down to NaN; a blend where contact() branches), so a lane passes
// exactly where the scalar test would at the same horizon. The passing lanes' contact times
// follow in turn from the lanes' b, c and discriminant, as contact_root() computes them; when
// one becomes the best, the horizon shrinks and the lanes after it are tested again. The
// outcome is that of offer() for each candidate in turn, in every bit.
template <bool LATEST, bool CELLS>
__attribute__((target("avx2"))) void EventDriven::offer_lanes(Seek &k, const Entry *e, const int *js, int n)
{
  const int i = k.i;
  const Hot *Q = H.data();
  const Image *IM = img.data();
  const int *pk = img[i].k;
  const __m256d pt = _mm256_set1_pd(k.p.t), pa = _mm256_set1_pd(k.p.a);
  const __m256d px = _mm256_set1_pd(k.p.x.x), py = _mm256_set1_pd(k.p.x.y), pz = _mm256_set1_pd(k.p.x.z);
  const __m256d pvx = _mm256_set1_pd(k.p.v.x), pvy = _mm256_set1_pd(k.p.v.y), pvz = _mm256_set1_pd(k.p.v.z);
  const __m256d neg = _mm256_set1_pd(-0.0), zero = _mm256_setzero_pd();
  const __m256d Px = _mm256_set1_pd(P.x), Py = _mm256_set1_pd(P.y), Pz = _mm256_set1_pd(P.z);
  for (int m = 0; m < n; m += 4) {
    const int live = n - m < 4 ? n - m : 4;    // (lanes past the end read i itself)
    const Entry *g = CELLS ? nullptr : e + m;
    int jl[4];
    for (int l = 0; l < 4; l++) jl[l] = l < live ? (CELLS ? js[m + l] : g[l].j) : i;
    const Hot *q[4] = {Q + jl[0], Q + jl[1], Q + jl[2], Q + jl[3]};
    // lane l: x y z vx of q[l] (r) and vy vz t a (s), transposed into one vector per field
    const __m256d r0 = _mm256_loadu_pd(&q[0]->x.x), r1 = _mm256_loadu_pd(&q[1]->x.x);
    const __m256d r2 = _mm256_loadu_pd(&q[2]->x.x), r3 = _mm256_loadu_pd(&q[3]->x.x);
    const __m256d s0 = _mm256_loadu_pd(&q[0]->v.y), s1 = _mm256_loadu_pd(&q[1]->v.y);
    const __m256d s2 = _mm256_loadu_pd(&q[2]->v.y), s3 = _mm256_loadu_pd(&q[3]->v.y);
    const __m256d ra = _mm256_unpacklo_pd(r0, r1), rb = _mm256_unpackhi_pd(r0, r1);
    const __m256d rc = _mm256_unpacklo_pd(r2, r3), rd = _mm256_unpackhi_pd(r2, r3);
    const __m256d sa = _mm256_unpacklo_pd(s0, s1), sb = _mm256_unpackhi_pd(s0, s1);
    const __m256d sc = _mm256_unpacklo_pd(s2, s3), sd = _mm256_unpackhi_pd(s2, s3);
    const __m256d X = _mm256_permute2f128_pd(ra, rc, 0x20), Z = _mm256_permute2f128_pd(ra, rc, 0x31);
    const __m256d Y = _mm256_permute2f128_pd(rb, rd, 0x20), VX = _mm256_permute2f128_pd(rb, rd, 0x31);
    const __m256d VY = _mm256_permute2f128_pd(sa, sc, 0x20), T = _mm256_permute2f128_pd(sa, sc, 0x31);
    const __m256d VZ = _mm256_permute2f128_pd(sb, sd, 0x20), A = _mm256_permute2f128_pd(sb, sd, 0x31);
    // the seeker at tr = the later of the two stored times (contact())
    __m256d tr = pt, ax = px, ay = py, az = pz, ux = pvx, uy = pvy, uz = pvz;
    if (!LATEST) {
      const __m256d later = _mm256_cmp_pd(T, pt, _CMP_NLE_UQ), dt = _mm256_sub_pd(T, pt);
      const Vec3 gv = opt.gravity;    // (zero: flight_v's arithmetic)
      tr = _mm256_blendv_pd(pt, T, later);
      ax = _mm256_blendv_pd(px, _mm256_add_pd(px, _mm256_mul_pd(dt, pvx)), later);
      ay = _mm256_blendv_pd(py, _mm256_add_pd(py, _mm256_mul_pd(dt, pvy)), later);
      az = _mm256_blendv_pd(pz, _mm256_add_pd(pz, _mm256_mul_pd(dt, pvz)), later);
      ux = _mm256_blendv_pd(pvx, _mm256_add_pd(pvx, _mm256_mul_pd(dt, _mm256_set1_pd(gv.x))), later);
      uy = _mm256_blendv_pd(pvy, _mm256_add_pd(pvy, _mm256_mul_pd(dt, _mm256_set1_pd(gv.y))), later);
      uz = _mm256_blendv_pd(pvz, _mm256_add_pd(pvz, _mm256_mul_pd(dt, _mm256_set1_pd(gv.z))), later);
    }
    // q at tr, and the separation
    const __m256d dq = _mm256_sub_pd(tr, T);
    __m256d rx = _mm256_sub_pd(ax, _mm256_add_pd(X, _mm256_mul_pd(dq, VX)));
    __m256d ry = _mm256_sub_pd(ay, _mm256_add_pd(Y, _mm256_mul_pd(dq, VY)));
    __m256d rz = _mm256_sub_pd(az, _mm256_add_pd(Z, _mm256_mul_pd(dq, VZ)));
    // image shifts as doubles (subtracting 0 P where a lane has none leaves it as it is; lanes
    // past the end are not used): a list entry's shift bytes, or i's image less the candidate's
    __m128i o0, o1, o2;
    if (CELLS) {
      const __m128i k0 = _mm_loadu_si128((const __m128i *) IM[jl[0]].k), k1 = _mm_loadu_si128((const __m128i *) IM[jl[1]].k);
      const __m128i k2 = _mm_loadu_si128((const __m128i *) IM[jl[2]].k), k3 = _mm_loadu_si128((const __m128i *) IM[jl[3]].k);
      const __m128i ka = _mm_unpacklo_epi32(k0, k1), kb = _mm_unpacklo_epi32(k2, k3);
      const __m128i kc = _mm_unpackhi_epi32(k0, k1), kd = _mm_unpackhi_epi32(k2, k3);
      o0 = _mm_sub_epi32(_mm_set1_epi32(pk[0]), _mm_unpacklo_epi64(ka, kb));
      o1 = _mm_sub_epi32(_mm_set1_epi32(pk[1]), _mm_unpackhi_epi64(ka, kb));
      o2 = _mm_sub_epi32(_mm_set1_epi32(pk[2]), _mm_unpacklo_epi64(kc, kd));
    } else {
      const __m128i sh = _mm256_castsi256_si128(
          _mm256_permutevar8x32_epi32(_mm256_loadu_si256((const __m256i *) g), _mm256_setr_epi32(1, 3, 5, 7, 1, 3, 5, 7)));
      o0 = _mm_srai_epi32(_mm_slli_epi32(sh, 24), 24);
      o1 = _mm_srai_epi32(_mm_slli_epi32(sh, 16), 24);
      o2 = _mm_srai_epi32(_mm_slli_epi32(sh, 8), 24);
    }
    rx = _mm256_sub_pd(rx, _mm256_mul_pd(_mm256_cvtepi32_pd(o0), Px));
    ry = _mm256_sub_pd(ry, _mm256_mul_pd(_mm256_cvtepi32_pd(o1), Py));
    rz = _mm256_sub_pd(rz, _mm256_mul_pd(_mm256_cvtepi32_pd(o2), Pz));
    const __m256d vx = _mm256_sub_pd(ux, VX), vy = _mm256_sub_pd(uy, VY), vz = _mm256_sub_pd(uz, VZ);
    const __m256d b = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(rx, vx), _mm256_mul_pd(ry, vy)), _mm256_mul_pd(rz, vz));
    const __m256d sig = _mm256_add_pd(pa, A);
    const __m256d rr = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(rx, rx), _mm256_mul_pd(ry, ry)), _mm256_mul_pd(rz, rz));
    const __m256d c = _mm256_sub_pd(rr, _mm256_mul_pd(sig, sig));
    const __m256d w2 = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(vx, vx), _mm256_mul_pd(vy, vy)), _mm256_mul_pd(vz, vz));
    const __m256d disc = _mm256_sub_pd(_mm256_mul_pd(b, b), _mm256_mul_pd(w2, c));
    // contact_root()'s tests: the horizon, then b < 0 and disc >= 0
    const __m256d nb = _mm256_xor_pd(b, neg), nd = _mm256_xor_pd(disc, neg);
    const int real = _mm256_movemask_pd(_mm256_and_pd(_mm256_cmp_pd(b, zero, _CMP_LT_OQ),
                                                      _mm256_cmp_pd(disc, zero, _CMP_GE_OQ))) & ((1 << live) - 1);
    int pass = real & within_lanes(b, c, w2, nb, nd, LATEST ? _mm256_set1_pd(k.h) : horizon_lanes(k.t, tr));
    if (!pass) continue;
    double bl[4], cl[4], dl[4], tl[4];
    _mm256_storeu_pd(bl, b);
    _mm256_storeu_pd(cl, c);
    _mm256_storeu_pd(dl, disc);
    _mm256_storeu_pd(tl, tr);
    while (pass) {
      const int l = __builtin_ctz(pass);
      pass &= pass - 1;
      const double tau = cl[l] / (-bl[l] + std::sqrt(dl[l]));
      const double t = at_least_now(tl[l] + (tau > 0.0 ? tau : 0.0));
      const int j = jl[l];
      const int o0 = CELLS ? pk[0] - IM[j].k[0] : g[l].o[0], o1 = CELLS ? pk[1] - IM[j].k[1] : g[l].o[1];
      const int o2 = CELLS ? pk[2] - IM[j].k[2] : g[l].o[2];
      if (t < k.t && !separating(i, j, o0, o1, o2)) {
        take(k, t, j, o0, o1, o2);
        // the lanes after l at the new horizon
        pass &= within_lanes(b, c, w2, nb, nd, LATEST ? _mm256_set1_pd(k.h) : horizon_lanes(k.t, tr));
      }
    }
  }
}
#else
bool EventDriven::have_lanes()
{
  return false;
}

template <bool LATEST, bool CELLS>
void EventDriven::offer_lanes(Seek &k, const Entry *e, const int *js, int n)
{
  const int *pk = img[k.i].k;
  for (int m = 0; m < n; m++) {
    const int j = CELLS ? js[m] : e[m].j;
    if (CELLS)
      offer<3, false, LATEST>(k, j, pk[0] - img[j].k[0], pk[1] - img[j].k[1], pk[2] - img[j].k[2]);
    else
      offer<3, false, LATEST>(k, j, e[m].o[0], e[m].o[1], e[m].o[2]);
  }
}
#endif

long EventDriven::overlaps(double tol, long &key_i, long &key_j, double &depth) const
{
  long count = 0;
  depth = 0.0;
  key_i = key_j = -1;
  const int n = (int) H.size();
  for (int i = 0; i < n; i++) {
    if (S[i].gone) continue;
    const Vec3 xi = pos(i, now);
    const long ki = key(i);
    const int *pk = img[i].k;
    // (with fewer than 3 cells a cell is reached at two or three image shifts: each is another
    // image of its particles)
    int cell[27];
    int8_t k[27][3];
    const int ncell = around(i, cell, k);
    for (int f = 0; f < ncell; f++)
      for (int j = head[cell[f]]; j >= 0; j = img[j].next) {
        if (j == i) continue;
        const long kj = key(j);
        if (ki > kj || (ki == kj && i > j)) continue;    // each pair once
        const int *qk = img[j].k;
        const Vec3 shift = periods(pk[0] + k[f][0] - qk[0], pk[1] + k[f][1] - qk[1], pk[2] + k[f][2] - qk[2]);
        const Vec3 r = xi - pos(j, now) - shift;
        const double sigma = H[i].a + H[j].a, lim = sigma * (1.0 - tol), r2 = norm2(r);
        // (the root only near contact: a pair is far when r2 exceeds lim^2 by more than the
        // roundings of the two ways of comparing)
        if (r2 > lim * lim * (1.0 + 1e-12) || !counted(ki <= kj ? i : j)) continue;
        const double dist = std::sqrt(r2);
        if (dist < lim) {
          count++;
          if (sigma - dist > depth) {
            depth = sigma - dist;
            key_i = ki;
            key_j = kj;
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
// the contact time of i and j seen from i at the image shift o (j's position + o P), offered to
// both as their collision candidate (the canonical time of pair_time(): the one number offer()
// gives either of them)
void EventDriven::offer_both(int i, int j, int o0, int o1, int o2)
{
  double t;
  if (opt.dim == 2)
    t = has_gravity ? pair_time<2, true>(i, j, o0, o1, o2) : pair_time<2, false>(i, j, o0, o1, o2);
  else
    t = has_gravity ? pair_time<3, true>(i, j, o0, o1, o2) : pair_time<3, false>(i, j, o0, o1, o2);
  Sched &si = S[i], &sj = S[j];
  if (!(t < si.ct) && !(t < sj.ct)) return;
  if (separating(i, j, o0, o1, o2)) return;
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

}    // namespace granfric
