// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: Lees-Edwards boundaries (simple shear, EDOptions::shear; see
// event_driven.h). The image of the box one period up in y lies shifted by s(t) in x and moves
// at the shear rate. Stored positions stay unwrapped: a pair's image shift o takes o_y s(t) in x
// and o_y times the shear rate in velocity (EDCore::image, contact_at, collide_pair); a particle
// in image k_y has its x cell from its position less k_y s(t) (place, sheared_frame).
//
// Which cells are next to each other across a y face changes with s alone, without any event of
// a particle: every time s passes a multiple of the x cell width (a shear tick) one new cell
// comes next to each cell of the top row, and the pairs of the two cells are offered to both
// partners as candidates (shear_tick). Between ticks a particle's scan takes the 4 cells across
// the face that can hold a partner (sheared_row). The shift is kept within [0, L_x]: when a tick
// takes it past, it loses a period and the images' labels follow (shear_relabel), so that the
// numbers stay as precise as in the first period.
#include "event_driven.h"

#include <cmath>

namespace granfric {

void EventDriven::set_shear_shift(double s)
{
  if (!std::isfinite(s)) throw std::invalid_argument("the shear shift must be finite");
  shear_s0 = s;
}

// (start(): the shift brought into [0, L_x) at the present, the last partners' image shifts
// following, so that sheared_row's cells hold)
void EDCore::shear_start()
{
  if (!opt.shear) return;
  const double M = std::floor(shift_at(now) / P.x);
  if (M == 0.0) return;
  shear_s0 -= M * P.x;
  for (auto &s : schedules) s.last_off[0] += (int) M * s.last_off[1];
}

// the shift's cell and the first tick (after the cells)
void EDCore::shear_cells()
{
  shear_next = NEVER;
  if (!opt.shear) return;
  shear_m = std::min(std::max(0, (int) std::floor(shift_at(now) / cw[0])), nc[0] - 1);
  const double u = opt.shear_rate;
  if (u == 0.0) return;
  const double edge = (u > 0.0 ? shear_m + 1 : shear_m) * cw[0];
  shear_next = std::max(now, (edge - shear_s0) / u);
}

// s has passed the next multiple of the cell width: the new pairs across the y faces
void EDCore::shear_tick()
{
  now = shear_next;
  const int dir = opt.shear_rate > 0.0 ? 1 : -1;
  shear_m += dir;
  if (shear_m == nc[0]) {
    shear_m = 0;
    shear_relabel(1);
  } else if (shear_m < 0) {
    shear_m = nc[0] - 1;
    shear_relabel(-1);
  }
  const double edge = (dir > 0 ? shear_m + 1 : shear_m) * cw[0];
  shear_next = std::max(now, (edge - shear_s0) / opt.shear_rate);
  // each top-row cell A and the bottom-row cell that has just come next to it (one period up
  // in y): the first of sheared_row's 4 (dir > 0) or the last (dir < 0), in each z row next
  // to A's
  const int top = nc[1] - 1, zr = opt.dim == 3 ? 1 : 0;
  for (int a2 = 0; a2 < nc[2]; a2++)
    for (int a0 = 0; a0 < nc[0]; a0++) {
      const int A = (a2 * nc[1] + top) * nc[0] + a0;
      if (head[A] < 0) continue;
      int u[4], k[4];
      sheared_row(a0, 1, u, k);
      const int e = dir > 0 ? 0 : 3;
      for (int dz = -zr; dz <= zr; dz++) {
        int b2 = a2 + dz, kz = 0;
        if (b2 < 0 || b2 >= nc[2]) {
          if (!opt.periodic[2]) continue;
          kz = b2 < 0 ? -1 : 1;
          b2 -= kz * nc[2];
        }
        const int B = (b2 * nc[1]) * nc[0] + u[e];
        for (int i = head[A]; i >= 0; i = images[i].next) {
          const int *pk = images[i].k;
          for (int j = head[B]; j >= 0; j = images[j].next) {
            const int *qk = images[j].k;
            const double ti = schedules[i].ct, tj = schedules[j].ct;
            offer_both(i, j, pk[0] + k[e] - qk[0], pk[1] + 1 - qk[1], pk[2] + kz - qk[2]);
            if (schedules[i].ct != ti) reschedule(i);
            if (schedules[j].ct != tj) reschedule(j);
          }
        }
      }
    }
}

// the shift less dir periods of x: a particle's x image and every image shift in x gain dir
// times their y image (the same displacement, o_x L_x + o_y s, with s less dir L_x)
void EDCore::shear_relabel(int dir)
{
  shear_s0 -= dir * P.x;
  const int n = (int) schedules.size();
  for (int i = 0; i < n; i++) {
    Schedule &s = schedules[i];
    images[i].k[0] += dir * images[i].k[1];
    s.coff[0] += dir * s.coff[1];
    s.last_off[0] += dir * s.last_off[1];
  }
}

}    // namespace granfric
