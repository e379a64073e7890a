// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core, internal: what the event-driven core (event_driven.h) keeps and how it
// works inside: EDCore, the state and the private functions of EventDriven, which derives from it
// privately (no virtual function, no extra indirection: a call costs what a call of a private
// member would). The records of the particles come first, each named for what it holds; then the
// state and the functions, grouped by the file that defines them. Only the core's own sources and
// event_driven.h include this header.
#ifndef GRANFRIC_CORE_ED_CORE_H
#define GRANFRIC_CORE_ED_CORE_H

#include "ed_types.h"
#include "event_queue.h"
#include "huge_alloc.h"
#include "prediction.h"

#include <cstdint>
#include <functional>
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

class EDCore {
 public:
  enum { NONE = 0, COLLISION = 1, CROSSING = 2, WALL = 3 };    // Schedule::ekind
  static constexpr long MAX_LISTS = 40000;    // the most particles that get lists automatically
  static double auto_cell_width(int dim, double sigma, double n);
  static bool have_lanes();
  static Vec3 flight_x(const Vec3 &x, const Vec3 &v, double dt, const Vec3 &g, bool grav)
  {
    return grav ? x + dt * v + (0.5 * dt * dt) * g : x + dt * v;
  }
  static Vec3 flight_v(const Vec3 &v, double dt, const Vec3 &g) { return v + dt * g; }

 protected:
  // The records of the particles, in internal order (cell order, for memory locality), one array
  // of each. What every candidate-partner test reads of a particle: its free flight and radius,
  // one cache line
  struct alignas(64) Flight {
    Vec3 x, v;                // position (unwrapped), velocity
    double t = 0.0;           // local time of x and v
    double a = 0.5;           // radius
  };
  static_assert(sizeof(Flight) == 64, "what a pair prediction reads fills one cache line");

  // what only a collision of the particle reads, and the tick of its last change of trajectory,
  // which the event loop reads of every event's partner (EDCore::stale)
  struct Collider {
    long key = 0;             // key(i), copied for the event loop (copy_keys)
    Vec3 w;                   // angular velocity
    double m = 1.0;           // mass (the shape factor q is its type's: qt)
    int last_partner = -1;    // partner of the last collision
    uint32_t changed = 0;     // the tick of its last change of trajectory (see EDCore::tick)
  };
  static_assert(sizeof(Collider) == 48, "the key, w, m, the last partner and the tick: 48 bytes");

  // a particle's own event bookkeeping, read only when it is predicted or processed: one cache
  // line (the next wall collision, which only systems with walls have, is kept apart in
  // EDCore::wall_times)
  struct alignas(64) Schedule {
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
    Schedule() : xdim(0), xdir(0) {}
  };
  static_assert(sizeof(Schedule) == 64, "a particle's schedule fills one cache line");

  // periodic image of a particle's cell, and the next particle in its cell's list: what the
  // candidate-partner search reads of a particle besides its flight, so one 16-byte record
  // (neighbours in cell order share its cache lines)
  struct CellImage {
    int k[3];
    int next;
  };

  // how many periods (EDOptions::period) below where the cell grid sees it a particle's stored
  // position lies, per dimension (EventDriven::set_frame)
  struct Frame {
    int f[3];
  };

  // a listed neighbour j and its image shift o: j's position + o P is the image next to i (fixed
  // until either rebuilds; a shift beyond -128..127 periods: cells from then on), and where j's
  // list holds the reverse entry (i at -o): at r, so that a rebuild leaves j's list without
  // searching it
  struct ListEntry {
    int32_t j;
    int8_t o[3];
    uint8_t r;
  };
  static_assert(sizeof(ListEntry) == 8, "a list entry holds 8 bytes");

