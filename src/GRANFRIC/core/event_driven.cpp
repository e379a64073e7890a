// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the exact event-driven loop (see event_driven.h): the start of a
// window sequence, the events of a window in time order, pair collisions, the clock of
// trajectory changes and the windows' time shifts.
#include "event_driven.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace granfric {

double EDCore::schedule(int i)
{
  Schedule &p = schedules[i];
  double et;
  if (p.ct <= p.xt) {
    et = p.ct;
    p.ekind = p.ct < NEVER ? COLLISION : NONE;
  } else {
    et = p.xt;
    p.ekind = CROSSING;
  }
  if (!wall_times.empty() && wall_times[i] < et) {
    et = wall_times[i];
    p.ekind = WALL;
  }
  return et;
}

void EDCore::predict(int i, bool pairs)
{
  Schedule &p = schedules[i];
  const Vec3 xi = pos(i, now), vi = vel(i, now);
  if (lists)
    predict_rebuild(i, xi, vi);
  else
    predict_crossing(i, xi, vi);
  predict_wall(i);
  p.ct = NEVER;
  p.cpartner = -1;
  if (!pairs) return;
  if (lists)
    scan_list(i);
  else
    scan_full(i);
}

void EDCore::collide_pair(int e)
{
  Schedule &se = schedules[e];
  const double t = se.ct;
  // the pair in a canonical order (i: the smaller key), whichever of the two had the event:
  // the collision law's arithmetic is not symmetric in the last bits
  const bool swap = loop_key(se.cpartner) < loop_key(e);
  const int i = swap ? se.cpartner : e, j = swap ? e : se.cpartner;
  const int sg = swap ? -1 : 1;
  const int off[3] = {sg * se.coff[0], sg * se.coff[1], sg * se.coff[2]};    // (j's image)
  Flight &hp = flights[i];
  Collider &p = colliders[i];
  Schedule &s = schedules[i];
  Flight &hq = flights[j];
  Collider &q = colliders[j];
  advance(i, t);
  advance(j, t);
  const Vec3 r = hp.x - hq.x - image(off[0], off[1], off[2], t);
  const Vec3 n = (1.0 / norm(r)) * r;
  const double du = image_speed(off[1]);    // (Lees-Edwards: j's image moves faster in x)

  LawParams law = laws[s.type * (ntypes + 1) + schedules[j].type];
  const bool tc_elastic = tc_recent(i, t) || tc_recent(j, t);
  if (!last_collision.empty()) last_collision[i] = last_collision[j] = t;
  if (tc_elastic) law = law.elastic();
  Body b1{hp.v, p.w, p.m, hp.a, qt[s.type]}, b2{hq.v, q.w, q.m, hq.a, qt[schedules[j].type]};
  if (du != 0.0) b2.v.x += du;
  const Collision c = collide(law, b1, b2, n);
  hp.v = c.v1;
  p.w = c.w1;
  hq.v = c.v2;
  q.w = c.w2;
  if (du != 0.0) hq.v.x -= du;
  if (tracking_fast()) {
    note_speed(i, hp.v);
    note_speed(j, hq.v);
  }
  turned(i, j);
  p.last_partner = j;
  q.last_partner = i;
  for (int d = 0; d < 3; d++) {
    s.last_off[d] = off[d];
    schedules[j].last_off[d] = -off[d];
  }
  const long ni = ++s.ncollisions, nj = ++schedules[j].ncollisions;
  record_pair(i, j, t, r, n, b1, b2, c, tc_elastic, ni, nj);
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

void EventDriven::start()
{
  now = 0.0;
  for (auto &h : flights) h.t = 0.0;
  for (auto &c : colliders) c.last_partner = -1;
  start_common();
}

void EventDriven::start_at(double t)
{
  now = t;
  for (size_t i = 0; i < flights.size(); i++)
    if (!schedules[i].gone && !(flights[i].t <= t))
      throw std::invalid_argument("start_at: a particle's stored time lies after the start");
  start_common();
}

void EDCore::start_common()
{
  const int n = (int) flights.size();
  for (auto &s : schedules) s.ncollisions = 0;
  wall_times.assign(opt.walls.empty() ? 0 : n, NEVER);
  tick = 0;
  for (int i = 0; i < n; i++) {
    colliders[i].changed = 0;
    if (opt.dim == 2) {
      flights[i].v.z = 0.0;
      colliders[i].w.x = colliders[i].w.y = 0.0;
    }
  }
  double amax = 0.0;
  for (int i = 0; i < n; i++)
    if (!schedules[i].gone) amax = std::max(amax, flights[i].a);
  setup_lists(2.0 * amax * (1.0 + 1e-10));
  shear_start();
  setup_cells();
  shear_cells();
  renumber(cell_order());
  if (lists && !build_all_lists()) lists_to_cells();
  predict_all();
  std::vector<double> times(n);
  for (int i = 0; i < n; i++) times[i] = schedule(i);
  queue.build(times);
  started = true;
  dirty.clear();
}

void EDCore::copy_keys()
{
  const int n = (int) flights.size();
  for (int i = 0; i < n; i++) colliders[i].key = key(i);
}

EDStats EventDriven::advance_to(double t_end)
{
  stats = EDStats();
  stats.gamma_hist.assign(std::max(0, opt.gamma_bins), 0);
  stats.wall_hits.assign(opt.walls.size(), 0);
  stats.wall_impulse.assign(3 * opt.walls.size(), 0.0);
  stats.wall_work.assign(opt.walls.size(), 0.0);
  if (tally_on) tallies.assign(flights.size(), EDParticleTally{{0, 0, 0, 0, 0, 0}, 0, 0, 0, 0, 0, -INF});
  for (auto &s : schedules) s.ncollisions = 0;
  const int n = (int) flights.size();
  window_crossings = 0;
  crossing_cap = opt.max_crossings * (long) std::max(1, n);
  refresh();
  if (crossings_since_reorder > 4L * n) reorder();
  copy_keys();
  upcoming = Upcoming();    // (indices of an earlier numbering, maybe of more particles)
  const long bytes = (long) memory_bytes();
  far = bytes > opt.prefetch_bytes;
  far_partners = far && (lists || bytes > PARTNERS_FAR * opt.prefetch_bytes);
  size_t g = 0;
  while (n > 0) {
    const int i = queue.top();
    const double et = queue.top_time();
    const Schedule &p = schedules[i];
    if (shear_next < t_end && !(et < shear_next) && !(g < gtimes.size() && gtimes[g] < shear_next)) {
      shear_tick();
      continue;
    }
    if (g < gtimes.size() && gtimes[g] < t_end && !(et < gtimes[g])) {
      global_event((int) g++);
      continue;
    }
    if (!(et < t_end)) break;
    now = et;
    if (far) prefetch_upcoming();
    if (p.ekind == COLLISION) {
      if (stale(p)) {
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

void EDCore::retick()
{
  const int n = (int) schedules.size();
  for (int i = 0; i < n; i++) {
    Schedule &s = schedules[i];
    if (s.cpartner >= 0) s.ctick = stale(s) ? 0 : 1;
  }
  for (int i = 0; i < n; i++) colliders[i].changed = 1;
  tick = 1;
}

void EventDriven::rebase(double dt)
{
  // the same shift for every time keeps the heap ordered (rounding is monotone)
  for (auto &p : flights) p.t -= dt;
  for (auto &t : last_collision) t -= dt;
  for (auto &s : schedules) {
    s.ct -= dt;
    s.xt -= dt;
  }
  for (auto &t : wall_times) t -= dt;
  queue.shift(dt);
  now -= dt;
  clock += dt;
  shear_s0 += opt.shear_rate * dt;
  shear_next -= dt;
}

EDStats EventDriven::run(double t_end)
{
  start();
  const EDStats s = advance_to(t_end);
  for (int i = 0; i < (int) flights.size(); i++) advance(i, t_end);
  return s;
}

}    // namespace granfric
