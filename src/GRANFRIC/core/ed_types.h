// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the values the event-driven core (event_driven.h) takes and gives: a
// particle as the user sets and reads it, walls, options, statistics, records of collisions, the
// accounting of a window that covers part of a larger system, and the error of an event cap.
#ifndef GRANFRIC_CORE_ED_TYPES_H
#define GRANFRIC_CORE_ED_TYPES_H

#include "collision.h"
#include "vec3.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

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
  // a constant velocity within the wall's plane (its component along dim is 0): the plane
  // stays where it is, so contact times do not change; the collision law acts on the velocity
  // relative to the wall's surface, and a thermal wall re-emits from the Maxwellian of the
  // moving wall
  Vec3 slide;
  bool sliding() const { return slide.x != 0.0 || slide.y != 0.0 || slide.z != 0.0; }
  // an oscillation within the wall's plane along dimension shake_dim (-1: none), displacement
  // shake_A sin(shake_omega t): as sliding, it leaves the contact times alone and gives the
  // surface the velocity shake_A shake_omega cos(shake_omega t) along that dimension
  int shake_dim = -1;
  double shake_A = 0.0, shake_omega = 0.0;
  bool shaking() const { return shake_dim >= 0 && shake_A > 0.0 && shake_omega > 0.0; }
  bool moving() const { return vibrating() || sliding() || shaking(); }
  // the component of an acceleration g (gravity) that points into the wall (> 0: toward it)
  double toward(const double g[3]) const { return side < 0 ? -g[dim] : g[dim]; }
  // the velocity of the wall's surface within its plane at absolute time s
  Vec3 surface_velocity(double s) const
  {
    Vec3 u = slide;
    if (shaking()) u[shake_dim] += shake_A * shake_omega * std::cos(shake_omega * s);
    return u;
  }
  // the wall's largest speed: A omega (sine), 4 A omega / pi (parabolic), 0 (static), plus the
  // largest speed within its plane
  double speed_bound() const
  {
    return (!vibrating() ? 0.0 : sine ? A * omega : 4.0 * A * omega / M_PI) + norm(slide) +
        (shaking() ? shake_A * shake_omega : 0.0);
  }
  // position, velocity and acceleration at absolute time s
  void motion(double s, double &w, double &vw, double &aw) const;

  // Every field, in one fixed order: f(name, field of s...) for each, with the fields of every s
  // given by reference (EDOptions::each_field)
  template <class F, class... S>
  static void each_field(F &&f, S &...s)
  {
    f("dim", s.dim...), f("side", s.side...), f("pos", s.pos...), f("laws", s.laws...);
    f("T", s.T...), f("seed", s.seed...), f("A", s.A...), f("omega", s.omega...), f("sine", s.sine...);
    f("slide", s.slide...), f("shake_dim", s.shake_dim...), f("shake_A", s.shake_A...);
    f("shake_omega", s.shake_omega...);
  }
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
  // cell crossings (or list rebuilds) per particle per window, summed over the particles (a
  // guard against particles far faster than the system's scale: energy that ran away)
  long max_crossings = 10000;
  int gamma_bins = 0;                   // > 0: histogram of impact angles in (pi/2, pi]
  std::vector<EDWall> walls;            // in non-periodic dimensions
  // moment of inertia / (m a^2) by particle type (index 0 unused), each in (0, 1]; empty:
  // 0.4 (solid spheres) for every type
  std::vector<double> shape;
  // > 0: cells at least this wide (never narrower than the largest contact distance); 0: the
  // automatic width (see setup_cells). For benchmarks of the cell width.
  double cell_width = 0.0;
  // a sheared box (shear): > 0, the rows of cells that move together as one band (see
  // shear.cpp); 0: the automatic choice (EDCore::shear_bands). For tests and benchmarks.
  int shear_band = 0;
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
  // the same bits). Below, the records mostly stay in the cache, where asking only adds work to
  // every event; above, most records an event reads are misses, whose wait asking early hides
  long prefetch_bytes = 5L << 20;
  // the clock of trajectory changes that marks stale predictions starts again from 1 once it
  // reaches this value (the predictions keep what they were; for tests of that restart, which
  // the 32-bit clock otherwise reaches after about 4e9 collisions)
  uint32_t tick_last = 0xfffffffeu;
  // Lees-Edwards boundaries (simple shear in the x-y plane): the periodic image one period up in
  // y lies shifted by s(t) in x and moves at shear_rate = ds/dt in x relative to the box, as in
  // a periodic triclinic box whose tilt xy = s(t) changes at that rate. x and y must be periodic;
  // candidates come from cells (not lists). The shift at window time 0 is
  // EventDriven::set_shear_shift's. Positions stay unwrapped: a particle that leaves the box
  // through a y face keeps its stored state, and its image inside the box is its position less
  // one lattice vector (s, L_y) and its velocity less (shear_rate, 0).
  bool shear = false;
  double shear_rate = 0.0;

  // Every field, in one fixed order: f(name, role, field of s...) for each, with the fields of
  // every s given by reference. role DEFINING: part of the configuration, whose change makes a
  // new event queue (EventDriven::same_configuration compares it); TUNING: a choice of how the
  // same trajectories are computed, which a kept event queue does not depend on. A field that
  // holds walls or laws holds records with an each_field of their own (EDWall, LawParams). The
  // one list of the fields, for comparisons (same_configuration) and descriptions (describe).
  enum Role { DEFINING, TUNING };
  template <class F, class... S>
  static void each_field(F &&f, S &...s)
  {
    f("dim", DEFINING, s.dim...), f("lo", DEFINING, s.lo...), f("hi", DEFINING, s.hi...);
    f("periodic", DEFINING, s.periodic...), f("open", DEFINING, s.open...);
    f("period", DEFINING, s.period...), f("gravity", DEFINING, s.gravity...);
    f("tc", DEFINING, s.tc...), f("max_collisions", DEFINING, s.max_collisions...);
    f("max_crossings", DEFINING, s.max_crossings...);
    f("gamma_bins", DEFINING, s.gamma_bins...), f("walls", DEFINING, s.walls...);
    f("shape", DEFINING, s.shape...), f("cell_width", DEFINING, s.cell_width...);
    f("neighbours", DEFINING, s.neighbours...), f("list_skin", DEFINING, s.list_skin...);
    f("simd", TUNING, s.simd...), f("prefetch_bytes", TUNING, s.prefetch_bytes...);
    f("tick_last", TUNING, s.tick_last...);
    f("shear", DEFINING, s.shear...), f("shear_rate", DEFINING, s.shear_rate...);
    f("shear_band", DEFINING, s.shear_band...);
  }
  // every field by name and value, in the order of each_field (for messages and logs)
  std::string describe() const;
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

// One particle's tallies of a window (EventDriven::tally_particles): the collision virial (6
// values as EDStats::virial), its pair and wall collisions, the changes of its translational and
// rotational kinetic energy in pair collisions and of its kinetic energy in wall collisions, and
// the window time of its last collision (-inf: none)
struct EDParticleTally {
  double virial[6];
  double collisions, wall_collisions, dE_tr, dE_rot, dE_wall, t_last;
};

// thrown when a window exceeds its work cap: a particle with more than max_collisions
// collisions (COLLISIONS: inelastic collapse), or more than max_crossings times the number of
// particles cell crossings or list rebuilds in all (CROSSINGS: particles far faster than the
// system's scale, e.g. after a law or a driving wall pumped energy into them)
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

}    // namespace granfric

#endif
