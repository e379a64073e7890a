// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: asking the memory ahead for the records of the events to come (see
// event_driven.h), in systems whose records do not stay in the cache.
#include "event_driven.h"

namespace granfric {

// Ask the memory for what a scan of particle i will read: its records, and the records of its
// candidates (the first particle of each cell around it; with neighbour lists only the list).
// Events come in time order, which is random in space, so in a system larger than the cache
// each of these is a miss; asked for ahead, they arrive while the events before are worked
// on. In two stages, because the candidates are known only from the cell lists: first
// (deep = false) the lines of those lists, one event later (deep = true) the candidates'
// records.
void EDCore::prefetch_around(int i, bool deep) const
{
  asm volatile("");    // (see EventQueue::prefetch_ahead)
  __builtin_prefetch(&flights[i]);
  __builtin_prefetch(&images[i]);
  if (lists) {
    const ListEntry *e = &list_entries[(size_t) i * LCAP];
    if (!deep) {
      // its list centre and the lines of its list
      __builtin_prefetch(&list_centres[i]);
      __builtin_prefetch(e);
      __builtin_prefetch(e + 64 / sizeof(ListEntry));    // (the next cache line)
    } else if (schedules[i].ekind != CROSSING) {
      // the records of its first listed neighbours, which its scan's first lanes wait for;
      // the later ones arrive while the first lanes are worked on, so asking for them too would
      // add requests without taking away a wait
      const int first = list_counts[i] < PREFETCH_LISTED ? list_counts[i] : PREFETCH_LISTED;
      for (int m = 0; m < first; m++) __builtin_prefetch(&flights[e[m].j]);
    } else {
      // a list rebuild leaves its neighbours' lists (list_drop): the line of each reverse
      // entry, and the neighbour's count
      for (int m = 0; m < list_counts[i]; m++) {
        __builtin_prefetch(&list_entries[(size_t) e[m].j * LCAP + e[m].r]);
        __builtin_prefetch(&list_counts[e[m].j]);
      }
    }
    return;
  }
  // the cells around the one the particle is in, or, where its event is a crossing, the one
  // it enters (the cells inside the grid; at its edges nothing more)
  const Schedule &p = schedules[i];
  int16_t c[3] = {p.c[0], p.c[1], p.c[2]};
  if (p.ekind == CROSSING) c[p.xdim] = (int16_t) (c[p.xdim] + p.xdir);
  // (a sheared box: into the row above or below across a band boundary, whose cells lie about m
  // further back or on)
  if (p.ekind == CROSSING && opt.shear && p.xdim == 1 && boundary_sheared(p.c[1], p.xdir))
    c[0] = (int16_t) (c[0] - p.xdir * shear_m);
  const int dz1 = opt.dim == 3 ? 1 : 0;
  if (c[0] < 1 || c[0] + 1 >= nc[0] || c[1] < 1 || c[1] + 1 >= nc[1] || c[2] < dz1 || c[2] + dz1 >= nc[2])
    return;
  const int *base = head.data() + (c[2] * nc[1] + c[1]) * nc[0] + c[0];
  // n cells of a row from h on: the lines of the list heads, or each one's first particle (an
  // empty cell, -1: particle 0, no branch)
  auto cells = [&](const int *h, int n) __attribute__((always_inline)) {
    if (!deep) {
      __builtin_prefetch(h);
      __builtin_prefetch(h + n - 1);
      return;
    }
#pragma GCC unroll 4
    for (int q = 0; q < n; q++) {
      const int j = h[q] & ~(h[q] >> 31);
      __builtin_prefetch(&flights[j]);
      __builtin_prefetch(&images[j]);
    }
  };
  // the rows below, at and above the particle's in every layer, from x offsets x0 on, n_below
  // and n_above cells in the rows below and above (known where it is inlined), 3 in its own
  auto rows = [&](const int *x0, int n_below, int n_above) __attribute__((always_inline)) {
    for (int dz = -dz1; dz <= dz1; dz++) {
      const int *h = base + dz * nc[1] * nc[0];
      cells(h - nc[0] + x0[0], n_below), cells(h + x0[1], 3), cells(h + nc[0] + x0[2], n_above);
    }
  };
  static const int around3[3] = {-1, -1, -1};
  if (!opt.shear) return rows(around3, 3, 3);
  // (a sheared box: the 4 cells of a row across a band boundary that sheared_spans takes,
  // where they lie inside the grid, else 4 around the particle's own x; which rows are across
  // a boundary decided once, by the row's kind)
  const int kind = row_kind[c[1]];
  if (kind == ROW_INSIDE || nc[0] < 4) return rows(around3, 3, 3);
  const int near = c[0] + 2 < nc[0] ? -1 : -2, fb = shear_m - 1, fa = -shear_m - 2;
  const int xb = c[0] + fb >= 0 && c[0] + fb + 3 < nc[0] ? fb : near;
  const int xa = c[0] + fa >= 0 && c[0] + fa + 3 < nc[0] ? fa : near;
  const int up[3] = {-1, -1, xa}, down[3] = {xb, -1, -1}, both[3] = {xb, -1, xa};
  if (kind == ROW_EDGE_UP) return rows(up, 3, 4);
  if (kind == ROW_EDGE_DOWN) return rows(down, 4, 3);
  rows(both, 4, 4);
}

// The events ahead, as the queue's walk along its next buckets meets their particles
// (EventQueue::prefetch_ahead): in stages over the next events, each reading what the one
// before asked for. A particle met now: its schedule and flight record; one event later the lines
// of the cell lists around it, and its collision partner's records; two events later the
// records of its first candidates, and the cell lists around the partner; three events later
// the partner's first candidates. The partner's cells and candidates only with neighbour
// lists or in systems of PARTNERS_FAR times the size from which the loop prefetches: in a
// smaller system what the partner's scan reads is mostly still in the cache from the events
// before, and asking for it again only adds work.
void EDCore::prefetch_upcoming()
{
  Upcoming &u = upcoming;
  const int s0 = u.turn & 3, s1 = (u.turn + 3) & 3, s2 = (u.turn + 2) & 3, s3 = (u.turn + 1) & 3;
  if (far_partners)
    for (int k = 0; k < u.n[s3]; k++)
      if (u.q[s3][k] >= 0) prefetch_around(u.q[s3][k], true);
  for (int k = 0; k < u.n[s2]; k++) {
    prefetch_around(u.p[s2][k], true);
    if (far_partners && u.q[s2][k] >= 0) prefetch_around(u.q[s2][k], false);
  }
  for (int k = 0; k < u.n[s1]; k++) {
    const int i = u.p[s1][k];
    prefetch_around(i, false);
    const Schedule &si = schedules[i];
    const int q = si.ekind == COLLISION ? si.cpartner : -1;
    u.q[s1][k] = q;
    prefetch_collider(i);
    if (q >= 0)
      prefetch_partner(q);
    else if (si.cpartner >= 0)    // (a crossing reads its candidate partner's tick: stale())
      __builtin_prefetch(&colliders[si.cpartner].changed);
  }
  u.n[s0] = 0;
  queue.prefetch_ahead([this, &u, s0](int i) {
    __builtin_prefetch(&schedules[i]);
    __builtin_prefetch(&flights[i]);
    if (u.n[s0] < Upcoming::MOST) u.p[s0][u.n[s0]++] = i;
  });
  u.turn++;
}

}    // namespace granfric
