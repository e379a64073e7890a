// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the exact event-driven loop for one time window.
//
// Particles fly freely (uniform gravity allowed) and collide instantaneously through a
// collision law (collision.h). Within a window [0, t_end) every pair collision is processed in
// exact time order; then every particle is advanced to t_end. Candidate partners come from a
// cell grid (cell width >= largest contact distance) kept exact by cell-crossing events, or, in
// dense 3d systems, from neighbour lists kept exact by list-rebuild events (neighbour_lists.cpp),
// so no pair can be missed whatever the window length. Per-particle local times and lazy updates, one
// scheduled event per particle, invalidation by a clock of trajectory changes, a calendar queue
// (event_queue.h), and the TC model of Luding & McNamara against inelastic collapse. Positions are unwrapped inside
// the window (periodic images are tracked by integer offsets, not by moving particles).
// The cell grid cannot change the rounding: a particle's stored state changes only at its own
// collisions and global events (a cell crossing leaves it alone), and a pair's contact time is
// computed from the two stored states alone (at the later of their times, the image shift
// taken off the difference of the positions), whoever predicts it and whenever; so within one
// time origin (no rebase()) the trajectory is the same bit for bit for any cell width, with
// cells or neighbour lists.
//
// One class, its roles in one file each: the event loop and pair collisions (event_driven.cpp),
// the options and their checks (options.cpp), the particles' slots and the changes from outside
// between windows (particle_slots.cpp), global events (global_events.cpp), asking the memory
// ahead for the events to come (prefetch.cpp), the cell grid and its crossings (cells.cpp), the
// search for collision candidates (candidate_search.cpp; four at a time in AVX2 lanes:
// candidate_lanes.cpp), neighbour lists (neighbour_lists.cpp), wall motion and contact times
// (wall_motion.cpp), the response at walls (wall_response.cpp), statistics and records of the
// collisions (statistics.cpp). The collision laws are collision.h, their table law_table.h,
// driving by kicks kicks.h.
#ifndef GRANFRIC_CORE_EVENT_DRIVEN_H
#define GRANFRIC_CORE_EVENT_DRIVEN_H

#include "collision.h"
#include "event_queue.h"
#include "huge_alloc.h"
#include "prediction.h"

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

// the candidate search tests four candidates at once in AVX2 lanes (candidate_lanes.cpp) where
// the compiler can target them function by function; elsewhere one at a time
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define GRANFRIC_LANES 1
#else
#define GRANFRIC_LANES 0
#endif

