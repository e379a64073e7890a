// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the collision candidates of a scan (see candidate_search.cpp) tested
// four at a time in AVX2 lanes, in 3d without gravity, in a sheared box too. Compiled for AVX2 function by function
// (the rest of the core stays plain x86-64) and chosen when the program runs (have_lanes()).
//
// Each lane does what contact() and contact_root() do up to the horizon test: the same
// operations on the same numbers in the same order (AVX2 without fused multiply-adds;
// std::max(x, y) is max_pd(y, x) and std::min(x, y) min_pd(y, x), down to NaN; a blend where
// contact() branches), so a lane passes exactly where the one-at-a-time test would at the same
// horizon. The passing lanes' contact times follow in turn from the lanes' b, c and
// discriminant, as contact_root() computes them; when one becomes the best, the horizon shrinks
// and the lanes after it are tested again. The outcome is that of offer() for each candidate in
// turn, in every bit (Lanes.SameBitsAsOneAtATime).
#include "event_driven.h"

#if GRANFRIC_LANES
#include <immintrin.h>

#include <cmath>

namespace granfric {

#define LANES __attribute__((target("avx2"), always_inline)) static inline

namespace {

// the eight doubles of four particles' flight records, one vector per field (lane l: record l)
struct Fields {
  __m256d x, y, z, vx, vy, vz, t, a;
};

// rec[l]: a record's first double (x y z, vx vy vz, t, a)
LANES Fields transpose(const double *const rec[4])
{
  const __m256d r0 = _mm256_loadu_pd(rec[0]), r1 = _mm256_loadu_pd(rec[1]);
  const __m256d r2 = _mm256_loadu_pd(rec[2]), r3 = _mm256_loadu_pd(rec[3]);
  const __m256d s0 = _mm256_loadu_pd(rec[0] + 4), s1 = _mm256_loadu_pd(rec[1] + 4);
  const __m256d s2 = _mm256_loadu_pd(rec[2] + 4), s3 = _mm256_loadu_pd(rec[3] + 4);
  const __m256d ra = _mm256_unpacklo_pd(r0, r1), rb = _mm256_unpackhi_pd(r0, r1);
  const __m256d rc = _mm256_unpacklo_pd(r2, r3), rd = _mm256_unpackhi_pd(r2, r3);
  const __m256d sa = _mm256_unpacklo_pd(s0, s1), sb = _mm256_unpackhi_pd(s0, s1);
  const __m256d sc = _mm256_unpacklo_pd(s2, s3), sd = _mm256_unpackhi_pd(s2, s3);
  return Fields{_mm256_permute2f128_pd(ra, rc, 0x20), _mm256_permute2f128_pd(rb, rd, 0x20),
                _mm256_permute2f128_pd(ra, rc, 0x31), _mm256_permute2f128_pd(rb, rd, 0x31),
                _mm256_permute2f128_pd(sa, sc, 0x20), _mm256_permute2f128_pd(sb, sd, 0x20),
                _mm256_permute2f128_pd(sa, sc, 0x31), _mm256_permute2f128_pd(sb, sd, 0x31)};
}

// image shifts of four candidates, one 32-bit vector per dimension
struct Shifts {
  __m128i o0, o1, o2;
};

// i's image pk less each candidate's (k[l]: the candidate's three image numbers)
LANES Shifts image_shifts(const int *pk, const int *const k[4])
{
  const __m128i k0 = _mm_loadu_si128((const __m128i *) k[0]), k1 = _mm_loadu_si128((const __m128i *) k[1]);
  const __m128i k2 = _mm_loadu_si128((const __m128i *) k[2]), k3 = _mm_loadu_si128((const __m128i *) k[3]);
  const __m128i ka = _mm_unpacklo_epi32(k0, k1), kb = _mm_unpacklo_epi32(k2, k3);
  const __m128i kc = _mm_unpackhi_epi32(k0, k1), kd = _mm_unpackhi_epi32(k2, k3);
  return Shifts{_mm_sub_epi32(_mm_set1_epi32(pk[0]), _mm_unpacklo_epi64(ka, kb)),
                _mm_sub_epi32(_mm_set1_epi32(pk[1]), _mm_unpackhi_epi64(ka, kb)),
                _mm_sub_epi32(_mm_set1_epi32(pk[2]), _mm_unpacklo_epi64(kc, kd))};
}

// the shift bytes of four 8-byte list entries (index, three signed bytes, one more byte), one
// 32-bit lane per entry
LANES __m128i entry_shift_bytes(const void *entries)
{
  return _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(_mm256_loadu_si256((const __m256i *) entries),
                                                            _mm256_setr_epi32(1, 3, 5, 7, 1, 3, 5, 7)));
}

// the shifts of entry_shift_bytes()
LANES Shifts entry_shifts(__m128i sh)
{
  return Shifts{_mm_srai_epi32(_mm_slli_epi32(sh, 24), 24), _mm_srai_epi32(_mm_slli_epi32(sh, 16), 24),
                _mm_srai_epi32(_mm_slli_epi32(sh, 8), 24)};
}

// whether any of the first live lanes has a shift (bits: the bits of a lane that hold shifts)
LANES bool shifted(__m128i sh, int bits, int live)
{
  const __m128i in = _mm_cmpgt_epi32(_mm_set1_epi32(live), _mm_setr_epi32(0, 1, 2, 3));
  return !_mm_testz_si128(sh, _mm_and_si128(in, _mm_set1_epi32(bits)));
}

// contact_root()'s horizon test from b, c, w2 and -b, -disc, with the horizon limits h: bit l
// set where lane l's contact may come before h
LANES int within(__m256d b, __m256d c, __m256d w2, __m256d nb, __m256d nd, __m256d h)
{
  const __m256d wh = _mm256_mul_pd(w2, h);
  const __m256d fh = _mm256_add_pd(c, _mm256_mul_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(2.0), b), wh), h));
  const __m256d mx = _mm256_max_pd(_mm256_max_pd(_mm256_min_pd(_mm256_sub_pd(nb, wh), fh), nd), b);
  return _mm256_movemask_pd(_mm256_cmp_pd(mx, _mm256_setzero_pd(), _CMP_LE_OQ));
}