  // ---- the particles' records (one array of each, by internal index)
  big_vector<Flight> flights;
  big_vector<Collider> colliders;
  big_vector<Schedule> schedules;
  big_vector<double> last_collision;     // time of the last collision (only with tc > 0)
  big_vector<double> wall_times;         // next wall collision: time (empty without walls)
  big_vector<CellImage> images;
  big_vector<Frame> frames;              // (set_frame; empty without frames)
  big_vector<int> ext, loc;              // internal -> external index, and back
  double tl_none = -INF;                 // what t_last refers to without the TC model
  static constexpr double TL_NONE = -INF;    // (read-only views: no store to tl_none)
  EDParticle ref(int i)
  {
    Flight &h = flights[i];
    Collider &c = colliders[i];
    double &tl = last_collision.empty() ? (tl_none = -INF) : last_collision[i];
    return EDParticle(h.x, h.v, h.t, h.a, c.w, c.m, qt[schedules[i].type], tl, schedules[i].type);
  }
  EDParticleView view(int i) const
  {
    const Flight &h = flights[i];
    const Collider &c = colliders[i];
    const double &tl = last_collision.empty() ? TL_NONE : last_collision[i];
    return EDParticleView(h.x, h.v, h.t, h.a, c.w, c.m, qt[schedules[i].type], tl, schedules[i].type);
  }
  // lazy state of internal particle i at window time t (inline: read for every candidate
  // partner and by the LAMMPS fix for every atom and step)
  Vec3 pos(int i, double t) const
  {
    const Flight &p = flights[i];
    return flight_x(p.x, p.v, t - p.t, opt.gravity, has_gravity);
  }
  Vec3 vel(int i, double t) const
  {
    const Flight &p = flights[i];
    return flight_v(p.v, t - p.t, opt.gravity);
  }
  // particle i's stored state brought to window time t (its position as pos() gives it)
  void advance(int i, double t)
  {
    Flight &p = flights[i];
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

  // ---- options (options.cpp)
  EDOptions opt;
  bool has_gravity = false;
  int ntypes = 0;
  std::vector<LawParams> laws;
  std::vector<double> qt = {0.4, 0.4};   // moment of inertia / (m a^2) by type (configure)
  Vec3 L;                                // box lengths
  Vec3 P;                                // periods of image shifts (L if periodic, else period)
  // an image shift of a, b, c periods as a displacement (without the shear shift: image())
  Vec3 periods(int a, int b, int c) const { return Vec3(a * P.x, b * P.y, c * P.z); }
  // Lees-Edwards (EDOptions::shear): the x shift of the image one period up in y, at window time
  // t, and the displacement and velocity of the image at shift a, b, c (b periods up in y)
  double shear_s0 = 0.0;                 // the shift at window time 0
  double shift_at(double t) const { return shear_s0 + opt.shear_rate * t; }
  Vec3 image(int a, int b, int c, double t) const
  {
    Vec3 r = periods(a, b, c);
    if (b && opt.shear) r.x += b * shift_at(t);
    return r;
  }
  double image_speed(int b) const { return b * opt.shear_rate; }
  bool framed = false;                   // open dimensions with a period: frames in use
  bool lanes = false;                    // offer_lanes() where it applies (opt.simd, AVX2)

  // ---- the event loop and pair collisions (event_driven.cpp)
  EventQueue queue;                      // particles by event time
  EDStats stats;
  double now = 0.0;
  double clock = 0.0;                    // absolute time of window time 0
  bool started = false;                  // start() done since resize()
  // Stale predictions. Every change of a particle's trajectory (a collision, a wall, a change
  // from outside) advances one clock, tick, and stores it in the particle's Collider record
  // (changed); a prediction stores the tick at which it was made (Schedule::ctick) and is stale
  // once its partner changed later. So a scan writes its best candidate without reading
  // anything of it, and the event loop reads the Collider record of each event's partner, which
  // a valid collision needs anyway
  uint32_t tick = 0;
  void turned(int i)
  {
    if (tick >= opt.tick_last) retick();
    colliders[i].changed = ++tick;
  }
  void turned(int i, int j)    // (one change of both: the same tick)
  {
    turned(i);
    colliders[j].changed = tick;
  }
  void retick();    // the clock back to 1, every prediction as stale or fresh as it was
                    // (past EDOptions::tick_last)
  // whether a schedule's collision candidate went stale: its partner changed course since
  bool stale(const Schedule &s) const { return colliders[s.cpartner].changed > s.ctick; }
  // the TC model: did i collide within tc before t? (only with tc > 0; a last collision 'in the
  // future' after a clock reset does not count)
  bool tc_recent(int i, double t) const
  {
    if (last_collision.empty()) return false;
    const double since = t - last_collision[i];
    return since >= 0.0 && since < opt.tc;
  }
  EDAccounting acct;
  bool counted(int i) const { return !acct.counted || acct.counted[ext[i]]; }
  long key(int i) const { return acct.key ? acct.key[ext[i]] : (long) ext[i]; }
  // key(i) as copy_keys() left it in i's record at the start of advance_to(): in the event loop
  // a pair's order costs no lookups through ext and the accounting's keys, which in a large
  // system are two cache misses per particle
  long loop_key(int i) const { return colliders[i].key; }
  void copy_keys();
  void start_common();                   // start() and start_at() after the particles' times
  // everything, against all neighbouring cells (pairs = false: crossing and walls only, the
  // collision candidate cleared)
  void predict(int i, bool pairs = true);
  double schedule(int i);                // ekind from the candidates; returns the event time
  void reschedule(int i) { queue.update(i, schedule(i)); }
  void no_events(int i)                  // no collision candidate, crossing or wall event
  {
    Schedule &s = schedules[i];
    s.ct = s.xt = NEVER;
    s.cpartner = -1;
    if (!wall_times.empty()) wall_times[i] = NEVER;
  }
  void collide_pair(int i);

  // ---- the particles' slots (particle_slots.cpp)
  std::vector<int> dirty;                // external indices changed since the last window
  void refresh();                        // predictions of the dirty particles

  // ---- global events (global_events.cpp)
  std::vector<double> gtimes;            // pending global events
  std::function<void(int)> gapply;
  void global_event(int k);

  // ---- asking the memory ahead (prefetch.cpp)
  void prefetch_around(int i, bool deep) const;
  static constexpr int PREFETCH_LISTED = 8;    // (two groups of the lanes)
  // what an event reads of i besides its flight: its Collider record (which may straddle two
  // cache lines) and its time of the last collision (with the TC model)
  void prefetch_collider(int i) const
  {
    asm volatile("");    // (see EventQueue::prefetch_ahead)
    __builtin_prefetch(&colliders[i]);
    __builtin_prefetch(reinterpret_cast<const char *>(&colliders[i]) + sizeof(Collider) - 1);
    if (!last_collision.empty()) __builtin_prefetch(&last_collision[i]);
  }
  // what an event reads of its collision partner q: its schedule, its records, its queue record
  void prefetch_partner(int q) const
  {
    asm volatile("");    // (see EventQueue::prefetch_ahead)
    __builtin_prefetch(&schedules[q]);
    __builtin_prefetch(&flights[q]);
    prefetch_collider(q);
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

  // ---- the cell grid and its crossings (cells.cpp)
  int nc[3] = {1, 1, 1};                 // cells per dimension
  double cw[3] = {1, 1, 1};              // cell widths
  // a cell boundary's shift per image: nc cells in a periodic dimension, P in another
  double kcells[3] = {0, 0, 0}, kper[3] = {0, 0, 0};
  big_vector<int> head;                  // cell lists (singly linked through CellImage::next)
  double cell_amax = 0.0;                // largest radius the cells admit
  long crossings_since_reorder = 0;
  long window_crossings = 0, crossing_cap = 0;    // (this window's, and its cap)
  void count_crossing(int i);            // throws EventCapError past the cap
  void setup_cells();
  void reorder();
  std::vector<int> cell_order() const;
  void renumber(const std::vector<int> &order);
  void place(int i);                     // cell and image of i from its position (at now)
  void locate(int d, double xd, int &c, int &k) const;
  int cell_of(int i) const
  {
    const int16_t *c = schedules[i].c;
    return (c[2] * nc[1] + c[1]) * nc[0] + c[0];
  }
  void cell_insert(int i);
  void cell_remove(int i);
  // the cells around i's (3^dim, fewer at non-periodic edges): cell indices and the image
  // shifts (-1, 0, 1 per dimension) at which they are reached; returns how many (not in a
  // sheared box: sheared_spans)
  static constexpr int AROUND = 27;
  int around(int i, int cell[AROUND], int8_t shift[AROUND][3]) const;
  // ---- Lees-Edwards (shear.cpp): the rows of cells are grouped in bands of neighbouring rows
  // that move with the flow together: band b (rows with row_band b) is shifted in x by
  // (b + 1/2) D(t) + h L_x / 2, where D = (s + w L_x) / nbands is the shift between
  // neighbouring bands (and, less w periods, across the y faces); D in cell widths is m + f
  // (0 <= m < nc[0]), and m changes at shear ticks, at which the pairs of the cells that come
  // next to each other across every band boundary become candidates
  int shear_m = 0;
  int shear_w = 0;                       // 0 <= w < nbands
  int shear_h = 0;                       // 0 or 1: half periods of x the bands are shifted
  double shear_wp = 0.0, shear_hp = 0.0; // w L_x and h L_x / 2
  int nbands = 1;
  double band_scale = 1.0, band_rate = 0.0;    // 1 / n_b, and the shear rate over n_b
  std::vector<int> row_band;             // per row of cells (y cell): its band
  std::vector<double> row_mid;           // per row: its band b + 1/2
  std::vector<uint8_t> row_sheared;      // per row: 1 if the boundary above it is a band's (or the y face)
  double shear_next = NEVER;             // the next shear event's time
  bool shear_wraps = false;              // whether it is the shift's passing a period
  void shear_bands();                    // (setup_cells(): the bands)
  void shear_schedule();
  double row_step(double t) const { return (shift_at(t) + shear_wp) * band_scale; }    // D(t)
  double row_shift(int r, double t) const { return row_mid[r] * row_step(t) + shear_hp; }
  double row_speed(int r) const { return row_mid[r] * band_rate; }
  void shear_periods()                   // (w or h changed)
  {
    shear_wp = shear_w * P.x;
    shear_hp = shear_h * P.x * 0.5;
  }
  // whether the boundary between row r and the row above (dir 1) or below (-1) is sheared
  bool boundary_sheared(int r, int dir) const
  {
    return dir > 0 ? row_sheared[r] : (r == 0 ? true : row_sheared[r - 1]);
  }
  // whether row r lies inside its band: the rows above and below of its band (no y face)
  bool band_interior(int r) const { return r > 0 && !row_sheared[r - 1] && !row_sheared[r]; }
  // how a scan takes the rows next to row r: as a block inside its band (ROW_INSIDE); at the
  // edge of its band, the boundary above (ROW_EDGE_UP) or below (ROW_EDGE_DOWN) and the row
  // across in the same y image; else by spans (ROW_SPANS: next to a y face, or a band of one row)
  enum RowKind : int8_t { ROW_INSIDE, ROW_EDGE_UP, ROW_EDGE_DOWN, ROW_SPANS };
  std::vector<int8_t> row_kind;
  // the cells a particle's scan takes in a sheared box: per row next to it (its first cell in
  // head at row, at y image ky and z image kz; dy, dz its row and z layer against i's), the x
  // cells a0..a1 counted across images (cell a - q nc[0] at x image q = floor(a / nc[0])), 3 in
  // a row of its band, 4 in a row across a band boundary (the scans gather at most 9 x 4
  // cells); a0 is cell u at x image q (start_at moves the start on by a few cells)
  struct RowSpan {
    int dy, dz, ky, kz, row, q, u;
    long a0, a1;
    void start_at(long a, int n0)
    {
      u += (int) (a - a0);
      a0 = a;
      while (u >= n0) u -= n0, q++;
    }
  };
  template <int DIM>
  int sheared_spans_t(int i, RowSpan out[9]) const;
  int sheared_spans(int i, RowSpan out[9]) const;
  static long floor_div(long a, long n) { return a >= 0 ? a / n : -((-a + n - 1) / n); }
  template <int DIM, bool GRAV, bool LATEST>
  void scan_spans_t(int i, const RowSpan *s, int n);
  void scan_spans(int i, const RowSpan *s, int n);
  void scan_sheared(int i, bool full, const int dlo[3], const int dhi[3]);
  void scan_new_spans(int i, const RowSpan *before, int nbefore);    // (after a y crossing)
  void sheared_frame(int i, double &x0, double &v0) const;
  void shear_start();                    // (start(): the shift into [0, L_x), before the cells)
  void shear_cells();                    // (start(): m and the first event, after the cells)
  void shear_tick();
  void shear_relabel(int dir);           // the shift by dir periods less: images follow
  void row_relabel(int dir);             // D by dir periods less: images follow

  // next cell crossing only; xi, vi: the particle's state now
  void predict_crossing(int i, const Vec3 &xi, const Vec3 &vi);
  template <bool SHEARED>
  void predict_crossing_in(int i, const Vec3 &xi, const Vec3 &vi);
  template <int DIM, bool GRAV, bool SHEARED>
  void predict_crossing_t(int i, const Vec3 &xi, const Vec3 &vi);
  void cross(int i);

  // ---- neighbour lists (neighbour_lists.cpp): a particle lists every particle whose list
  // centre lies within lrad of its own (its position when it last rebuilt its list), and
  // rebuilds its list when it has moved lskin from its centre. With lrad = sigma + 2 lskin no
  // pair outside the lists can touch before one of them rebuilds. The cells (at least lrad wide)
  // then hold the particles by list centre and serve only to build lists; there are no crossings.
  bool lists = false;
  double lskin = 0.0, lrad2 = 0.0;       // lskin, and lrad squared
  static constexpr int LCAP = 32;        // entries per list (more: cells from then on)
  static_assert(LCAP <= 256, "a reverse index r fits 8 bits");
  // list centres inside the box: the centre less the image of its cell, (x_c - k P)
  big_vector<Vec3> list_centres;
  big_vector<ListEntry> list_entries;    // LCAP entries per particle
  big_vector<uint8_t> list_counts;       // entries in use
  Vec3 list_centre(int i) const          // (unwrapped, as i's position)
  {
    const int *k = images[i].k;
    return list_centres[i] + periods(k[0], k[1], k[2]);
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
  void predict_all_lists();

  // ---- the search for collision candidates (candidate_search.cpp; four at a time in AVX2
  // lanes: candidate_lanes.cpp)
  static constexpr int LANE_BUFFER = 64; // candidates of a cell scan offered at once
  void predict_all();                    // predict() for every particle, each pair once
  void offer_both(int i, int j, int o0, int o1, int o2);
  void scan_list(int i);
  template <int DIM, bool LATEST>
  void scan_list_t(int i);
  // collision candidates in the block of cells at offsets dlo..dhi (from i's stored state)
  void scan(int i, const int dlo[3], const int dhi[3]);
  void scan_full(int i);    // offsets -1..1 in every dimension
  template <bool FULL>
  void scan_in(int i, const int dlo[3], const int dhi[3]);
  template <bool FULL>
  void scan_shear_in(int i, const int dlo[3], const int dhi[3]);    // (a sheared box)
  template <int DIM, bool GRAV, bool FULL>
  void scan_at(int i, const int dlo[3], const int dhi[3]);
  // whether i's stored state is at the present: no stored time is later than now, so i is then
  // the later one of every pair it predicts
  bool at_present(int i) const { return flights[i].t == now; }
  template <int DIM, bool GRAV, bool FULL, bool LATEST>
  void scan_t(int i, const int dlo[3], const int dhi[3]);
  // a scan in progress: particle i's stored state (read once), its best candidate so far
  // (time t, partner j, image shift o; j = -1: the schedule's candidate stands) and the
  // horizon limit of t seen from p's time (horizon_limit(t - p.t, t))
  struct Seek {
    Flight p;
    double t, h;
    int i, j, o[3];
  };
  Seek seek(int i) const;            // from i's schedule
  void settle(const Seek &k);        // the best candidate into i's schedule
  // the block of cells at offsets dlo..dhi around i's inside the grid, scanned at i's own image
  // (no wrapping, no edges)
  template <int DIM, bool FULL>
  bool block_inside(int i, const int dlo[3], const int dhi[3]) const
  {
    const int16_t *c = schedules[i].c;
    for (int d = 0; d < DIM; d++)
      if (c[d] + (FULL ? -1 : dlo[d]) < 0 || c[d] + (FULL ? 1 : dhi[d]) >= nc[d]) return false;
    return true;
  }
  template <int DIM, bool GRAV, bool FULL, bool LATEST, bool SHEARED>
  void scan_block(Seek &k, const int dlo[3], const int dhi[3]);
  template <int DIM, bool GRAV, bool FULL>
  bool scan_band_at(int i, const int dlo[3], const int dhi[3]);    // (a sheared box: band_interior)
  template <int DIM, bool GRAV, bool FULL>
  bool scan_edge_at(int i, const int dlo[3], const int dhi[3]);    // (at a band's edge)
  template <int DIM, bool GRAV, bool FULL>
  bool scan_rows_at(int i, const int dlo[3], const int dhi[3]);
  // one candidate j at the image shift o (j's position + o P)
  template <int DIM, bool GRAV, bool LATEST, bool SHEARED = false>
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
  // (SHEARED: a sheared box, the image shifts taken as contact_at's SHEARED takes them)
  template <bool LATEST, bool CELLS, bool SHEARED = false>
  void offer_lanes(Seek &k, const ListEntry *e, const int *js, int n);
  template <bool LATEST>
  bool offer_spans_lanes(Seek &k, const RowSpan *s, int n);
  template <bool LATEST, bool SHEARED = false>
  bool offer_cells_lanes(Seek &k, const int *first, int nfirst, const int8_t (*shift)[3], const int *of);
  template <bool LATEST, bool SHEARED>
  bool buffer_cell(Seek &k, int j0, int k0, int k1, int k2, ListEntry *buf, int &nb, int &wide);
  double at_least_now(double t) const { return t < now ? now : t; }    // (a contact time)
  // the candidates in the cells whose first particles a scan gathered (shift: their image
  // shifts, the f-th at of[f]; null: none)
  template <int DIM, bool GRAV, bool LATEST, bool SHEARED = false>
  void offer_cells(Seek &k, const int *first, int nfirst, const int8_t (*shift)[3], const int *of);
  // the canonical contact time of stored states p and q at the image shift o (q's position +
  // o P), >= now; NEVER also where it is certainly >= before
  template <int DIM, bool GRAV, bool SHEARED = false>
  double contact(const Flight &p, const Flight &q, int o0, int o1, int o2, double before) const;
  template <int DIM, bool GRAV, bool SHEARED = false>
  double contact_at(const Flight &p, double tr, const Vec3 &a, const Vec3 &u, const Flight &q, int o0,
                    int o1, int o2, double h) const;
  // the canonical contact time of i and j at the image shift o (j's position + o P), >= now
  template <int DIM, bool GRAV, bool SHEARED = false>
  double pair_time(int i, int j, int o0, int o1, int o2) const;
  // two particles that last collided with each other, at this image shift: no candidates
  bool separating(int i, int j, int o0, int o1, int o2) const
  {
    const int *lo = schedules[i].last_off;
    return colliders[i].last_partner == j && colliders[j].last_partner == i && o0 == lo[0] &&
        o1 == lo[1] && o2 == lo[2];
  }

  // ---- wall motion and contact times (wall_motion.cpp), the response at walls
  // (wall_response.cpp)
  // (from the stored state alone, as pair contact times: the same number whenever predicted)
  void predict_wall(int i)
  {
    schedules[i].wall = -1;
    if (wall_times.empty()) return;
    wall_times[i] = NEVER;
    predict_walls(i);
  }
  void predict_walls(int i);    // (there are walls)
  void collide_wall(int i);
  Collision thermal_reemission(const EDWall &w, int i, const Vec3 &n, double t, const Vec3 &u);

  // ---- statistics and records of the collisions (statistics.cpp)
  std::vector<EDEvent> *history = nullptr;
  std::vector<EDCollisionRecord> *collision_log = nullptr;
  const uint8_t *record_only = nullptr;
  bool tally_on = false;
  std::vector<EDParticleTally> tallies;  // (tally_particles; by external index)
  // particle i's part in a collision at t: r (x) dP (halved for a pair), its energy changes
  void tally(int i, const Vec3 &r, const Vec3 &dP, double t, double dE_tr, double dE_rot, bool wall);
  // the one hook per collision into the statistics and records
  void record_pair(int i, int j, double t, const Vec3 &r, const Vec3 &n, const Body &b1, const Body &b2,
                   const Collision &c, bool tc_elastic, long ni, long nj);
  void record_wall(int i, int k, double t, const Vec3 &n, const Vec3 &dP, const Collision &c,
                   double dE_tr, double dE_rot, bool tc_elastic, long ni);
  double fast_s2 = INF;                  // track_fast(): the threshold, and who reached it
  bool fast_on = false;
  std::vector<std::pair<int, double>> fast;
  bool tracking_fast() const { return fast_on; }
  void note_speed(int i, const Vec3 &v)    // (only while tracking_fast())
  {
    const double s2 = norm2(v);
    if (s2 >= fast_s2) fast.emplace_back(ext[i], s2);
  }
};

}    // namespace granfric

#endif
