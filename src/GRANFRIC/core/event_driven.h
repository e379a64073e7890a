// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the exact event-driven loop for one time window; its public interface.
//
// Particles fly freely (uniform gravity allowed) and collide instantaneously through a
// collision law (collision.h). Within a window [0, t_end) every pair collision is processed in
// exact time order; then every particle is advanced to t_end. Candidate partners come from a
// cell grid (cell width >= largest contact distance) kept exact by cell-crossing events, or, in
// dense 3d systems, from neighbour lists kept exact by list-rebuild events (neighbour_lists.cpp),
// so no pair can be missed whatever the window length. Per-particle local times and lazy
// updates, one scheduled event per particle, invalidation by a clock of trajectory changes, a
// calendar queue (event_queue.h), and the TC model of Luding & McNamara against inelastic
// collapse. Positions are unwrapped inside the window (periodic images are tracked by integer
// offsets, not by moving particles).
// The cell grid cannot change the rounding: a particle's stored state changes only at its own
// collisions and global events (a cell crossing leaves it alone), and a pair's contact time is
// computed from the two stored states alone (at the later of their times, the image shift
// taken off the difference of the positions), whoever predicts it and whenever; so within one
// time origin (no rebase()) the trajectory is the same bit for bit for any cell width, with
// cells or neighbour lists.
//
// This header is the core's public interface: the class EventDriven and what its functions do.
// The values it takes and gives (EDParticle, EDWall, EDOptions, EDStats, ...) are ed_types.h; the
// records of the particles and the private functions are ed_core.h (EDCore, from which
// EventDriven derives privately). The functions, one role per file:
//   event_driven.cpp     the event loop: start, the events of a window in time order, pair
//                        collisions, the clock of trajectory changes, time shifts
//   options.cpp          the options: their checks, configure(), same_configuration(), and their
//                        one field list's uses (EDOptions::describe)
//   particle_slots.cpp   the particles' slots: resize(), remove(), changed(), nudge(), last
//                        partners and frames
//   global_events.cpp    instants at which every particle may change (kicks)
//   prefetch.cpp         asking the memory ahead for the records of the events to come
//   cells.cpp            the cell grid, cell order and cell crossings
//   shear.cpp            Lees-Edwards boundaries: bands of rows of cells moving with the flow, shear ticks
//   candidate_search.cpp the search for collision candidates and their contact times (four at a
//                        time in AVX2 lanes: candidate_lanes.cpp), and for overlaps
//   neighbour_lists.cpp  neighbour lists and their rebuild events
//   wall_motion.cpp      wall motion and wall contact times; wall_response.cpp: the response at
//                        walls
//   statistics.cpp       statistics, tallies and records of the collisions
// The collision laws are collision.h, their table law_table.h (with the normal restitution
// models; the viscoelastic one is viscoelastic.h), driving by kicks kicks.h.
#ifndef GRANFRIC_CORE_EVENT_DRIVEN_H
#define GRANFRIC_CORE_EVENT_DRIVEN_H

#include "ed_core.h"
#include "ed_types.h"

#include <cmath>
#include <functional>
#include <utility>
#include <vector>

namespace granfric {

class EventDriven : private EDCore {
 public:
  // laws: (ntypes+1)^2 table indexed [itype * (ntypes+1) + jtype]
  void configure(const EDOptions &opt, int ntypes, const std::vector<LawParams> &laws);
  const EDOptions &options() const { return opt; }
  // true if configure(o, ntypes, laws) would change nothing (a kept event queue stays valid)
  bool configured_as(const EDOptions &o, int ntypes, const std::vector<LawParams> &laws) const
  {
    return same_configuration(o, ntypes, laws, opt, this->ntypes, this->laws);
  }
  static bool same_configuration(const EDOptions &a, int nta, const std::vector<LawParams> &la,
                                 const EDOptions &b, int ntb, const std::vector<LawParams> &lb);

  // particles by external index 0..n-1 (the order they were given in); internally they are
  // kept in cell order for memory locality
  void resize(int n);
  int size() const { return (int) flights.size(); }
  EDParticle particle(int e) { return ref(loc[e]); }
  EDParticleView particle(int e) const { return view(loc[e]); }

  // process every event in [0, t_end) and advance all particles to t_end
  EDStats run(double t_end);

  // the same in pieces, keeping the event queue between windows:
  //   start()          cells and predictions from the particles' x, v, w at time 0
  //   advance_to(t)    process every event before t (lazy states are not advanced;
  //                    read them with position() / velocity())
  //   rebase(dt)       subtract dt from every time, so the next window starts at 0 again
  // A window sequence start, advance_to(dt), rebase(dt), advance_to(dt), ... follows the same
  // trajectory as one long window, up to the rounding of the time shifts; without rebase()
  // (windows ending at dt, 2 dt, ...: one time origin) it is that trajectory bit for bit.
  //   start_at(t)      start() at window time t from particles whose stored states (x, v at
  //                    their own times particle(e).t <= t, w, t_last, last partners) are kept
  //                    as they are: the same predictions, bit for bit, as the core that
  //                    computed those states holds (a new cell grid, the same trajectory)
  void start();
  void start_at(double t);
  EDStats advance_to(double t_end);
  void rebase(double dt);

