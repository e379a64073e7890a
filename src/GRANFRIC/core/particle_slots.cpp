// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the particles' slots (see event_driven.h): their number, and the
// changes from outside between windows (removal, changed or nudged particles, last partners,
// frames) with the fresh predictions they need.
#include "event_driven.h"

#include <stdexcept>

namespace granfric {

void EventDriven::resize(int n)
{
  fast.clear();
  acct = EDAccounting();
  flights.assign(n, Flight());
  colliders.assign(n, Collider());
  last_collision.assign(opt.tc > 0.0 ? n : 0, -INF);
  schedules.assign(n, Schedule());
  wall_times.clear();
  images.assign(n, CellImage{{0, 0, 0}, -1});
  if (framed) frames.assign(n, Frame{{0, 0, 0}});
  lists = false;
  list_centres.clear();
  list_entries.clear();
  list_counts.clear();
  ext.resize(n);
  loc.resize(n);
  for (int i = 0; i < n; i++) ext[i] = loc[i] = i;
  started = false;
  dirty.clear();
}

void EventDriven::set_last_partner(int e, int p, const int off[3])
{
  const int i = loc[e];
  colliders[i].last_partner = p < 0 ? -1 : loc[p];
  for (int d = 0; d < 3; d++) schedules[i].last_off[d] = p < 0 ? 0 : off[d];
}

void EventDriven::set_frame(int e, const int f[3])
{
  if (!framed) {
    if (f[0] | f[1] | f[2]) throw std::invalid_argument("set_frame: no open dimension has a period");
    return;
  }
  for (int d = 0; d < 3; d++)
    if (f[d] && !(opt.period[d] > 0.0 && d < opt.dim))
      throw std::invalid_argument("set_frame: a frame shift in a dimension without a period");
  Frame &F = frames[loc[e]];
  for (int d = 0; d < 3; d++) F.f[d] = f[d];
}

void EventDriven::remove(int e)
{
  const int i = loc[e];
  Schedule &s = schedules[i];
  if (s.gone) return;
  if (started) {
    if (lists) list_drop(i);
    cell_remove(i);
    queue.update(i, NEVER);
  }
  s.gone = 1;
  no_events(i);
  s.ekind = NONE;
  turned(i);    // predictions that involved it are stale
  colliders[i].last_partner = -1;
}

void EventDriven::changed(int e, bool own_time)
{
  const int i = loc[e];
  Flight &p = flights[i];
  Collider &c = colliders[i];
  Schedule &s = schedules[i];
  if (!started) throw std::logic_error("EventDriven::changed() before start()");
  if (!(p.a <= cell_amax))
    throw std::invalid_argument("a changed particle's radius exceeds what the cell grid admits");
  if (!s.gone) {
    if (lists) list_drop(i);
    cell_remove(i);
  }
  s.gone = 0;
  if (!own_time) p.t = now;
  if (!(p.t <= now)) throw std::invalid_argument("changed: a particle's stored time lies after now");
  turned(i);    // every prediction that involved it is stale
  c.last_partner = -1;
  if (opt.dim == 2) {
    p.v.z = 0.0;
    c.w.x = c.w.y = 0.0;
  }
  place(i);
  const bool built = !lists || list_build(i, false);    // (i in no cell)
  cell_insert(i);
  no_events(i);
  queue.update(i, NEVER);    // until refresh() predicts it
  dirty.push_back(e);
  if (!built) lists_to_cells();
}

bool EventDriven::nudge(int e, const double *x, const double *v, const double *w)
{
  const int i = loc[e];
  Flight &p = flights[i];
  const Schedule &s = schedules[i];
  if (!started) throw std::logic_error("EventDriven::nudge() before start()");
  if (s.gone || lists || opt.shear) return false;    // (with shear: changed())
  for (int d = 0; d < opt.dim; d++) {    // the cell (and image) place() would give
    int c, k;
    locate(d, x[d], c, k);
    if (k != images[i].k[d] || c != s.c[d]) return false;
  }
  p.x = Vec3(x[0], x[1], x[2]);
  p.v = Vec3(v[0], v[1], v[2]);
  p.t = now;
  Collider &c = colliders[i];
  c.w = Vec3(w[0], w[1], w[2]);
  if (opt.dim == 2) {
    p.v.z = 0.0;
    c.w.x = c.w.y = 0.0;
  }
  return true;
}

void EDCore::refresh()
{
  for (int e : dirty) {
    const int i = loc[e];
    if (schedules[i].gone) continue;    // (changed, then removed)
    predict(i);
    reschedule(i);
  }
  dirty.clear();
}

}    // namespace granfric
