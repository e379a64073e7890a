// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: Lees-Edwards boundaries (simple shear, EDOptions::shear; see
// event_driven.h). The image of the box one period up in y lies shifted by s(t) in x and moves
// at the shear rate. Stored positions stay unwrapped: a pair's image shift o takes o_y s(t) in x
// and o_y times the shear rate in velocity (EDCore::image, contact_at, collide_pair).
//
// The cells move with the flow, so that a particle crosses them at its speed relative to the
// flow rather than at the streaming speed, which grows with the box. They move in bands of
// neighbouring rows (row_band; shear_bands chooses how many rows a band takes): band b is
// shifted in x by (b + 1/2) D(t) + h L_x / 2, D = (s + w L_x) / n_b (row_step; row_shift), and
// moves at b + 1/2 times the shear rate over n_b, the speed of the streaming profile (zero at
// the lower y face, as LAMMPS's fix deform and compute temp/deform take it) at the band's
// middle. Neighbouring bands are then shifted by D against each other, and so are the top band
// and the bottom band of the image one period up (s - (n_b - 1) D = D - w L_x: the same shift,
// less w periods of x): every boundary between bands is sheared alike, and the rows within a
// band lie over each other as in an unsheared box. A particle in image k_y and band b has its x
// cell from its position less k_y s and its band's shift (place, sheared_frame); a crossing
// into another band, or through a y face, finds its x cell afresh (cross).
//
// Wider bands take fewer scans across sheared boundaries, whose rows take 4 cells instead of 3
// at image shifts of their own (a row inside its band is scanned as in an unsheared box), and a
// particle crosses the cells of a band at its speed relative to the band, which differs from
// the flow's by up to half the band's share of the shear (bands that moved at the speed of
// their lowest row took 22 % more crossings, 3d, bench/in.speed at N = 10648). shear_bands sizes
// the bands between the two.
//
// Which cells of neighbouring bands are next to each other changes with D alone, without any
// event of a particle: every time D passes a multiple of the x cell width (a shear tick) one new
// cell comes next to each cell from the row above a band's boundary, and the pairs of the two
// cells are offered to both partners as candidates (shear_tick). Between ticks a particle's scan
// takes the 4 cells of a row across a band boundary that can hold a partner (sheared_spans). The
// shift s is kept within [0, L_x): a period is taken from it when it passes L_x (or 0), at a
// time that depends on s alone, and w counts the periods taken (shear_relabel). D stays within
// [0, L_x): when w reaches n_b, D has passed a period with s, w starts again, h moves on by one
// and the images' labels follow (row_relabel). So the numbers stay as precise as in the first period.
#include "event_driven.h"

#include <algorithm>
#include <cmath>