  // Changes from outside between windows, keeping the queue (after rebase(), before the next
  // advance_to()), for a caller whose system changes only in part: the copies of other ranks'
  // atoms in domain-decomposed windows. An external index is a slot that may be empty.
  //   remove(e)    particle e leaves the system: its slot keeps no cell and no event (before
  //                start(): the slot starts empty)
  //   changed(e)   the caller set particle(e)'s x, v and w (their values at window time now)
  //                and maybe a (up to cell_radius()), m, q, type, t_last; an empty slot is
  //                filled. The particle moves to its new cell, every prediction that involved
  //                it goes stale, and the next advance_to() first predicts it afresh against
  //                every neighbour (after all changes, so changed neighbours see each other).
  // The result is the exact trajectory of the changed system, as a new start() would give,
  // at the cost of the changed particles only.
  //   nudge(e, x, v, w)   x, v and w (3 values each, at window time now) are particle e's
  //                own trajectory again, computed with other rounding (by another rank, on
  //                another cell grid): they replace its state and its predictions stand (they
  //                are those of the same trajectory up to rounding).
  //                Only if the new position lies in the particle's cell (else nothing changes
  //                and it returns false: use changed()). The caller bounds the difference.
  //                With neighbour lists it always returns false.
  //   changed(e, true)    the same, but x and v are given at their own time particle(e).t
  //                (<= now), as another core stored them, not re-rounded to now
  // Between changed() (which forgets it) and the next advance_to(), or before start_at():
  //   set_last_partner(e, p, off)   e's last collision was with p (-1: none) at the image
  //                shift off (p's stored position + off * period next to e's), as the core that
  //                computed e's state has it: two particles that last collided with each other
  //                are no candidates for each other (their contact right after the collision
  //                is rounding)
  //   set_frame(e, f)    particle e's stored position lies f[d] periods (EDOptions::period)
  //                below where this core's cell grid sees it, in each open dimension with a
  //                period (0 elsewhere); before start_at() or changed()
  void remove(int e);
  void changed(int e, bool own_time = false);
  void set_last_partner(int e, int p, const int off[3]);
  int last_partner(int e) const
  {
    const int j = colliders[loc[e]].last_partner;
    return j < 0 ? -1 : ext[j];
  }
  const int *last_offset(int e) const { return schedules[loc[e]].last_off; }
  void set_frame(int e, const int f[3]);
  bool nudge(int e, const double *x, const double *v, const double *w);
  bool present(int e) const { return !schedules[loc[e]].gone; }
  // the largest radius the cell grid of the last start() admits
  double cell_radius() const { return cell_amax; }
  double cell_size() const { return cw[0]; }    // the cell width in x (after start())
  int shear_band_count() const { return nbands; }    // a sheared box's bands of rows (after start())
  using EDCore::have_lanes;              // the processor has AVX2 (EDOptions::simd can use it)
  bool uses_lists() const { return lists; }     // neighbour lists (after start())
  using EDCore::MAX_LISTS;               // the most particles that get lists automatically
  // the width of cells the core chooses for number density n (EDOptions::cell_width = 0), with
  // sigma the largest contact distance
  using EDCore::auto_cell_width;

  // Instant events that change many particles at once (random kicks): at each of the given
  // window times (ascending, processed before t_end by the next advance_to) every particle is
  // brought to that time, apply(k) may change velocities and spins through particle(e), the
  // kinetic energy change is booked as injected, and every prediction is made afresh.
  void set_global_events(const std::vector<double> &times, std::function<void(int)> apply);

  // optional per-window records: every collision into *h
  // with `only` (a flag per particle, external index, kept alive by the caller): only the
  // events of flagged particles (pair collisions with at least one flagged partner)
  void record_events(std::vector<EDEvent> *h, const uint8_t *only = nullptr)
  {
    history = h;
    record_only = only;
  }
  // optional per-window list of the booked collisions (pairs and walls) into *log
  void record_collisions(std::vector<EDCollisionRecord> *log) { collision_log = log; }
  // Optional per-particle tallies of each window (by external index; every collision a particle
  // takes part in, booked here or not; what they hold: EDParticleTally). Of the collision virial
  // a particle gets half of a pair collision's r_a dP_b and the whole of a wall collision's.
  using ParticleTally = EDParticleTally;
  void tally_particles(bool on) { tally_on = on; }
  const ParticleTally &particle_tally(int e) const { return tallies[e]; }
  // Fast particles, for a bound on how far particles travel in a window (the guard of domain
  // windows): after track_fast(s2), every velocity change (collision, wall, kick) that leaves
  // a particle with a squared speed of s2 or more lists it with that squared speed, in the
  // order they happen (a particle may be listed more than once). A particle never listed had,
  // right after each of its velocity changes in the window, a squared speed below s2; with its
  // squared speed s0 at window time 0 its path up to window time t is then at most
  // path_bound(max(s0, s2), t). track_fast(INF): off (the default).
  void track_fast(double s2)
  {
    fast_s2 = s2;
    fast_on = s2 != INF;
    fast.clear();
  }
  const std::vector<std::pair<int, double>> &fast_list() const { return fast; }
  // the path length bound from a largest squared speed s2 over [0, t]: between velocity
  // changes gravity changes the speed by at most |g| t
  double path_bound(double s2, double t) const { return t * (std::sqrt(s2) + 0.5 * t * norm(opt.gravity)); }
  void set_accounting(EDAccounting a) { acct = a; }