namespace granfric {

// A particle as the user sets and reads it: references into the core's storage (x, v, t, a
// are kept in one 64-byte record that every candidate-partner test reads, w, m, q apart, type
// with the particle's schedule). Assigning one EDParticle to another copies the values.
// t_last (the time of the last collision, for the TC model) is kept only while tc > 0: without
// the TC model it plays no part, reads -inf, and what is written to it is dropped.
template <bool CONST>
struct EDParticleT {
  template <class T>
  using R = std::conditional_t<CONST, const T &, T &>;
  R<Vec3> x, v;          // position (unwrapped), velocity
  R<double> t, a;        // local time of x and v (internal), radius
  R<Vec3> w;             // angular velocity
  R<double> m;           // mass
  const double &q;       // moment of inertia / (m a^2): its type's (EDOptions::shape), read-only
  R<double> t_last;      // time of the last collision (window time), for the TC model
  R<int16_t> type;       // 1 .. ntypes
  template <bool C>
  EDParticleT &operator=(const EDParticleT<C> &o)
  {
    static_assert(!CONST, "a const particle cannot be assigned");
    x = o.x, v = o.v, t = o.t, a = o.a, w = o.w, m = o.m, t_last = o.t_last, type = o.type;
    return *this;
  }
  EDParticleT &operator=(const EDParticleT &o) { return operator=<CONST>(o); }
  EDParticleT(const EDParticleT &) = default;
  EDParticleT(R<Vec3> x_, R<Vec3> v_, R<double> t_, R<double> a_, R<Vec3> w_, R<double> m_,
              const double &q_, R<double> tl_, R<int16_t> ty_) :
      x(x_), v(v_), t(t_), a(a_), w(w_), m(m_), q(q_), t_last(tl_), type(ty_)
  {
  }
};
using EDParticle = EDParticleT<false>;
using EDParticleView = EDParticleT<true>;

// A static plane wall normal to dimension dim at position pos: side -1 bounds the particles
// from below (they live at x[dim] > pos, the wall normal is +e_dim), side +1 from above. The
// collision law is the wall limit of the particle's law, per particle type.
struct EDWall {
  int dim = 1;
  int side = -1;
  double pos = 0.0;
  std::vector<LawParams> laws;    // by particle type (index 0 unused)
  // thermal wall (T >= 0): a particle that hits it leaves with a velocity drawn from the
  // Maxwellian flux at T (normal component Rayleigh, tangential Gaussian) and a spin drawn from
  // the Maxwellian at T; random numbers from (seed, particle, collision time)
  double T = -1.0;
  uint64_t seed = 1;
  // vibration of a lower wall (side -1): piecewise constant acceleration that mimics
  // pos + A sin(omega t) (Risso et al. ref. 13): acceleration -aw on the half periods where the
  // sinusoid is positive, +aw on the others, aw = 8 A omega^2 / pi^2 (same amplitude, period)
  double A = 0.0, omega = 0.0;
  bool sine = false;              // true: pos + A sin(omega t) itself (contacts by safe search)
  bool vibrating() const { return A > 0.0 && omega > 0.0; }
  // the wall's largest speed: A omega (sine), 4 A omega / pi (parabolic), 0 (static)
  double speed_bound() const { return !vibrating() ? 0.0 : sine ? A * omega : 4.0 * A * omega / M_PI; }
  // position, velocity and acceleration at absolute time s
  void motion(double s, double &w, double &vw, double &aw) const;
};

struct EDOptions {
  int dim = 3;                          // 2: motion in x-y, spin about z; 3: full
  double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  bool periodic[3] = {true, true, true};
  // a non-periodic dimension needs a wall unless it is open: particles may leave [lo, hi]
  // (they stay in the edge cells), as in a piece of a larger system
  bool open[3] = {false, false, false};
  // > 0 in an open dimension: the period of that larger system. A particle's stored position
  // may then lie whole periods away from where [lo, hi] sees it (its frame, set_frame()): pair
  // distances take the periods off as integers, as periodic images do, so a particle keeps
  // the stored position its owner computed
  double period[3] = {0, 0, 0};
  Vec3 gravity;
  double tc = 0.0;                      // TC model duration (0: off)
  long max_collisions = 1000000;        // per particle per window (inelastic-collapse guard)
  int gamma_bins = 0;                   // > 0: histogram of impact angles in (pi/2, pi]
  std::vector<EDWall> walls;            // in non-periodic dimensions
  // moment of inertia / (m a^2) by particle type (index 0 unused), each in (0, 1]; empty:
  // 0.4 (solid spheres) for every type
  std::vector<double> shape;
  // > 0: cells at least this wide (never narrower than the largest contact distance); 0: the
  // automatic width (see setup_cells). For benchmarks of the cell width.
  double cell_width = 0.0;
  // how candidate partners are found: CELLS (cell crossings), LISTS (neighbour lists; not with
  // gravity) or AUTO (lists in small dense 3d systems without gravity, see choose_lists)
  enum Neighbours { AUTO = 0, CELLS = 1, LISTS = 2 };
  int neighbours = AUTO;
  // > 0: the skin of neighbour lists in units of the largest contact distance sigma (lists hold
  // the pairs whose list centres lie within sigma (1 + skin)); 0: the automatic skin
  double list_skin = 0.0;
  // true: scans in 3d without gravity (cells or lists) test four candidates at once in AVX2
  // lanes where the processor has them (the same candidates are found: the trajectories are the
  // same bits); false: one at a time
  bool simd = true;
  // from how many bytes of the core's records (memory_bytes()) on the event loop asks the
  // memory ahead for the records of the events to come (performance only: the trajectories are
  // the same bits). Below, the records mostly stay in the cache and asking costs up to 18 %;
  // around 5 MB it is alike, from 7 MB on faster (bench/README.md)
  long prefetch_bytes = 5L << 20;
  // the clock of trajectory changes that marks stale predictions starts again from 1 once it
  // reaches this value (the predictions keep what they were; for tests of that restart, which
  // the 32-bit clock otherwise reaches after about 4e9 collisions)
  uint32_t tick_last = 0xfffffffeu;
};

struct EDStats {
  // (crossings: the neighbour structure's own events, cell crossings or list rebuilds)
  long collisions = 0, sliding = 0, tc_elastic = 0, energy_created = 0, crossings = 0;
  long max_collisions_one_particle = 0;
  double dE = 0.0;                      // sum of pair collision energy changes (< 0: dissipated)
  long wall_collisions = 0;
  double dE_wall = 0.0;                 // sum of wall collision energy changes
  double injected = 0.0;                // kinetic energy added by instant global events (kicks)
  // collision virial: the sum over the booked collisions (pairs and walls) of r_a dP_b, with r
  // the contact vector (from partner j's centre to i's, or from the wall's contact point to the
  // particle's centre) and dP the impulse on i; components xx, yy, zz, xy, xz, yz (r_x dP_y ...)
  double virial[6] = {0, 0, 0, 0, 0, 0};
  // per wall (EDOptions::walls order): collisions, the momentum given to the wall (3 values per
  // wall, minus the sum of the particles' impulses) and the kinetic energy it gave the particles
  std::vector<long> wall_hits;
  std::vector<double> wall_impulse, wall_work;
  long global_events = 0;
  std::vector<long> gamma_hist;         // impact angles, EDOptions::gamma_bins bins
  void add(const EDStats &o);           // (the vectors grow to o's sizes)

