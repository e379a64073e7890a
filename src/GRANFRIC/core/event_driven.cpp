// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the exact event-driven loop (see event_driven.h): configuration, the particles' slots,
// the event loop, pair collisions, global events and the windows' time shifts.
#include "event_driven.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace granfric {

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
  lanes = o.simd && have_lanes();    // (the scans that use them are 3d without gravity)
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
  framed = false;
  for (int d = 0; d < 3; d++) {
    if (!(o.period[d] >= 0.0)) throw std::invalid_argument("a period must be >= 0");
    if (o.period[d] > 0.0 && !o.open[d])
      throw std::invalid_argument("a period is for open dimensions only");
    P[d] = o.periodic[d] ? L[d] : o.period[d];
    framed = framed || (o.period[d] > 0.0 && d < o.dim);
  }
  if (!framed) FR.clear();
  else if (FR.size() != H.size()) FR.assign(H.size(), Frame{{0, 0, 0}});
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

bool EventDriven::same_configuration(const EDOptions &o, int nt, const std::vector<LawParams> &table,
                                     const EDOptions &opt, int ntypes, const std::vector<LawParams> &laws)
{
  if (o.dim != opt.dim || nt != ntypes || !same_laws(table, laws) ||
      o.gravity.x != opt.gravity.x || o.gravity.y != opt.gravity.y || o.gravity.z != opt.gravity.z ||
      o.tc != opt.tc || o.max_collisions != opt.max_collisions || o.gamma_bins != opt.gamma_bins ||
      o.cell_width != opt.cell_width || o.neighbours != opt.neighbours ||
      o.list_skin != opt.list_skin ||
      o.walls.size() != opt.walls.size() ||
      shape_table(o, nt) != shape_table(opt, ntypes))
    return false;
  for (int d = 0; d < 3; d++)
    if (o.lo[d] != opt.lo[d] || o.hi[d] != opt.hi[d] || o.periodic[d] != opt.periodic[d] ||
        o.open[d] != opt.open[d] || o.period[d] != opt.period[d])
      return false;
  for (size_t k = 0; k < o.walls.size(); k++) {
    const EDWall &a = o.walls[k], &b = opt.walls[k];
    if (a.dim != b.dim || a.side != b.side || a.pos != b.pos || a.T != b.T || a.seed != b.seed ||
        a.A != b.A || a.omega != b.omega || a.sine != b.sine || !same_laws(a.laws, b.laws))
      return false;
  }
  return true;
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
  if (framed) FR.assign(n, Frame{{0, 0, 0}});
  lists = false;
  XW.clear();
  NB.clear();
  NN.clear();
  ext.resize(n);
  loc.resize(n);
  for (int i = 0; i < n; i++) ext[i] = loc[i] = i;
  started = false;
  dirty.clear();
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

void EventDriven::predict(int i, bool pairs)
{
  Sched &p = S[i];
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

void EventDriven::collide_pair(int e)
{
  Sched &se = S[e];
  const double t = se.ct;
  // the pair in a canonical order (i: the smaller key), whichever of the two had the event:
  // the collision law's arithmetic is not symmetric in the last bits
  const bool swap = loop_key(se.cpartner) < loop_key(e);
  const int i = swap ? se.cpartner : e, j = swap ? e : se.cpartner;
  const int sg = swap ? -1 : 1;
  const int off[3] = {sg * se.coff[0], sg * se.coff[1], sg * se.coff[2]};    // (j's image)
  Hot &hp = H[i];
  Cold &p = C[i];
  Sched &s = S[i];
  Hot &hq = H[j];
  Cold &q = C[j];
  advance(i, t);
  advance(j, t);
  const Vec3 r = hp.x - hq.x - periods(off[0], off[1], off[2]);
  const Vec3 n = (1.0 / norm(r)) * r;

  LawParams law = laws[s.type * (ntypes + 1) + S[j].type];
  const bool tc_elastic = tc_recent(i, t) || tc_recent(j, t);
  if (!TL.empty()) TL[i] = TL[j] = t;
  if (tc_elastic) law = law.elastic();
  Body b1{hp.v, p.w, p.m, hp.a, qt[s.type]}, b2{hq.v, q.w, q.m, hq.a, qt[S[j].type]};
  const Collision c = collide(law, b1, b2, n);
  hp.v = c.v1;
  p.w = c.w1;
  hq.v = c.v2;
  q.w = c.w2;
  if (tracking_fast()) {
    note_speed(i, hp.v);
    note_speed(j, hq.v);
  }
  turned(i, j);
  p.last_partner = j;
  q.last_partner = i;
  for (int d = 0; d < 3; d++) {
    s.last_off[d] = off[d];
    S[j].last_off[d] = -off[d];
  }
  const long ni = ++s.ncollisions, nj = ++S[j].ncollisions;
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
  for (auto &h : H) h.t = 0.0;
  for (auto &c : C) c.last_partner = -1;
  start_common();
}

void EventDriven::start_at(double t)
{
  now = t;
  for (size_t i = 0; i < H.size(); i++)
    if (!S[i].gone && !(H[i].t <= t))
      throw std::invalid_argument("start_at: a particle's stored time lies after the start");
  start_common();
}

void EventDriven::start_common()
{
  const int n = (int) H.size();
  for (auto &s : S) s.ncollisions = 0;
  WT.assign(opt.walls.empty() ? 0 : n, NEVER);
  tick = 0;
  for (int i = 0; i < n; i++) {
    C[i].changed = 0;
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

void EventDriven::set_last_partner(int e, int p, const int off[3])
{
  const int i = loc[e];
  C[i].last_partner = p < 0 ? -1 : loc[p];
  for (int d = 0; d < 3; d++) S[i].last_off[d] = p < 0 ? 0 : off[d];
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
  Frame &F = FR[loc[e]];
  for (int d = 0; d < 3; d++) F.f[d] = f[d];
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
  turned(i);    // predictions that involved it are stale
  C[i].last_partner = -1;
}

void EventDriven::changed(int e, bool own_time)
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

// Ask the memory for what a scan of particle i will read: its records, and the records of its
// candidates (the first particle of each cell around it; with neighbour lists only the list).
// Events come in time order, which is random in space, so in a system larger than the cache
// each of these is a miss; asked for ahead, they arrive while the events before are worked
// on. In two stages, because the candidates are known only from the cell lists: first
// (deep = false) the lines of those lists, one event later (deep = true) the candidates'
// records.
void EventDriven::prefetch_around(int i, bool deep) const
{
  asm volatile("");    // (see EventQueue::prefetch_ahead)
  __builtin_prefetch(&H[i]);
  __builtin_prefetch(&img[i]);
  if (lists) {
    const Entry *e = &NB[(size_t) i * LCAP];
    if (!deep) {
      // its list centre and the lines of its list
      __builtin_prefetch(&XW[i]);
      __builtin_prefetch(e);
      __builtin_prefetch(e + 64 / sizeof(Entry));    // (the next cache line)
    } else if (S[i].ekind != CROSSING) {
      // the records of its first listed neighbours, which its scan's first lanes wait for;
      // the loads of the later ones overlap with the work on those (asking for every
      // neighbour's record was alike, bench/README.md)
      const int first = NN[i] < PREFETCH_LISTED ? NN[i] : PREFETCH_LISTED;
      for (int m = 0; m < first; m++) __builtin_prefetch(&H[e[m].j]);
    } else {
      // a list rebuild leaves its neighbours' lists (list_drop): the line of each reverse
      // entry, and the neighbour's count
      for (int m = 0; m < NN[i]; m++) {
        __builtin_prefetch(&NB[(size_t) e[m].j * LCAP + e[m].r]);
        __builtin_prefetch(&NN[e[m].j]);
      }
    }
    return;
  }
  // the cells around the one the particle is in, or, where its event is a crossing, the one
  // it enters (the cells inside the grid; at its edges nothing more)
  const Sched &p = S[i];
  int16_t c[3] = {p.c[0], p.c[1], p.c[2]};
  if (p.ekind == CROSSING) c[p.xdim] = (int16_t) (c[p.xdim] + p.xdir);
  const int dz1 = opt.dim == 3 ? 1 : 0;
  if (c[0] < 1 || c[0] + 1 >= nc[0] || c[1] < 1 || c[1] + 1 >= nc[1] || c[2] < dz1 || c[2] + dz1 >= nc[2])
    return;
  const int *base = head.data() + (c[2] * nc[1] + c[1]) * nc[0] + c[0];
  for (int dz = -dz1; dz <= dz1; dz++)
    for (int dy = -1; dy <= 1; dy++) {
      const int *row = base + (dz * nc[1] + dy) * nc[0];
      if (!deep) {
        __builtin_prefetch(row - 1);
        __builtin_prefetch(row + 1);
        continue;
      }
      for (int dx = -1; dx <= 1; dx++) {
        const int j = row[dx] & ~(row[dx] >> 31);    // (an empty cell, -1: particle 0, no branch)
        __builtin_prefetch(&H[j]);
        __builtin_prefetch(&img[j]);
      }
    }
}

void EventDriven::copy_keys()
{
  const int n = (int) H.size();
  for (int i = 0; i < n; i++) C[i].key = key(i);
}

// The events ahead, as the queue's walk along its next buckets meets their particles
// (EventQueue::prefetch_ahead): in stages over the next events, each reading what the one
// before asked for. A particle met now: its schedule and hot record; one event later the lines
// of the cell lists around it, and its collision partner's records; two events later the
// records of its first candidates, and the cell lists around the partner; three events later
// the partner's first candidates. The partner's cells and candidates only with neighbour
// lists or in systems of PARTNERS_FAR times the size from which the loop prefetches: below,
// they cost more than they save (bench/README.md).
void EventDriven::prefetch_upcoming()
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
    const Sched &si = S[i];
    const int q = si.ekind == COLLISION ? si.cpartner : -1;
    u.q[s1][k] = q;
    prefetch_cold(i);
    if (q >= 0)
      prefetch_partner(q);
    else if (si.cpartner >= 0)    // (a crossing reads its candidate partner's tick: stale())
      __builtin_prefetch(&C[si.cpartner].changed);
  }
  u.n[s0] = 0;
  queue.prefetch_ahead([this, &u, s0](int i) {
    __builtin_prefetch(&S[i]);
    __builtin_prefetch(&H[i]);
    if (u.n[s0] < Upcoming::MOST) u.p[s0][u.n[s0]++] = i;
  });
  u.turn++;
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
  copy_keys();
  upcoming = Upcoming();    // (indices of an earlier numbering, maybe of more particles)
  const long bytes = (long) memory_bytes();
  far = bytes > opt.prefetch_bytes;
  far_partners = far && (lists || bytes > PARTNERS_FAR * opt.prefetch_bytes);
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
    turned(i);    // every trajectory changed: all stored predictions are stale
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

void EventDriven::retick()
{
  const int n = (int) S.size();
  for (int i = 0; i < n; i++) {
    Sched &s = S[i];
    if (s.cpartner >= 0) s.ctick = stale(s) ? 0 : 1;
  }
  for (int i = 0; i < n; i++) C[i].changed = 1;
  tick = 1;
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
