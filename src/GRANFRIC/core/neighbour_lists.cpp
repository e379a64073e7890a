// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: neighbour lists, the second way of finding collision candidates (see
// event_driven.h). In a dense gas most particles of the 3^d cells around a particle are too far
// to be its next partner; a list of the particles within sigma plus a skin holds about half as
// many, and a particle rebuilds its list only when it has moved half the skin (lskin) from
// where it built it. Rebuilding is symmetric: the particle leaves every list it was in and
// enters the lists of its new neighbours, so a pair is listed by both partners or by neither,
// and the cells hold particles by list centre, so they change only at rebuilds.
#include "event_driven.h"

#include <algorithm>
#include <cmath>

namespace granfric {

// Lists pay in dense 3d gases: from about n sigma^3 = 0.75 (packing fraction 0.39), up to
// MAX_LISTS particles. A list holds fewer candidates than the 27 cells around a particle, so a
// collision takes less work; but the records take more than twice the memory (about 500 bytes
// per particle with the lists, against about 220 with cells), which pays only while they stay in
// the last-level cache: in a larger system every scan would wait for its list. In 2d the 9 cells
// around a particle hold few candidates to save.
bool EDCore::choose_lists(int dim, double sigma, double n, long count)
{
  return dim == 3 && n * sigma * sigma * sigma >= 0.75 && count <= MAX_LISTS;
}

// Decide whether this start() uses lists and size them (the cells come after, at least lrad
// wide). The skin: lists of the pairs within sigma (1 + skin), rebuilt after a path of
// skin sigma / 2.
void EDCore::setup_lists(double sigma)
{
  double vol = 1.0;
  long present = 0;
  for (int d = 0; d < opt.dim; d++) vol *= L[d];
  for (const Schedule &s : schedules) present += !s.gone;
  lists = opt.neighbours == EDOptions::LISTS ||
      (opt.neighbours == EDOptions::AUTO && !has_gravity && !opt.shear && vol > 0.0 &&
       choose_lists(opt.dim, sigma, present / vol, present));
  list_centres.clear();
  list_entries.clear();
  list_counts.clear();
  if (!lists) return;
  // (a larger skin rebuilds less often but scans longer lists: 0.6 balances the two where
  // candidates are tested in lanes, which make the longer lists cheap)
  const double skin = opt.list_skin > 0.0 ? opt.list_skin : 0.6;
  lskin = 0.5 * skin * sigma;
  const double lrad = (sigma + 2.0 * lskin) * (1.0 + 1e-9);
  lrad2 = lrad * lrad;
  const size_t n = flights.size();
  list_centres.resize(n);    // (set by place())
  list_entries.assign(n * LCAP, ListEntry{0, {0, 0, 0}, 0});
  list_counts.assign(n, 0);
}

// Remove i from the list of each of its neighbours (every entry, whatever its image) and empty
// i's list. Each entry's reverse index gives the place of i in the neighbour's list; the
// neighbour's last entry takes that place, and the reverse index of that entry's own reverse
// follows it (it may be one of i's later entries: i listed at two images).
void EDCore::list_drop(int i)
{
  const ListEntry *e = &list_entries[(size_t) i * LCAP];
  for (int m = 0; m < list_counts[i]; m++) {
    const int j = e[m].j, r = e[m].r;
    ListEntry *f = &list_entries[(size_t) j * LCAP];
    const int last = --list_counts[j];
    if (r == last) continue;
    f[r] = f[last];
    list_entries[(size_t) f[r].j * LCAP + f[r].r].r = (uint8_t) r;
  }
  list_counts[i] = 0;
}

// Enter every particle whose list centre lies within lrad of i's into i's list and i into
// theirs (higher_only: only particles of a higher index, for building all lists at once, with
// i in its cell; otherwise i in no cell, so that no test per candidate is needed to leave it
// out). i's list must be empty. False if a list would exceed LCAP or an image shift would not
// fit an entry (nothing changed).
bool EDCore::list_build(int i, bool higher_only)
{
  return higher_only ? list_build_t<true>(i) : list_build_t<false>(i);
}

template <bool HIGHER>
bool EDCore::list_build_t(int i)
{
  int cell[AROUND];
  int8_t shift[AROUND][3];
  const int ncell = around(i, cell, shift);
  const int *pk = images[i].k;
  const CellImage *IM = images.data();
  const Vec3 *X = list_centres.data();
  // near ones: the particle and the cell it was found in
  int fj[LCAP + 1];
  uint8_t fc[LCAP + 1];
  int nf = 0;
  for (int f = 0; f < ncell; f++) {
    // i's centre seen from the cell's image (the centres are inside the box)
    const Vec3 c = X[i] - periods(shift[f][0], shift[f][1], shift[f][2]);
    for (int j = head[cell[f]]; j >= 0; j = IM[j].next) {
      // (written always, kept if near: whether a particle of the 3^d cells is near is a
      // coin toss for a branch)
      fj[nf] = j;
      fc[nf] = (uint8_t) f;
      nf += HIGHER ? (norm2(c - X[j]) < lrad2) & (j > i) : norm2(c - X[j]) < lrad2;
      if (nf > LCAP) return false;
    }
  }
  if (list_counts[i] + nf > LCAP) return false;
  ListEntry *mine = &list_entries[(size_t) i * LCAP + list_counts[i]];
  for (int m = 0; m < nf; m++) {
    const int j = fj[m];
    const int8_t *k = shift[fc[m]];
    const int *qk = IM[j].k;
    const int o[3] = {pk[0] + k[0] - qk[0], pk[1] + k[1] - qk[1], pk[2] + k[2] - qk[2]};
    for (int d = 0; d < 3; d++)
      if (o[d] < -127 || o[d] > 127) return false;
    mine[m] = ListEntry{j, {(int8_t) o[0], (int8_t) o[1], (int8_t) o[2]}, 0};
  }
  // (each j once per image: its own count is checked before it is entered)
  for (int m = 0; m < nf; m++) {
    const int j = fj[m];
    if (list_counts[j] == LCAP) {
      for (int r = 0; r < m; r++) list_counts[fj[r]]--;    // undo: i leaves the lists it entered
      return false;
    }
    const int8_t *o = mine[m].o;
    const int rj = list_counts[j]++;
    list_entries[(size_t) j * LCAP + rj] =
        ListEntry{i, {(int8_t) -o[0], (int8_t) -o[1], (int8_t) -o[2]}, (uint8_t) (list_counts[i] + m)};
    mine[m].r = (uint8_t) rj;
  }
  list_counts[i] = (uint8_t) (list_counts[i] + nf);
  return true;
}

bool EDCore::build_all_lists()
{
  std::fill(list_counts.begin(), list_counts.end(), 0);
  for (int i = 0; i < (int) flights.size(); i++)
    if (!schedules[i].gone && !list_build(i, true)) return false;
  return true;
}

// The rebuild event of particle i (at now): a new list around its position now. Its own
// trajectory is untouched (its stored state is not advanced), so rebuilds change no rounding.
void EDCore::list_rebuild(int i)
{
  count_crossing(i);
  list_drop(i);
  cell_remove(i);
  place(i);    // (the new list centre)
  const bool built = list_build(i, false);    // (i in no cell)
  cell_insert(i);
  if (!built) {
    lists_to_cells();
    return;
  }
  stats.crossings++;
  crossings_since_reorder++;
  predict(i);
  reschedule(i);
}

// A list would overflow (a very dense spot): from now on this system finds its candidates in
// cells, as start() would set them up at this moment (every particle brought to now).
void EDCore::lists_to_cells()
{
  const int n = (int) flights.size();
  for (int i = 0; i < n; i++) advance(i, now);
  lists = false;
  list_centres.clear();
  list_entries.clear();
  list_counts.clear();
  setup_cells();
  predict_all();
  std::vector<double> times(n);
  for (int i = 0; i < n; i++) times[i] = schedule(i);
  queue.build(times);
}

// When i leaves the sphere of radius lskin around its list centre (moving now from xi at vi;
// no gravity with lists)
void EDCore::predict_rebuild(int i, const Vec3 &xi, const Vec3 &vi)
{
  Schedule &p = schedules[i];
  const Vec3 d = xi - list_centre(i);
  const double b = dot(d, vi), v2 = norm2(vi), c = norm2(d) - lskin * lskin;
  if (!(v2 > 0.0)) {
    p.xt = NEVER;
    return;
  }
  // the positive root of v2 tau^2 + 2 b tau + c = 0 (c <= 0 up to rounding), in stable forms
  const double s = std::sqrt(std::max(0.0, b * b - v2 * c));
  const double tau = b > 0.0 ? -c / (b + s) : (s - b) / v2;
  p.xt = now + std::max(0.0, tau);
}

// predict_all() with lists: rebuild times and walls per particle, each listed pair once
void EDCore::predict_all_lists()
{
  const int n = (int) flights.size();
  for (int i = 0; i < n; i++) {
    if (schedules[i].gone) {
      no_events(i);
      continue;
    }
    predict(i, false);
  }
  for (int i = 0; i < n; i++) {
    const ListEntry *e = &list_entries[(size_t) i * LCAP];
    for (int m = 0; m < list_counts[i]; m++)
      if (e[m].j > i) offer_both(i, e[m].j, e[m].o[0], e[m].o[1], e[m].o[2]);
  }
}

}    // namespace granfric
