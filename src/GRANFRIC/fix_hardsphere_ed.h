/* -*- c++ -*- ----------------------------------------------------------
   SPDX-License-Identifier: GPL-2.0-or-later
   Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
   GRANFRIC: fix hardsphere/ed, the exact event-driven integrator for hard spheres and discs.

   fix ID group hardsphere/ed [gravity gx gy gz] [tc t_c] [maxevents N] [parallel domain|gather]
                              [reach f] [check yes|no] [overlap error|allow]

   Each time step is a window in which every collision is processed in exact time order with the
   collision law of the hardsphere pair style (core/event_driven.h); positions, velocities and
   spins are advanced exactly to the end of the step.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(hardsphere/ed,FixHardsphereED);
// clang-format on
#else

#ifndef LMP_GRANFRIC_FIX_HARDSPHERE_ED_H
#define LMP_GRANFRIC_FIX_HARDSPHERE_ED_H

#include "fix.h"

#include "atom_record.h"

#include "event_driven.h"
#include "hardsphere_window_parts.h"
#include "host_compat.h"

#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace LAMMPS_NS {
namespace hardsphere {
class FarWrap;
}

class FixHardsphereED : public Fix {
 protected:
  GRANFRIC_HOST_ERROR    // (under LIGGGHTS: LAMMPS's error calls)

 public:
  // output vector entries (every collision count includes wall collisions; WALL_COLLISIONS is
  // their part)
  // QUEUE_REBUILDS: the fix's own neighbour structure (cell grid and every prediction) rebuilt
  // from scratch, because something outside the fix changed the atoms or a new run began
  enum { STEP_COLLISIONS, COLLISIONS, DISSIPATED, SLIDING, MAX_ONE_PARTICLE, QUEUE_REBUILDS,
         TC_ELASTIC, ENERGY_CREATING, INJECTED, WALL_COLLISIONS, WALL_ENERGY,
         // parallel windows (parallel domain): windows done by domain, conflicts (ghosts whose
         // history disagreed with their owner's where it mattered, guard failures) in the last
         // step and in total, windows repaired (or redone gathered), doubles communicated in the
         // last step and in total
         DOMAIN_WINDOWS, STEP_CONFLICTS, CONFLICTS, WINDOWS_REDONE, STEP_COMM, COMM,
         // particles predicted afresh at the start of the last step (over all ranks)
         STEP_PREDICTED,
         // repairs: rounds in total, and ranks' windows redone in them in total
         REPAIR_ROUNDS, RANKS_REDONE,
         // copies simulated in the last step (over all ranks)
         STEP_COPIES, NVECTOR };
  enum { GATHER, DOMAIN };
  static constexpr double RESTART_FORMAT = 2.0;    // (see write_restart)

  FixHardsphereED(class LAMMPS *, int, char **);
  // the fix hardsphere/ed with ID id, or an error in the name of who (a command and its style)
  static FixHardsphereED *lookup(class LAMMPS *lmp, const std::string &id, const char *who);
  ~FixHardsphereED() override;
  int setmask() override;
  void init() override;
  void post_force(int) override;
  void post_force_respa(int, int, int) override;
  void setup(int) override;
  void setup_pre_neighbor() override { undo_rounding(); }
  void pre_neighbor() override
  {
    if (balancing) undo_rounding();
  }
  void initial_integrate(int) override;
  void initial_integrate_respa(int, int, int) override;
  double compute_vector(int) override;

  double memory_usage() override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;

  // for computes and tests
  // everything since the fix was created (not kept in restart files; the output totals are)
  const granfric::EDStats &cumulative() const { return cum; }
  // elapsed simulated time covered by cumulative()
  double cumulative_time() const { return cum_time; }
  // a compute asks for impact-angle histograms with this many bins (one size per fix)
  void request_gamma_bins(int nbins);
  // one collision of the last step, for per-collision output: absolute time, the atoms' IDs and
  // group masks (id[1] = 0 and mask[1] = 0 for a wall), the wall (0: a pair; k: the k-th wall
  // fix), what the core reports. Each collision is kept by one rank only.
  struct CollisionRow {
    double t;
    tagint id[2];
    int mask[2];
    int wall;
    granfric::EDCollisionRecord c;
  };
  // a compute asks for the rows of every step from now on
  void request_collision_rows() { want_rows = true; }
  const std::vector<CollisionRow> &collision_rows() const { return rows; }
  // Per-atom tallies of the last step, kept with the atoms (they migrate with them), from the
  // first step after they were asked for (a compute, or LAMMPS asking for per-atom virials):
  // the atom's collision virial (6), its pair and wall collisions, its translational and
  // rotational energy change in pair collisions, its energy change in wall collisions (energy
  // units), and the time of its last collision since the tallies began (-1: none)
  enum { T_VIRIAL = 0, T_COLL = 6, T_WALL, T_DETR, T_DEROT, T_DEWALL, T_LAST, NTALLY };
  void request_atom_tallies();
  const double *atom_tally(int i) const { return atally[i]; }

 protected:
  double gravity[3];
  double tc;
  long maxevents;
  int nlevels_respa;
  double *tlast;                         // per atom: absolute time of the last collision
                                         //   (only with the TC model, else null)
  int tlast_n = 0;                       // entries of tlast set (to -inf when grown)
  // atom i's last collision time relative to t0 (-inf: none, or no TC model), and back
  double tlast_since(int i, double t0) const
  {
    return !tlast || tlast[i] == -granfric::INF ? -granfric::INF : tlast[i] - t0;
  }
  void set_tlast(int i, double t_last, double t0)
  {
    if (tlast) tlast[i] = t_last == -granfric::INF ? -granfric::INF : t_last + t0;
  }

  // ---- one time origin of the windows (an epoch)
  // Within an epoch the core's times run on from its start: a window ends at epoch time
  // (step - epoch_step) dt, and a particle's stored state (position and velocity at the time of
  // its last collision or kick) changes only by its own events, never by a shift of the time
  // origin. Every pair quantity is then computed from the same operands on any rank count and
  // whenever it is computed, so that a run gives the same bits serially and in domain windows.
  // A new epoch starts from LAMMPS's atoms as they are: at the first window, after anything
  // other than this fix changed atoms or the configuration, after a restart file was written,
  // and every EPOCH_WINDOWS windows (which bounds how far the times run: the rounding of the
  // core's times stays that of a short run); every rank and a serial run start epochs at the
  // same steps.
  static constexpr bigint EPOCH_WINDOWS = 1000;
  bigint epoch_step = 0;                 // the step at which the epoch's time is 0
  double epoch_clock = 0.0;              // the absolute time then
  double epoch_dt = 0.0;                 // its step length
  bool epoch_due = true;                 // a new epoch at the next window
  // the configuration of the last run (a new run with another one starts a new epoch)
  granfric::EDOptions run_options;
  std::vector<granfric::LawParams> run_laws;
  int run_ntypes = -1;
  bool epoch_starts() const;             // must the next window start a new epoch?
  void begin_epoch(double t0);           // a new epoch at this window (absolute start t0)
  double epoch_time(bigint step) const { return (double) (step - epoch_step) * epoch_dt; }
  // Per atom, on several ranks (both parallel modes): the atom's stored state as the
  // core that last owned it left it (AtomRecord), so that it goes with the atom to another rank
  // and a window built afresh (a gathered redo, a new cell grid) continues it exactly.
  // XS_WX, XS_WV: the x and v the last window wrote into LAMMPS's arrays, as they were
  // written (NaN: not written with this state), so that the next window sees that nothing
  // else changed the atom without flying its stored state forward again.
  enum { XS_X = 0, XS_V = 3, XS_T = 6, XS_OFF = 7, XS_PARTNER = 10, XS_POFF = 11, XS_TLAST = 14,
         XS_WX = 15, XS_WV = 18, XS_SIZE = 21 };
  double **xstate = nullptr;             // (null unless kept)
  int xstate_n = 0;                      // rows set (t = NaN: none yet, when grown)
  double written_at = NAN;               // the epoch time XS_WX and XS_WV hold (NaN: none)
  // owned atom i from core particle e at window end time T1 (off: its periods; partner: the
  // last partner's ID, 0: none; wx, wv: what the window wrote into x and v, or null)
  void store_state(int i, int e, const double *off, double partner, const double *wx = nullptr,
                   const double *wv = nullptr);
  // do owned atoms 0..n-1 still hold what the last window wrote (their states at epoch time
  // T0)? LAMMPS may have wrapped some into the box: their periods follow (state_holds: one atom)
  bool states_hold(int n, double T0, const hardsphere::FarWrap &wrap);
  bool state_holds(int i, double T0, const hardsphere::FarWrap &wrap);
  // LAMMPS's balance and fix balance (shift) may round positions (FarWrap::match). Before
  // each neighbour list, every atom moved only so is put back where it was (undo_rounding):
  // where the last window wrote it, or, before the first window, where it was when the run
  // (or the balance command) began (note_positions, kept in XS_WX; written_at then holds no
  // time). So the positions a new epoch takes, and those of dumps and restart files, are the
  // serial run's bits.
  void note_positions();
  void undo_rounding();
  bool balancing = false;    // a fix moves the subdomains during the run (fix balance)
  class PairHardsphere *pair;

  granfric::EventDriven ed;
  granfric::EDStats last;                // last step
  granfric::EDStats cum;                 // cumulative
  double cum_time;
  int gamma_bins;
  double totals[NVECTOR];                // running totals (restart)

  // the windows: gathered (serial, parallel gather, and the redo of a domain window that had a
  // conflict) and domain-decomposed; both run the one core
  friend class HardsphereGatherWindow;
  friend class HardsphereDomainWindow;
  class HardsphereGatherWindow *gwin;
  class HardsphereDomainWindow *dwin;
  void invalidate_windows();             // the core no longer holds what a window left
  std::vector<int> counts, displs;       // where each rank's part of the last received buffer lies
  // a restart file was written: the next window starts afresh from the atoms as the file holds
  // them, as a run continued from that file does (see resync_for_restart)
  bool resync = false;
  std::vector<class HardsphereDriving *> kicks;  // driving fixes, applied inside the window
  std::vector<class HardsphereWallPart *> walls; // walls, collided inside the window

  bool check_windows = true;             // keyword check: redo a domain window that has a conflict
  int parallel;                          // GATHER or DOMAIN
  double reach;                          // ghost shell safety factor on v_max dt
  double widen;                          // adaptive factor on top of reach (>= 1)

  int choice(const char *keyword, const std::string &value,
             const std::vector<std::string> &allowed) const;
  granfric::EDOptions core_options() const;
  std::vector<granfric::LawParams> law_table() const;
  void configure_core(const granfric::EDOptions &o, bool collective = true);
  double window_start_time() const;
  void resync_for_restart();
  // image flags of an atom that was wrapped by dimg periods (most are not: inline test)
  static void shift_image(imageint &image, const int *dimg)
  {
    if (dimg[0] | dimg[1] | dimg[2]) wrap_image(image, dimg);
  }
  static void wrap_image(imageint &image, const int *dimg);
  void finish_window(double dt);
  // owned atom i: its stored state (exact: from xstate) or LAMMPS's at an epoch start
  AtomRecord atom_record(int i, bool exact) const;
  int allgather(const std::vector<double> &send, std::vector<double> &recv);
  bool check_overlaps = false;
  bool allow_overlap = false;            // keyword overlap allow: overlapping pairs separate
  void report_overlaps(bool partial);
  // errors in the setup of a run: walls that cross, a diameter longer than the box, atoms
  // behind a wall
  void check_walls_cross() const;
  void check_box_fits_atoms() const;
  void check_atoms_between_walls() const;
  void check_plane();                      // (2d: every atom at z = 0, vz = 0, spin about z)
  void refuse_rerun() const;
  void check_scales() const;
  void check_thermal_walls(double mmax, double amax) const;
  void warn_ignored_inputs() const;
  bigint plane_checked = -1;               // the number of atoms the last check_plane saw
  bigint added_at = -1;                    // the step atoms were added in this run (-1: none)
  static constexpr tagint NOATOM = MAXTAGINT;
  tagint first_atom(const std::function<bool(int)> &bad) const;
  double atom_value(tagint who, const std::function<double(int)> &value) const;
  // the core's start from the particles set; its exceptions (and configure_core's) become
  // LAMMPS errors, of all ranks when collective (every rank runs the same core), else of one
  void start_core(bool collective);
  void core_failed(const std::exception &e, bool collective);
  // the kicks of the window [t0, t0 + dt) (collective: every rank plans them alike), then
  // given to the core whose slots hold the atoms tags
  std::vector<PlannedKick> plan_kicks(double t0, double dt);
  void schedule_kicks(const std::vector<PlannedKick> &plan, const std::vector<tagint> &tags,
                      const std::vector<int> &masks);

  // per-collision rows (request_collision_rows): the core's records of the window, and the rows
  bool want_rows = false;
  double **atally = nullptr;                    // per-atom tallies (NTALLY per atom), or null
  int atally_n = 0;                             // rows of atally set (to zero when grown)
  double wstep[6] = {0, 0, 0, 0, 0, 0};         // the step's global collision virial
  void store_tally(int i, int s);
  std::vector<granfric::EDCollisionRecord> clog;
  std::vector<CollisionRow> rows;
  // the rows of the core's collision records of the window (epoch times), with the IDs and
  // masks of its particles (by core index)
  template <class TAGS>
  void keep_rows(const TAGS &tags, const std::vector<int> &masks)
  {
    const double t0 = epoch_clock;
    ed.record_collisions(nullptr);
    rows.clear();
    for (const auto &c : clog) {
      const bool wall = c.j < 0;
      rows.push_back({t0 + c.t, {(tagint) tags[c.i], wall ? 0 : (tagint) tags[c.j]},
                      {masks[c.i], wall ? 0 : masks[c.j]}, wall ? -c.j : 0, c});
    }
  }
};

}    // namespace LAMMPS_NS

#endif
#endif
