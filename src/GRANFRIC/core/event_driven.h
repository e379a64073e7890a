// GRANFRIC physics core: the exact event-driven loop for one time window.
//
// Particles fly freely (uniform gravity allowed) and collide instantaneously through a
// collision law (collision.h). Within a window [0, t_end) every pair collision is processed in
// exact time order; then every particle is advanced to t_end. Candidate partners come from a
// cell grid (cell width >= largest contact distance) kept exact by cell-crossing events, so no
// pair can be missed whatever the window length. Per-particle local times and lazy updates, one
// scheduled event per particle, invalidation by collision counters, an indexed binary heap, and
// the TC model of Luding & McNamara against inelastic collapse. Positions are unwrapped inside
// the window (periodic images are tracked by integer offsets, not by moving particles).
#ifndef GRANFRIC_CORE_EVENT_DRIVEN_H
#define GRANFRIC_CORE_EVENT_DRIVEN_H

#include "collision.h"
#include "prediction.h"

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace granfric {

struct EDParticle {
  // input (window time 0)
  Vec3 x, v, w;               // position (unwrapped), velocity, angular velocity
  double a = 0.5, m = 1.0, q = 0.4;
  int type = 1;
  double t_last = -INF;       // time of the last collision (window time), for the TC model

  // internal state
  double t = 0.0;             // local time of x and v
  uint32_t ncoll = 0;         // collisions since start(): invalidates partners' predictions
  int last_partner = -1;      // partner of the last collision
  int last_off[3] = {0, 0, 0};  // periodic image offset of that partner (see eoff)
  int cell = -1;              // linear cell index
  int c[3] = {0, 0, 0};       // cell coordinates within the grid
  int img[3] = {0, 0, 0};     // periodic image of the cell
  long ncollisions = 0;       // collisions in this window (event cap)

  // scheduled event
  double et = NEVER;
  int ekind = 0;              // NONE, COLLISION, CROSSING
  int epartner = -1;          // collision: partner; crossing: dimension
  uint32_t ecount = 0;        // collision: partner's ncoll at prediction; crossing: direction (0/1)
  int eoff[3] = {0, 0, 0};    // collision: the partner's unwrapped position is shifted by eoff * L
};

struct EDOptions {
  int dim = 3;                          // 2: motion in x-y, spin about z; 3: full
  double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  bool periodic[3] = {true, true, true};
  Vec3 gravity;
  double tc = 0.0;                      // TC model duration (0: off)
  long max_collisions = 1000000;        // per particle per window (inelastic-collapse guard)
  int gamma_bins = 0;                   // > 0: histogram of impact angles in (pi/2, pi]
};

struct EDStats {
  long collisions = 0, sliding = 0, tc_elastic = 0, energy_created = 0, crossings = 0;
  long max_collisions_one_particle = 0;
  double dE = 0.0;                      // sum of collision energy changes (< 0: dissipated)
  std::vector<long> gamma_hist;         // impact angles, EDOptions::gamma_bins bins
  void add(const EDStats &o);
};

// thrown when a particle exceeds the per-window collision cap (inelastic collapse)
class EventCapError : public std::runtime_error {
 public:
  EventCapError(const std::string &what, int i_, int j_, double t_, long n_) :
      std::runtime_error(what), i(i_), j(j_), t(t_), n(n_)
  {
  }
  int i, j;      // particle indices of the collision that crossed the cap
  double t;      // window time
  long n;        // collisions of particle i in this window
};

class EventDriven {
 public:
  enum { NONE = 0, COLLISION = 1, CROSSING = 2 };

  // laws: (ntypes+1)^2 table indexed [itype * (ntypes+1) + jtype]
  void configure(const EDOptions &opt, int ntypes, const std::vector<LawParams> &laws);
  const EDOptions &options() const { return opt; }

  std::vector<EDParticle> particles;

  // process every event in [0, t_end) and advance all particles to t_end
  EDStats run(double t_end);

  // the same in pieces, keeping the event queue between windows:
  //   start()          cells and predictions from the particles' x, v, w at time 0
  //   advance_to(t)    process every event before t (lazy states are not advanced;
  //                    read them with position() / velocity())
  //   rebase(dt)       subtract dt from every time, so the next window starts at 0 again
  // A window sequence start, advance_to(dt), rebase(dt), advance_to(dt), ... follows the same
  // trajectory as one long window, up to the rounding of the time shifts.
  void start();
  EDStats advance_to(double t_end);
  void rebase(double dt);

  // state of particle i at window time t (lazy update, not stored)
  Vec3 position(int i, double t) const;
  Vec3 velocity(int i, double t) const;

 private:
  EDOptions opt;
  int ntypes = 0;
  std::vector<LawParams> laws;
  Vec3 L;                                // box lengths
  int nc[3] = {1, 1, 1};                 // cells per dimension
  double cw[3] = {1, 1, 1};              // cell widths
  std::vector<int> head, next, prev;     // cell lists
  std::vector<int> heap, hpos;           // indexed binary heap of particles by event time
  EDStats stats;
  double now = 0.0;

  void setup_cells();
  void cell_insert(int i);
  void cell_remove(int i);
  void advance(int i, double t);
  void predict(int i);
  void collide_pair(int i);
  void cross(int i);
  bool before(int i, int j) const;
  void heap_up(int k);
  void heap_down(int k);
  void heap_update(int i);
};

}    // namespace granfric

#endif