  // Pairs that overlap by more than tol times their contact distance at the current time
  // (after start()), counted once (where the partner with the smaller key is counted); the
  // keys of the deepest one and its overlap depth. The dynamics copes with overlaps (an
  // approaching pair collides at once, a receding one separates), but they are usually a
  // mistake in the initial configuration.
  long overlaps(double tol, long &key_i, long &key_j, double &depth) const;

  // bytes held (particles, index maps, cells, queue, optional records)
  size_t memory_bytes() const
  {
    return flights.capacity() * sizeof(Flight) + colliders.capacity() * sizeof(Collider) +
        last_collision.capacity() * sizeof(double) + schedules.capacity() * sizeof(Schedule) +
        wall_times.capacity() * sizeof(double) + images.capacity() * sizeof(CellImage) +
        (ext.capacity() + loc.capacity()) * sizeof(int) + list_centres.capacity() * sizeof(Vec3) +
        list_entries.capacity() * sizeof(ListEntry) + list_counts.capacity() +
        tallies.capacity() * sizeof(EDParticleTally) + head.capacity() * sizeof(int) +
        queue.memory_bytes() + fast.capacity() * sizeof(fast[0]) + gtimes.capacity() * sizeof(double);
  }

  // Lees-Edwards (EDOptions::shear): the x shift s of the image one period up in y at window
  // time 0 (before start(); rebase() advances it by the shear rate). start() and the window's
  // events keep it within [0, L_x] by whole periods (the images' labels follow), so that it is
  // s plus or minus whole periods of x afterwards
  void set_shear_shift(double s);
  double shear_shift() const { return shear_s0; }
  // absolute time of window time 0 (the phase of vibrating walls); rebase() advances it
  void set_clock(double t) { clock = t; }
  double get_clock() const { return clock; }

  // a free flight as the core computes it (pos(), vel()): position and velocity x, v brought
  // forward by dt under gravity g (grav: g is not zero), the same bits
  using EDCore::flight_x;
  using EDCore::flight_v;
  // the frame shift of particle e (set_frame), or null without frames
  const int *frame(int e) const { return frames.empty() ? nullptr : frames[loc[e]].f; }

  // state of particle e (external index) at window time t (lazy update, not stored)
  Vec3 position(int e, double t) const { return pos(loc[e], t); }
  Vec3 velocity(int e, double t) const { return vel(loc[e], t); }
  // does particle e have radius a, mass m and type ty (bit for bit)?
  bool is_body(int e, double a, double m, int ty) const
  {
    const int i = loc[e];
    return flights[i].a == a && colliders[i].m == m && schedules[i].type == ty;
  }
  // does particle e hold, bit for bit, radius a, mass m, type ty and, at window time t,
  // position x, velocity v and angular velocity w (3 values each)?
  bool holds(int e, double t, const double *x, const double *v, const double *w, double a, double m,
             int ty) const
  {
    if (!is_body(e, a, m, ty)) return false;
    const int i = loc[e];
    const Vec3 xs = pos(i, t), vs = vel(i, t), &ws = colliders[i].w;
    return x[0] == xs.x && x[1] == xs.y && x[2] == xs.z && v[0] == vs.x && v[1] == vs.y &&
        v[2] == vs.z && w[0] == ws.x && w[1] == ws.y && w[2] == ws.z;
  }
  // Performance only: ask the memory for what state(), holds() and is_body() read of particle
  // e, for a host that walks every particle and calls it some particles ahead
  void prefetch_particle(int e) const
  {
    asm volatile("");    // (see EventQueue::prefetch_ahead)
    const int i = loc[e];
    __builtin_prefetch(&flights[i]);
    __builtin_prefetch(&schedules[i]);
    prefetch_collider(i);
  }
  // position, velocity and angular velocity of particle e at window time t into x, v, w (3
  // values each): what position(), velocity() and particle().w give, with one index lookup
  void state(int e, double t, double *x, double *v, double *w) const
  {
    const int i = loc[e];
    pos(i, t).to(x);
    vel(i, t).to(v);
    colliders[i].w.to(w);
  }
};

}    // namespace granfric

#endif