namespace granfric {

void EventDriven::set_shear_shift(double s)
{
  if (!std::isfinite(s)) throw std::invalid_argument("the shear shift must be finite");
  shear_s0 = s;
}

// (start(): the shift brought into [0, L_x) at the present, the last partners' image shifts
// following, so that the cells hold; the rows start unshifted against the shift's period)
void EDCore::shear_start()
{
  shear_w = 0;
  shear_h = 0;
  shear_periods();
  if (!opt.shear) return;
  const double M = std::floor(shift_at(now) / P.x);
  if (M == 0.0) return;
  shear_s0 -= M * P.x;
  for (auto &s : schedules) s.last_off[0] += (int) M * s.last_off[1];
}

// The next shear event: the shift passing a period of x (at s = L_x or 0: whole periods are
// taken from it at times that do not depend on the cells), or D the next multiple of the cell
// width ahead (a tick). D passes a period only with the shift (s + w L_x = n_y L_x: w at its
// end), so that tick is the shift's.
void EDCore::shear_schedule()
{
  shear_next = NEVER;
  const double u = opt.shear_rate;
  if (!opt.shear || u == 0.0) return;
  const int dir = u > 0.0 ? 1 : -1;
  const double wrap = std::max(now, ((dir > 0 ? P.x : 0.0) - shear_s0) / u);
  double tick_at = NEVER;
  if (dir > 0 ? shear_m + 1 < nc[0] : shear_m > 0) {
    const double edge = (dir > 0 ? shear_m + 1 : shear_m) * cw[0];
    tick_at = std::max(now, (nbands * edge - shear_w * P.x - shear_s0) / u);
  }
  shear_wraps = !(tick_at < wrap);
  shear_next = shear_wraps ? wrap : tick_at;
}

// D's cell and the first event (after the cells)
void EDCore::shear_cells()
{
  shear_next = NEVER;
  if (!opt.shear) return;
  shear_m = std::min(std::max(0, (int) std::floor(row_step(now) / cw[0])), nc[0] - 1);
  shear_schedule();
}

// The rows of cells next to particle i's and the x cells of each that can hold a partner: its
// own row and a row of its band, x cells c0 - 1 .. c0 + 1; the row above across a band boundary,
// shifted by D = (m + f) cell widths, the 4 x cells from c0 - m - 2 on (a partner within a cell
// width lies within 2 + f cells less m); the row below across one, the 4 from c0 + m - 1 on.
// Across a y face the row is that of the image up or down, w periods of x further
// (s - (n_b - 1) D = D - w L_x). Counted across images: x cell a of a row is its cell
// a - q nc[0] at x image q.
template <int DIM>
inline __attribute__((always_inline)) int EDCore::sheared_spans_t(int i, RowSpan out[9]) const
{
  const int16_t *c = schedules[i].c;
  const int *pk = images[i].k;
  const int n0 = nc[0], n1 = nc[1];
  const long C = c[0] + (long) n0 * pk[0], face = (long) shear_w * n0;
  // the rows below, at and above i's (y cell, y image, first x cell: counted across images,
  // and as cell u at x image q, found without a division; m 0 across no band boundary)
  const bool sb = boundary_sheared(c[1], -1), sa = row_sheared[c[1]];
  const int mb = sb ? shear_m : 0, ma = sa ? shear_m + 1 : 0;
  int cy[3] = {c[1] - 1, c[1], c[1] + 1}, ky[3] = {pk[1], pk[1], pk[1]};
  long a0[3] = {C + mb - 1, C - 1, C - ma - 1};
  int u[3] = {c[0] + mb - 1, c[0] - 1, c[0] - ma - 1}, q[3] = {pk[0], pk[0], pk[0]};
  const int wide[3] = {sb, 0, sa};
  if (cy[0] < 0) cy[0] += n1, ky[0]--, a0[0] -= face, q[0] -= shear_w;
  if (cy[2] >= n1) cy[2] -= n1, ky[2]++, a0[2] += face, q[2] += shear_w;
  for (int r = 0; r < 3; r++) {
    if (u[r] < 0) {
      u[r] += n0, q[r]--;
      if (u[r] < 0) u[r] += n0, q[r]--;    // (the row above: down to -nc[0] - 1)
    } else if (u[r] >= n0) {
      u[r] -= n0, q[r]++;
    }
  }
  int n = 0;
  const int zr = DIM == 3 ? 1 : 0;
  for (int dz = -zr; dz <= zr; dz++) {
    int cz = c[2] + dz, kz = pk[2];
    if (DIM == 3 && (cz < 0 || cz >= nc[2])) {
      if (!opt.periodic[2]) continue;
      const int e = cz < 0 ? -1 : 1;
      cz -= e * nc[2];
      kz += e;
    }
    for (int r = 0; r < 3; r++) {
      RowSpan &s = out[n++];
      s.dy = r - 1, s.dz = dz, s.ky = ky[r], s.kz = kz;
      s.row = (cz * n1 + cy[r]) * n0, s.q = q[r], s.u = u[r];
      s.a0 = a0[r];
      s.a1 = a0[r] + 2 + wide[r];
    }
  }
  return n;
}

int EDCore::sheared_spans(int i, RowSpan out[9]) const
{
  return opt.dim == 3 ? sheared_spans_t<3>(i, out) : sheared_spans_t<2>(i, out);
}

// scan() in a sheared box: every row next to i (full), or the cells that a crossing in x, y or
// z (the offsets dlo..dhi of one layer) has just brought next to it: in x the leading cell of
// every row, in y (within a band) the row ahead, in z the rows of the new layer
void EDCore::scan_sheared(int i, bool full, const int dlo[3], const int dhi[3])
{
  RowSpan s[9];
  int n = opt.dim == 3 ? sheared_spans_t<3>(i, s) : sheared_spans_t<2>(i, s);
  if (!full && dlo[0] == dhi[0]) {
    for (int r = 0; r < n; r++) {
      if (dlo[0] > 0) s[r].start_at(s[r].a1, nc[0]);
      else s[r].a1 = s[r].a0;
    }
  } else if (!full && (dlo[1] == dhi[1] || (opt.dim == 3 && dlo[2] == dhi[2]))) {
    const bool y = dlo[1] == dhi[1];
    int m = 0;
    for (int r = 0; r < n; r++)
      if (y ? s[r].dy == dlo[1] : s[r].dz == dlo[2]) s[m++] = s[r];
    n = m;
  }
  scan_spans(i, s, n);
}

// after a crossing into another row: the cells of the rows next to i now that were not next to
// it before (the same row, at the same images, with x cells outside the earlier ones)
void EDCore::scan_new_spans(int i, const RowSpan *before, int nbefore)
{
  RowSpan now_[9], todo[18];
  const int n = sheared_spans(i, now_);
  int m = 0;
  for (int r = 0; r < n; r++) {
    const RowSpan &s = now_[r];
    const RowSpan *b = nullptr;
    for (int q = 0; q < nbefore && !b; q++)
      if (before[q].row == s.row && before[q].ky == s.ky && before[q].kz == s.kz)
        b = &before[q];
    if (!b || b->a1 < s.a0 || s.a1 < b->a0) {
      todo[m++] = s;
      continue;
    }
    if (s.a0 < b->a0) {
      todo[m] = s;
      todo[m++].a1 = b->a0 - 1;
    }
    if (s.a1 > b->a1) {
      todo[m] = s;
      todo[m++].start_at(b->a1 + 1, nc[0]);
    }
  }
  scan_spans(i, todo, m);
}

// A shear event (shear_schedule): the shift has passed a period, or D a multiple of the cell
// width; at a tick, the new pairs across every band boundary
void EDCore::shear_tick()
{
  now = shear_next;
  const int dir = opt.shear_rate > 0.0 ? 1 : -1;
  const int ny = nc[1];
  if (shear_wraps) {
    shear_relabel(dir);
    if (shear_w >= 0 && shear_w < nbands) {
      shear_schedule();
      return;
    }
    row_relabel(dir);    // (D has passed its period with the shift: a tick)
    shear_m = dir > 0 ? 0 : nc[0] - 1;
  } else {
    shear_m += dir;
  }
  shear_schedule();
  // each cell A and the cell of the row above that has just come next to it: the first of its
  // 4 (dir > 0) or the last (dir < 0), in each z row next to A's
  const int zr = opt.dim == 3 ? 1 : 0;
  const long n0 = nc[0];
  for (int a2 = 0; a2 < nc[2]; a2++)
    for (int a1 = 0; a1 < ny; a1++) {
      if (!row_sheared[a1]) continue;
      const int b1 = a1 + 1 == ny ? 0 : a1 + 1, ky = a1 + 1 == ny ? 1 : 0;
      for (int a0 = 0; a0 < nc[0]; a0++) {
        const int A = (a2 * ny + a1) * nc[0] + a0;
        if (head[A] < 0) continue;
        const long b = (dir > 0 ? a0 - shear_m - 2 : a0 - shear_m + 1) + ky * (long) shear_w * n0;
        const long kx = floor_div(b, n0);
        const int b0 = (int) (b - kx * n0);
        for (int dz = -zr; dz <= zr; dz++) {
          int b2 = a2 + dz, kz = 0;
          if (b2 < 0 || b2 >= nc[2]) {
            if (!opt.periodic[2]) continue;
            kz = b2 < 0 ? -1 : 1;
            b2 -= kz * nc[2];
          }
          const int B = (b2 * ny + b1) * nc[0] + b0;
          for (int i = head[A]; i >= 0; i = images[i].next) {
            const int *pk = images[i].k;
            for (int j = head[B]; j >= 0; j = images[j].next) {
              const int *qk = images[j].k;
              const double ti = schedules[i].ct, tj = schedules[j].ct;
              offer_both(i, j, pk[0] + (int) kx - qk[0], pk[1] + ky - qk[1], pk[2] + kz - qk[2]);
              if (schedules[i].ct != ti) reschedule(i);
              if (schedules[j].ct != tj) reschedule(j);
            }
          }
        }
      }
    }
}

// the shift less dir periods of x (w gains dir): a particle's x image and every image shift in
// x gain dir times their y image (the same displacement, o_x L_x + o_y s, with s less dir L_x)
void EDCore::shear_relabel(int dir)
{
  shear_s0 -= dir * P.x;
  shear_w += dir;
  shear_periods();
  const int n = (int) schedules.size();
  for (int i = 0; i < n; i++) {
    Schedule &s = schedules[i];
    images[i].k[0] += dir * images[i].k[1];
    s.coff[0] += dir * s.coff[1];
    s.last_off[0] += dir * s.last_off[1];
  }
}

// D less dir periods of x (w back to the other end), h plus dir: band b is shifted b periods
// less, b + 1 where h passes 1 or 0 and starts again (dir periods less), and the x images of its
// particles gain that times dir (image shifts of pairs are displacements and stay)
void EDCore::row_relabel(int dir)
{
  shear_w -= dir * nbands;
  shear_h += dir;
  const int carry = shear_h == 2 || shear_h == -1;
  shear_h -= 2 * dir * carry;
  shear_periods();
  const int n = (int) schedules.size();
  for (int i = 0; i < n; i++) images[i].k[0] += dir * (row_band[schedules[i].c[1]] + carry);
}

// The bands of rows (setup_cells(), before the particles are placed): EDOptions::shear_band
// rows each, or as many as keep the flow's difference across a band within f times the spread
// of x velocities about the streaming profile (of the particles present; one row where they are
// at rest on it): f = 1 in 2d, 3 in 3d, where a row across a band boundary costs 3 layers of
// cells (the optima of instructions per collision, bench/README.md, "Sheared boxes"). Bands of
// n_y / n_b rows, some one more.
void EDCore::shear_bands()
{
  const int ny = nc[1];
  int rows = opt.shear_band;
  if (rows == 0) {
    double n = 0.0, sum = 0.0, sum2 = 0.0;
    const double rate = opt.shear_rate / P.y;
    for (size_t i = 0; i < flights.size(); i++) {
      if (schedules[i].gone) continue;
      const double u = vel((int) i, now).x - rate * (pos((int) i, now).y - opt.lo[1]);
      n += 1.0, sum += u, sum2 += u * u;
    }
    const double spread = n > 1.0 ? std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n))) : 0.0;
    const double per_row = std::fabs(opt.shear_rate) / ny;
    const double f = opt.dim == 3 ? 3.0 : 1.0;
    rows = per_row == 0.0 ? ny : (int) std::min<double>(ny, std::floor(f * spread / per_row));
  }
  nbands = std::max(1, ny / std::max(1, rows));
  band_scale = 1.0 / nbands;    // (products where the crossings are predicted: no division)
  band_rate = opt.shear_rate * band_scale;
  row_band.resize(ny);
  row_sheared.resize(ny);
  for (int r = 0; r < ny; r++) row_band[r] = (int) ((long) r * nbands / ny);
  row_mid.resize(ny);
  for (int r = 0; r < ny; r++) row_mid[r] = row_band[r] + 0.5;
  for (int r = 0; r < ny; r++) row_sheared[r] = r + 1 == ny || row_band[r + 1] != row_band[r];
  row_kind.resize(ny);
  for (int r = 0; r < ny; r++) {
    const bool up = row_sheared[r], down = boundary_sheared(r, -1);
    row_kind[r] = band_interior(r) ? ROW_INSIDE
        : r == 0 || r + 1 == ny || up == down ? ROW_SPANS
        : up ? ROW_EDGE_UP : ROW_EDGE_DOWN;
  }
}

}    // namespace granfric