  // Every summed field (all but max_collisions_one_particle, a maximum), in one fixed order:
  // f(field of s...) for each, with the fields of every s given (long, double,
  // std::vector<long> or std::vector<double>, by reference). The one list of the fields, for
  // sums over windows (add) and over ranks (flatten).
  template <class F, class... S>
  static void each_sum(F &&f, S &...s)
  {
    f(s.collisions...), f(s.sliding...), f(s.tc_elastic...), f(s.energy_created...);
    f(s.crossings...), f(s.wall_collisions...), f(s.global_events...);
    f(s.dE...), f(s.dE_wall...), f(s.injected...);
    for (int k = 0; k < 6; k++) f(s.virial[k]...);
    f(s.wall_hits...), f(s.wall_impulse...), f(s.wall_work...), f(s.gamma_hist...);
  }
  // the summed fields as two flat arrays (vectors element by element) and back from arrays
  // of those sizes: what a sum over ranks reduces
  void flatten(std::vector<long> &counts, std::vector<double> &sums) const;
  void unflatten(const long *counts, const double *sums);
};

// One collision of a window, for the cross-rank consistency check of domain-decomposed runs:
// window time, the particles (external indices; j = -1 - k for wall k) and their velocities and
// spins right after it. Global events (kicks) are not recorded: they act alike on every copy.
struct EDEvent {
  double t;
  int i, j;
  Vec3 vi, wi, vj, wj;
};

// One booked collision, for per-collision output: window time, the particles (external indices;
// j = -1 - k for wall k) and what the collision law reports of it
struct EDCollisionRecord {
  double t;
  int i, j;
  double gn, gt, cos_gamma;    // before: g.n (< 0 approaching), |g_t|, cos of the impact angle
  double jn;                   // normal impulse |dP . n|
  double dE;                   // kinetic energy change (for a moving wall: in the lab frame)
  bool sliding;
};

// Accounting of a window that covers part of a larger system (the owned atoms of an MPI rank
// plus copies of its neighbours' atoms): key = a global identity per particle (external index;
// also seeds the thermal walls' random numbers), counted = the particles whose events this
// window books. A pair collision is booked where its particle with the smaller key is counted,
// so every collision is booked exactly once over all ranks. Both are arrays by external index
// that the caller keeps alive and unchanged while the core uses them; none: everything is
// counted, keys = indices.
struct EDAccounting {
  const long *key = nullptr;
  const uint8_t *counted = nullptr;
};

// thrown when a window exceeds its work cap: a particle with more than max_collisions
// collisions (COLLISIONS: inelastic collapse), or more than max_collisions times the number of
// particles cell crossings or list rebuilds in all (CROSSINGS: particles far faster than the
// system's scale, e.g. after a law created energy)
class EventCapError : public std::runtime_error {
 public:
  enum Kind { COLLISIONS, CROSSINGS };
  EventCapError(const std::string &what, int i_, int j_, double t_, long n_, Kind k = COLLISIONS,
                double speed_ = 0.0) :
      std::runtime_error(what), i(i_), j(j_), t(t_), n(n_), kind(k), speed(speed_)
  {
  }
  int i, j;      // particle indices of the event that crossed the cap (j = i: a cell crossing;
                 // j < 0: a collision with wall -1 - j)
  double t;      // window time
  long n;        // COLLISIONS: collisions of particle i in this window; CROSSINGS: all crossings
  Kind kind;
  double speed;  // CROSSINGS: particle i's speed then
};

class EventDriven {
 public:
  enum { NONE = 0, COLLISION = 1, CROSSING = 2, WALL = 3 };

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
  int size() const { return (int) H.size(); }
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
    const int j = C[loc[e]].last_partner;
    return j < 0 ? -1 : ext[j];
  }
  const int *last_offset(int e) const { return S[loc[e]].last_off; }
  void set_frame(int e, const int f[3]);
  bool nudge(int e, const double *x, const double *v, const double *w);
  bool present(int e) const { return !S[loc[e]].gone; }
  // the largest radius the cell grid of the last start() admits
  double cell_radius() const { return cell_amax; }
  double cell_size() const { return cw[0]; }    // the cell width in x (after start())
  static bool have_lanes();              // the processor has AVX2 (EDOptions::simd can use it)
  bool uses_lists() const { return lists; }     // neighbour lists (after start())
  static constexpr long MAX_LISTS = 40000;    // the most particles that get lists automatically
  // the width of cells the core chooses for number density n (EDOptions::cell_width = 0), with
  // sigma the largest contact distance
  static double auto_cell_width(int dim, double sigma, double n);

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
  // takes part in, booked here or not): the collision virial (6 values as EDStats::virial, half
  // of a pair collision's r_a dP_b to each partner, a wall collision's to its particle), its
  // pair and wall collisions, the changes of its translational and rotational kinetic energy in
  // pair collisions and of its kinetic energy in wall collisions, and the window time of its
  // last collision (-inf: none)
  struct ParticleTally {
    double virial[6];
    double collisions, wall_collisions, dE_tr, dE_rot, dE_wall, t_last;
  };
  void tally_particles(bool on) { tally_on = on; }
  const ParticleTally &particle_tally(int e) const { return PT[e]; }
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
    return H.capacity() * sizeof(Hot) + C.capacity() * sizeof(Cold) +
        TL.capacity() * sizeof(double) + S.capacity() * sizeof(Sched) + WT.capacity() * sizeof(double) +
        img.capacity() * sizeof(Image) + (ext.capacity() + loc.capacity()) * sizeof(int) +
        XW.capacity() * sizeof(Vec3) + NB.capacity() * sizeof(Entry) + NN.capacity() +
        PT.capacity() * sizeof(ParticleTally) +
        head.capacity() * sizeof(int) + queue.memory_bytes() +
        fast.capacity() * sizeof(fast[0]) + gtimes.capacity() * sizeof(double);
  }

  // absolute time of window time 0 (the phase of vibrating walls); rebase() advances it
  void set_clock(double t) { clock = t; }
  double get_clock() const { return clock; }

  // a free flight as the core computes it (pos(), vel()): position and velocity x, v brought
  // forward by dt under gravity g (grav: g is not zero), the same bits
  static Vec3 flight_x(const Vec3 &x, const Vec3 &v, double dt, const Vec3 &g, bool grav)
  {
    return grav ? x + dt * v + (0.5 * dt * dt) * g : x + dt * v;
  }
  static Vec3 flight_v(const Vec3 &v, double dt, const Vec3 &g) { return v + dt * g; }
  // the frame shift of particle e (set_frame), or null without frames
  const int *frame(int e) const { return FR.empty() ? nullptr : FR[loc[e]].f; }

  // state of particle e (external index) at window time t (lazy update, not stored)
  Vec3 position(int e, double t) const { return pos(loc[e], t); }
  Vec3 velocity(int e, double t) const { return vel(loc[e], t); }
  // does particle e have radius a, mass m and type ty (bit for bit)?
  bool is_body(int e, double a, double m, int ty) const
  {
    const int i = loc[e];
    return H[i].a == a && C[i].m == m && S[i].type == ty;
  }
  // does particle e hold, bit for bit, radius a, mass m, type ty and, at window time t,
  // position x, velocity v and angular velocity w (3 values each)?
  bool holds(int e, double t, const double *x, const double *v, const double *w, double a, double m,
             int ty) const
  {
    if (!is_body(e, a, m, ty)) return false;
    const int i = loc[e];
    const Vec3 xs = pos(i, t), vs = vel(i, t), &ws = C[i].w;
    return x[0] == xs.x && x[1] == xs.y && x[2] == xs.z && v[0] == vs.x && v[1] == vs.y &&
        v[2] == vs.z && w[0] == ws.x && w[1] == ws.y && w[2] == ws.z;
  }
  // Performance only: ask the memory for what state(), holds() and is_body() read of particle
  // e, for a host that walks every particle and calls it some particles ahead
  void prefetch_particle(int e) const
  {
    asm volatile("");    // (see EventQueue::prefetch_ahead)
    const int i = loc[e];
    __builtin_prefetch(&H[i]);
    __builtin_prefetch(&S[i]);
    prefetch_cold(i);
  }
  // position, velocity and angular velocity of particle e at window time t into x, v, w (3
  // values each): what position(), velocity() and particle().w give, with one index lookup
  void state(int e, double t, double *x, double *v, double *w) const
  {
    const int i = loc[e];
    pos(i, t).to(x);
    vel(i, t).to(v);
    C[i].w.to(w);
  }

 private:
  // the particles in internal order: what every candidate-partner test reads (one cache line),
  // and what only a collision reads
  struct alignas(64) Hot {
    Vec3 x, v;                // position (unwrapped), velocity
    double t = 0.0;           // local time of x and v
    double a = 0.5;           // radius
  };
  static_assert(sizeof(Hot) == 64, "what a pair prediction reads fills one cache line");
  struct Cold {
    long key = 0;             // key(i), copied for the event loop (copy_keys)
    Vec3 w;                   // angular velocity
    double m = 1.0;           // mass (the shape factor q is its type's: qt)
    int last_partner = -1;    // partner of the last collision
    uint32_t changed = 0;     // the tick of its last change of trajectory (see tick)
  };
  static_assert(sizeof(Cold) == 48, "the key, w, m, the last partner and the tick: 48 bytes");
  big_vector<Hot> H;
  big_vector<Cold> C;
  // Stale predictions. Every change of a particle's trajectory (a collision, a wall, a change
  // from outside) advances one clock, tick, and stores it in the particle's Cold record
  // (changed); a prediction stores the tick at which it was made (Sched::ctick) and is stale
  // once its partner changed later. So a scan writes its best candidate without reading
  // anything of it, and the event loop reads the Cold record of each event's partner, which a
  // valid collision needs anyway
  uint32_t tick = 0;
  void turned(int i)
  {
    if (tick >= opt.tick_last) retick();
    C[i].changed = ++tick;
  }
  void turned(int i, int j)    // (one change of both: the same tick)
  {
    turned(i);
    C[j].changed = tick;
  }
  void retick();    // the clock back to 1, every prediction as stale or fresh as it was
                    // (past EDOptions::tick_last)
  big_vector<double> TL;                 // time of the last collision (only with tc > 0)
  double tl_none = -INF;                 // what t_last refers to without the TC model
  static constexpr double TL_NONE = -INF;    // (read-only views: no store to tl_none)
  EDParticle ref(int i)
  {
    Hot &h = H[i];
    Cold &c = C[i];
    double &tl = TL.empty() ? (tl_none = -INF) : TL[i];
    return EDParticle(h.x, h.v, h.t, h.a, c.w, c.m, qt[S[i].type], tl, S[i].type);
  }
  EDParticleView view(int i) const
  {
    const Hot &h = H[i];
    const Cold &c = C[i];
    const double &tl = TL.empty() ? TL_NONE : TL[i];
    return EDParticleView(h.x, h.v, h.t, h.a, c.w, c.m, qt[S[i].type], tl, S[i].type);
  }
  // the TC model: did i collide within tc before t? (only with tc > 0; a last collision 'in the
  // future' after a clock reset does not count)
  bool tc_recent(int i, double t) const
  {
    if (TL.empty()) return false;
    const double since = t - TL[i];
    return since >= 0.0 && since < opt.tc;
  }
  // a particle's own event bookkeeping, read only when it is predicted or processed: one cache
  // line (the next wall collision, which only systems with walls have, is kept apart in WT)
  struct alignas(64) Sched {
    int16_t c[3] = {0, 0, 0}; // cell coordinates within the grid (at most 32767 cells a side)
    int16_t type = 1;         // the particle's type (at most 32767 types)
    int8_t gone = 0;          // an empty slot (remove()): no cell, no event
    int8_t ekind = 0;         // scheduled event: NONE, COLLISION, CROSSING, WALL
    int8_t xdim : 4, xdir : 4;    // crossing dimension and direction (+1 / -1)
    int8_t wall = -1;         // which wall
    int cpartner = -1;        // collision candidate: partner,
    uint32_t ctick = 0;       //   the tick at prediction (stale when the partner changed later),
    uint32_t ncollisions = 0; // collisions in this window (event cap)
    int coff[3] = {0, 0, 0};  //   partner's unwrapped position is shifted by coff * P
    int last_off[3] = {0, 0, 0};    // periodic image offset of the last partner (see coff)
    double ct = NEVER;        //   and time
    double xt = NEVER;        // next cell crossing: time
    Sched() : xdim(0), xdir(0) {}
  };
  static_assert(sizeof(Sched) == 64, "a particle's schedule fills one cache line");
  // whether a schedule's collision candidate went stale: its partner changed course since
  bool stale(const Sched &s) const { return C[s.cpartner].changed > s.ctick; }
  big_vector<Sched> S;
  big_vector<double> WT;                 // next wall collision: time (empty without walls)
  // periodic image of each particle's cell, and the next particle in its cell's list: what
  // the candidate-partner search reads of a particle besides its hot record, so one 16-byte
  // record (neighbours in cell order share its cache lines)
  struct Image {
    int k[3];
    int next;
  };
  big_vector<Image> img;
  big_vector<int> ext, loc;             // internal -> external index, and back
  long crossings_since_reorder = 0;
  double clock = 0.0;
  std::vector<EDEvent> *history = nullptr;
  std::vector<EDCollisionRecord> *collision_log = nullptr;
  bool tally_on = false;
  std::vector<ParticleTally> PT;         // (tally_particles)
  // particle i's part in a collision at t: r (x) dP (halved for a pair), its energy changes
  void tally(int i, const Vec3 &r, const Vec3 &dP, double t, double dE_tr, double dE_rot, bool wall);
  // the one hook per collision into the statistics and records (statistics.cpp)
  void record_pair(int i, int j, double t, const Vec3 &r, const Vec3 &n, const Body &b1, const Body &b2,
                   const Collision &c, bool tc_elastic, long ni, long nj);
  void record_wall(int i, int k, double t, const Vec3 &n, const Vec3 &dP, const Collision &c,
                   double dE_tr, double dE_rot, bool tc_elastic, long ni);
  const uint8_t *record_only = nullptr;
  double fast_s2 = INF;                  // track_fast(): the threshold, and who reached it
  bool fast_on = false;
  std::vector<std::pair<int, double>> fast;
  bool tracking_fast() const { return fast_on; }
  void note_speed(int i, const Vec3 &v)    // (only while tracking_fast())
  {
    const double s2 = norm2(v);
    if (s2 >= fast_s2) fast.emplace_back(ext[i], s2);
  }
  EDAccounting acct;
  bool counted(int i) const { return !acct.counted || acct.counted[ext[i]]; }
  long key(int i) const { return acct.key ? acct.key[ext[i]] : (long) ext[i]; }
  // key(i) as copy_keys() left it in i's record at the start of advance_to(): in the event loop
  // a pair's order costs no lookups through ext and the accounting's keys, which in a large
  // system are two cache misses per particle
  long loop_key(int i) const { return C[i].key; }
  void copy_keys();
  long window_crossings = 0, crossing_cap = 0;    // (this window's, and its cap)
  void count_crossing(int i);            // throws EventCapError past the cap
  std::vector<double> gtimes;            // pending global events
  std::function<void(int)> gapply;
  void global_event(int k);
  EDOptions opt;
  bool has_gravity = false;
  int ntypes = 0;
  std::vector<LawParams> laws;
  std::vector<double> qt = {0.4, 0.4};   // moment of inertia / (m a^2) by type (configure)
  Vec3 L;                                // box lengths
  Vec3 P;                                // periods of image shifts (L if periodic, else period)
  // an image shift of a, b, c periods as a displacement
  Vec3 periods(int a, int b, int c) const { return Vec3(a * P.x, b * P.y, c * P.z); }
  bool framed = false;                   // open dimensions with a period: frames (FR) in use
  struct Frame {
    int f[3];
  };
  big_vector<Frame> FR;                  // (set_frame; empty without frames)
  int nc[3] = {1, 1, 1};                 // cells per dimension
  double cw[3] = {1, 1, 1};              // cell widths
  // a cell boundary's shift per image: nc cells in a periodic dimension, P in another
  double kcells[3] = {0, 0, 0}, kper[3] = {0, 0, 0};
  big_vector<int> head;                 // cell lists (singly linked through Image::next)
  double cell_amax = 0.0;                // largest radius the cells admit
  // Neighbour lists (neighbour_lists.cpp): a particle lists every particle whose list centre lies
  // within lrad of its own (its position when it last rebuilt its list), and rebuilds its list
  // when it has moved lskin from its centre. With lrad = sigma + 2 lskin no pair outside the
  // lists can touch before one of them rebuilds. The cells (at least lrad wide) then hold the
  // particles by list centre and serve only to build lists; there are no crossings.
  bool lists = false;
  double lskin = 0.0, lrad2 = 0.0;       // lskin, and lrad squared
  static constexpr int LCAP = 32;        // entries per list (more: cells from then on)
  // a listed neighbour j and its image shift o: j's position + o P is the image next to i
  // (fixed until either rebuilds; a shift beyond -128..127 periods: cells from then on), and
  // where j's list holds the reverse entry (i at -o): at r, so that a rebuild leaves j's list
  // without searching it
  struct Entry {
    int32_t j;
    int8_t o[3];
    uint8_t r;
  };
  static_assert(sizeof(Entry) == 8, "a list entry holds 8 bytes");
  static_assert(LCAP <= 256, "a reverse index r fits 8 bits");
  // list centres inside the box: the centre less the image of its cell, (x_c - k P)
  big_vector<Vec3> XW;
  big_vector<Entry> NB;                  // LCAP entries per particle
  big_vector<uint8_t> NN;                // entries in use
  Vec3 list_centre(int i) const          // (unwrapped, as i's position)
  {
    const int *k = img[i].k;
    return XW[i] + periods(k[0], k[1], k[2]);
  }
  static bool choose_lists(int dim, double sigma, double n, long count);
  void setup_lists(double sigma);        // (in start(), before the cells)
  void list_drop(int i);                 // i leaves its neighbours' lists; its list empties
  bool list_build(int i, bool higher_only);    // false: a list would overflow
  template <bool HIGHER>
  bool list_build_t(int i);
  bool build_all_lists();                // every list from empty lists (false: an overflow)
  void list_rebuild(int i);              // the rebuild event
  void lists_to_cells();                 // after an overflow: cells from now on
  void predict_rebuild(int i, const Vec3 &xi, const Vec3 &vi);
  void scan_list(int i);
  template <int DIM, bool LATEST>
  void scan_list_t(int i);
  bool lanes = false;                    // offer_lanes() where it applies (opt.simd, AVX2)
  static constexpr int LANE_BUFFER = 64; // candidates of a cell scan offered at once
  void predict_all_lists();
  bool started = false;                  // start() done since resize()
  std::vector<int> dirty;                // external indices changed since the last window
  void refresh();                        // predictions of the dirty particles
  void place(int i);                     // cell and image of i from its position (at now)
  void no_events(int i)                  // no collision candidate, crossing or wall event
  {
    Sched &s = S[i];
    s.ct = s.xt = NEVER;
    s.cpartner = -1;
    if (!WT.empty()) WT[i] = NEVER;
  }
  EventQueue queue;                      // particles by event time
  EDStats stats;
  double now = 0.0;

  void setup_cells();
  void reorder();
  std::vector<int> cell_order() const;
  void renumber(const std::vector<int> &order);
  void predict_all();                    // predict() for every particle, each pair once
  void prefetch_around(int i, bool deep) const;
  static constexpr int PREFETCH_LISTED = 8;    // (two groups of the lanes)
  // what an event reads of i besides its hot record: its Cold record
  // (which may straddle two cache lines) and its time of the last collision (with the TC model)
  void prefetch_cold(int i) const
  {
    asm volatile("");    // (see EventQueue::prefetch_ahead)
    __builtin_prefetch(&C[i]);
    __builtin_prefetch(reinterpret_cast<const char *>(&C[i]) + sizeof(Cold) - 1);
    if (!TL.empty()) __builtin_prefetch(&TL[i]);
  }
  // what an event reads of its collision partner q: its schedule, its records, its queue record
  void prefetch_partner(int q) const
  {
    asm volatile("");    // (see EventQueue::prefetch_ahead)
    __builtin_prefetch(&S[q]);
    __builtin_prefetch(&H[q]);
    prefetch_cold(q);
    queue.prefetch(q);
  }
  // the particles the queue's walk met at each of the last four events, and their partners
  // (-1: none; set one event after they were met): prefetch_upcoming
  struct Upcoming {
    static constexpr int MOST = 16;
    int p[4][MOST], q[4][MOST];
    int n[4] = {0, 0, 0, 0};
    unsigned turn = 0;
  };
  Upcoming upcoming;
  bool far = false;    // this window prefetches (its records exceed EDOptions::prefetch_bytes)
  bool far_partners = false;    // and asks for what the partners' scans read (prefetch_upcoming)
  static constexpr long PARTNERS_FAR = 8;    // (from this many times prefetch_bytes; lists: always)
  void prefetch_upcoming();
  void offer_both(int i, int j, int o0, int o1, int o2);
  // lazy state of internal particle i at window time t (inline: read for every candidate
  // partner and by the LAMMPS fix for every atom and step)
  Vec3 pos(int i, double t) const
  {
    const Hot &p = H[i];
    return flight_x(p.x, p.v, t - p.t, opt.gravity, has_gravity);
  }
  Vec3 vel(int i, double t) const
  {
    const Hot &p = H[i];
    return flight_v(p.v, t - p.t, opt.gravity);
  }
  void locate(int d, double xd, int &c, int &k) const;
  int cell_of(int i) const
  {
    const int16_t *c = S[i].c;
    return (c[2] * nc[1] + c[1]) * nc[0] + c[0];
  }
  void cell_insert(int i);
  void cell_remove(int i);
  // the cells around i's (3^dim, fewer at non-periodic edges): cell indices and the image
  // shifts (-1, 0, 1 per dimension) at which they are reached; returns how many
  int around(int i, int cell[27], int8_t shift[27][3]) const;
  // particle i's stored state brought to window time t (its position as pos() gives it)
  void advance(int i, double t)
  {
    Hot &p = H[i];
    if (p.t == t) return;
    const double dt = t - p.t;
    if (has_gravity) {
      p.x += dt * p.v + (0.5 * dt * dt) * opt.gravity;
      p.v += dt * opt.gravity;
    } else {
      p.x += dt * p.v;
    }
    p.t = t;
  }
  // everything, against all neighbouring cells (pairs = false: crossing and walls only, the
  // collision candidate cleared)
  void predict(int i, bool pairs = true);
  // next cell crossing only; xi, vi: the particle's state now
  void predict_crossing(int i, const Vec3 &xi, const Vec3 &vi);
  template <int DIM, bool GRAV>
  void predict_crossing_t(int i, const Vec3 &xi, const Vec3 &vi);
  // collision candidates in the block of cells at offsets dlo..dhi (from i's stored state)
  void scan(int i, const int dlo[3], const int dhi[3]);
  void scan_full(int i);    // offsets -1..1 in every dimension
  template <bool FULL>
  void scan_in(int i, const int dlo[3], const int dhi[3]);
  template <int DIM, bool GRAV, bool FULL>
  void scan_at(int i, const int dlo[3], const int dhi[3]);
  // whether i's stored state is at the present: no stored time is later than now, so i is then
  // the later one of every pair it predicts
  bool at_present(int i) const { return H[i].t == now; }
  template <int DIM, bool GRAV, bool FULL, bool LATEST>
  void scan_t(int i, const int dlo[3], const int dhi[3]);
  // a scan in progress: particle i's stored state (read once), its best candidate so far
  // (time t, partner j, image shift o; j = -1: the schedule's candidate stands) and the
  // horizon limit of t seen from p's time (horizon_limit(t - p.t, t))
  struct Seek {
    Hot p;
    double t, h;
    int i, j, o[3];
  };
  Seek seek(int i) const;            // from i's schedule
  void settle(const Seek &k);        // the best candidate into i's schedule
  // one candidate j at the image shift o (j's position + o P)
  template <int DIM, bool GRAV, bool LATEST>
  void offer(Seek &k, int j, int o0, int o1, int o2);
  // (the best so far; the queue's bucket for its time asked for from the memory now, while the
  // scan goes on)
  void take(Seek &k, double t, int j, int o0, int o1, int o2)
  {
    if (far) queue.prefetch_time(t);
    k.t = t;
    k.h = horizon_limit(t - k.p.t, t);
    k.j = j;
    k.o[0] = o0, k.o[1] = o1, k.o[2] = o2;
  }
  // offer() for each of the n candidates e[0..n) in turn, in 3d without gravity; four at once
  // (CELLS: the candidates js[0..n) at i's own image, else the list entries e[0..n))
  template <bool LATEST, bool CELLS>
  void offer_lanes(Seek &k, const Entry *e, const int *js, int n);
  template <bool LATEST>
  bool offer_cells_lanes(Seek &k, const int *first, int nfirst, const int8_t (*shift)[3], const int *of);
  double at_least_now(double t) const { return t < now ? now : t; }    // (a contact time)
  // the candidates in the cells whose first particles a scan gathered (shift: their image
  // shifts, the f-th at of[f]; null: none)
  template <int DIM, bool GRAV, bool LATEST>
  void offer_cells(Seek &k, const int *first, int nfirst, const int8_t (*shift)[3], const int *of);
  // the canonical contact time of stored states p and q at the image shift o (q's position +
  // o P), >= now; NEVER also where it is certainly >= before
  template <int DIM, bool GRAV>
  double contact(const Hot &p, const Hot &q, int o0, int o1, int o2, double before) const;
  template <int DIM, bool GRAV>
  double contact_at(const Hot &p, double tr, const Vec3 &a, const Vec3 &u, const Hot &q, int o0, int o1,
                    int o2, double h) const;
  // the canonical contact time of i and j at the image shift o (j's position + o P), >= now
  template <int DIM, bool GRAV>
  double pair_time(int i, int j, int o0, int o1, int o2) const;
  // two particles that last collided with each other, at this image shift: no candidates
  bool separating(int i, int j, int o0, int o1, int o2) const
  {
    const int *lo = S[i].last_off;
    return C[i].last_partner == j && C[j].last_partner == i && o0 == lo[0] && o1 == lo[1] &&
        o2 == lo[2];
  }
  void start_common();                   // start() and start_at() after the particles' times
  double schedule(int i);                // ekind from the candidates; returns the event time
  // (from the stored state alone, as pair contact times: the same number whenever predicted)
  void predict_wall(int i)
  {
    S[i].wall = -1;
    if (WT.empty()) return;
    WT[i] = NEVER;
    predict_walls(i);
  }
  void predict_walls(int i);    // (there are walls)
  void collide_wall(int i);
  Collision thermal_reemission(const EDWall &w, int i, const Vec3 &n, double t);
  void collide_pair(int i);
  void cross(int i);
  void reschedule(int i) { queue.update(i, schedule(i)); }
};

}    // namespace granfric

#endif