// horizon_limit(before - tr, before)
LANES __m256d horizon(double before, __m256d tr)
{
  const __m256d ahead = _mm256_sub_pd(_mm256_set1_pd(before), tr);
  return _mm256_add_pd(_mm256_mul_pd(ahead, _mm256_set1_pd(1.0 + 1e-6)), _mm256_set1_pd(std::fabs(before) * 1e-15));
}

LANES __m256d dot4(__m256d ax, __m256d ay, __m256d az, __m256d bx, __m256d by, __m256d bz)
{
  return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(ax, bx), _mm256_mul_pd(ay, by)), _mm256_mul_pd(az, bz));
}

// a + dt u, or a where keep is set (flight_x, flight_v without gravity terms of their own)
LANES __m256d ahead_by(__m256d a, __m256d dt, __m256d u, __m256d keep)
{
  return _mm256_blendv_pd(_mm256_add_pd(a, _mm256_mul_pd(dt, u)), a, keep);
}

}    // namespace

bool EDCore::have_lanes()
{
  return __builtin_cpu_supports("avx2");
}

template <bool LATEST, bool CELLS, bool SHEARED>
__attribute__((target("avx2"))) void EDCore::offer_lanes(Seek &k, const ListEntry *e, const int *js, int n)
{
  const int i = k.i;
  const int *pk = images[i].k;
  const Vec3 g = opt.gravity;    // (zero: flight_v's arithmetic)
  const __m256d pt = _mm256_set1_pd(k.p.t), pa = _mm256_set1_pd(k.p.a), neg = _mm256_set1_pd(-0.0);
  for (int m = 0; m < n; m += 4) {
    const int live = n - m < 4 ? n - m : 4;    // (lanes past the end read i itself)
    const ListEntry *el = CELLS ? nullptr : e + m;
    int jl[4];
    for (int l = 0; l < 4; l++) jl[l] = l < live ? (CELLS ? js[m + l] : el[l].j) : i;
    const double *rec[4] = {&flights[jl[0]].x.x, &flights[jl[1]].x.x, &flights[jl[2]].x.x,
                            &flights[jl[3]].x.x};
    const Fields q = transpose(rec);
    // the seeker at tr, the later of the two stored times (contact())
    const __m256d keep = LATEST ? _mm256_set1_pd(-0.0) : _mm256_cmp_pd(q.t, pt, _CMP_LE_OQ);
    const __m256d tr = LATEST ? pt : _mm256_blendv_pd(q.t, pt, keep), dt = _mm256_sub_pd(q.t, pt);
    const __m256d ax = ahead_by(_mm256_set1_pd(k.p.x.x), dt, _mm256_set1_pd(k.p.v.x), keep);
    const __m256d ay = ahead_by(_mm256_set1_pd(k.p.x.y), dt, _mm256_set1_pd(k.p.v.y), keep);
    const __m256d az = ahead_by(_mm256_set1_pd(k.p.x.z), dt, _mm256_set1_pd(k.p.v.z), keep);
    const __m256d ux = ahead_by(_mm256_set1_pd(k.p.v.x), dt, _mm256_set1_pd(g.x), keep);
    const __m256d uy = ahead_by(_mm256_set1_pd(k.p.v.y), dt, _mm256_set1_pd(g.y), keep);
    const __m256d uz = ahead_by(_mm256_set1_pd(k.p.v.z), dt, _mm256_set1_pd(g.z), keep);
    // q at tr; the separation less the image shift
    const __m256d dq = _mm256_sub_pd(tr, q.t);
    __m256d rx = _mm256_sub_pd(ax, _mm256_add_pd(q.x, _mm256_mul_pd(dq, q.vx)));
    __m256d ry = _mm256_sub_pd(ay, _mm256_add_pd(q.y, _mm256_mul_pd(dq, q.vy)));
    __m256d rz = _mm256_sub_pd(az, _mm256_add_pd(q.z, _mm256_mul_pd(dq, q.vz)));
    // (mostly every lane has none, and x - 0 P is x: then nothing to subtract)
    Shifts o;
    bool any;
    if (CELLS) {
      const int *kl[4] = {images[jl[0]].k, images[jl[1]].k, images[jl[2]].k, images[jl[3]].k};
      o = image_shifts(pk, kl);
      any = shifted(_mm_or_si128(_mm_or_si128(o.o0, o.o1), o.o2), -1, live);
    } else {
      const __m128i sh = entry_shift_bytes(el);
      any = shifted(sh, 0x00ffffff, live);
      if (any || SHEARED) o = entry_shifts(sh);
    }
    if (any) {
      rx = _mm256_sub_pd(rx, _mm256_mul_pd(_mm256_cvtepi32_pd(o.o0), _mm256_set1_pd(P.x)));
      ry = _mm256_sub_pd(ry, _mm256_mul_pd(_mm256_cvtepi32_pd(o.o1), _mm256_set1_pd(P.y)));
      rz = _mm256_sub_pd(rz, _mm256_mul_pd(_mm256_cvtepi32_pd(o.o2), _mm256_set1_pd(P.z)));
      if (SHEARED) {    // (contact_at: the image o1 periods up, o1 s(tr) further in x)
        const __m256d s = _mm256_add_pd(_mm256_set1_pd(shear_s0), _mm256_mul_pd(_mm256_set1_pd(opt.shear_rate), tr));
        rx = _mm256_sub_pd(rx, _mm256_mul_pd(_mm256_cvtepi32_pd(o.o1), s));
      }
    }
    __m256d vx = _mm256_sub_pd(ux, q.vx);
    const __m256d vy = _mm256_sub_pd(uy, q.vy), vz = _mm256_sub_pd(uz, q.vz);
    if (SHEARED) vx = _mm256_sub_pd(vx, _mm256_mul_pd(_mm256_cvtepi32_pd(o.o1), _mm256_set1_pd(opt.shear_rate)));
    const __m256d b = dot4(rx, ry, rz, vx, vy, vz), sig = _mm256_add_pd(pa, q.a);
    const __m256d c = _mm256_sub_pd(dot4(rx, ry, rz, rx, ry, rz), _mm256_mul_pd(sig, sig));
    const __m256d w2 = dot4(vx, vy, vz, vx, vy, vz);
    const __m256d disc = _mm256_sub_pd(_mm256_mul_pd(b, b), _mm256_mul_pd(w2, c));
    // contact_root()'s tests: the horizon, then b < 0 and disc >= 0
    const __m256d nb = _mm256_xor_pd(b, neg), nd = _mm256_xor_pd(disc, neg), zero = _mm256_setzero_pd();
    const int real = _mm256_movemask_pd(_mm256_and_pd(_mm256_cmp_pd(b, zero, _CMP_LT_OQ),
                                                      _mm256_cmp_pd(disc, zero, _CMP_GE_OQ))) & ((1 << live) - 1);
    int pass = real & within(b, c, w2, nb, nd, LATEST ? _mm256_set1_pd(k.h) : horizon(k.t, tr));
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
      const int o0 = CELLS ? pk[0] - images[j].k[0] : el[l].o[0],
                o1 = CELLS ? pk[1] - images[j].k[1] : el[l].o[1];
      const int o2 = CELLS ? pk[2] - images[j].k[2] : el[l].o[2];
      if (t < k.t && !separating(i, j, o0, o1, o2)) {
        take(k, t, j, o0, o1, o2);
        // the lanes after l at the new horizon
        pass &= within(b, c, w2, nb, nd, LATEST ? _mm256_set1_pd(k.h) : horizon(k.t, tr));
      }
    }
  }
}

template void EDCore::offer_lanes<true, true>(Seek &, const ListEntry *, const int *, int);
template void EDCore::offer_lanes<true, false>(Seek &, const ListEntry *, const int *, int);
template void EDCore::offer_lanes<false, true>(Seek &, const ListEntry *, const int *, int);
template void EDCore::offer_lanes<false, false>(Seek &, const ListEntry *, const int *, int);
template void EDCore::offer_lanes<true, false, true>(Seek &, const ListEntry *, const int *, int);
template void EDCore::offer_lanes<false, false, true>(Seek &, const ListEntry *, const int *, int);
template void EDCore::offer_lanes<true, true, true>(Seek &, const ListEntry *, const int *, int);
template void EDCore::offer_lanes<false, true, true>(Seek &, const ListEntry *, const int *, int);

#undef LANES

}    // namespace granfric
#endif
