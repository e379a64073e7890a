/* -*- c++ -*- ----------------------------------------------------------
   SPDX-License-Identifier: GPL-2.0-or-later
   Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
   GRANFRIC: the state of a run of fix hardsphere/ed that every window reads and writes.

   The fix owns one of these and hands it to whichever window runs a step (gathered or
   domain-decomposed, hardsphere_*_window.h): the one event-driven core, the time origin of
   the windows (an epoch), the per-atom states, the settings the core is configured from, the
   kick plan, the counters of the output vector and the per-collision rows. A window reads and
   writes only this object, never the fix.
------------------------------------------------------------------------- */

#ifndef LMP_GRANFRIC_HARDSPHERE_RUN_STATE_H
#define LMP_GRANFRIC_HARDSPHERE_RUN_STATE_H

#include "pointers.h"

#include "hardsphere_atom_states.h"
#include "hardsphere_window_parts.h"
#include "host_compat.h"

#include "event_driven.h"

#include <exception>
#include <string>
#include <vector>

namespace LAMMPS_NS {

class PairHardsphere;

class HardsphereRunState : protected Pointers {
 protected:
  GRANFRIC_HOST_ERROR    // (under LIGGGHTS: LAMMPS's error calls)

 public:
  // the output vector of the fix (every collision count includes wall collisions;
  // WALL_COLLISIONS is their part)
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

  // stored: keep each atom's stored state (several ranks); the TC model's duration
  HardsphereRunState(LAMMPS *lmp, bool stored, double tc);
  LAMMPS *instance() const { return lmp; }    // (for the windows)

  // ---- what the core is configured from: the fix's keywords, and what init() found
  struct Settings {
    double gravity[3] = {0.0, 0.0, 0.0};
    double tc = 0.0;                      // TC model duration (0: off)
    long maxevents = 1000000;             // collisions per atom and step (collapse guard)
    long maxcross = 10000;                // cell crossings per atom and step, summed (runaway guard)
    bool allow_overlap = false;           // overlapping pairs separate (else an error)
    int gamma_bins = 0;                   // impact-angle histogram bins (0: none)
  } settings;
  PairHardsphere *pair = nullptr;
  std::vector<HardsphereDriving *> kicks;    // driving fixes, applied inside the window
  std::vector<HardsphereWallPart *> walls;   // walls, collided inside the window
  granfric::EDOptions core_options() const;
  std::vector<granfric::LawParams> law_table() const;
  // A new run: the core is configured afresh (and the kept windows dropped) unless its
  // configuration is the same in every respect as the last run's
  void new_run();

  // ---- the one core, used by one window at a time
  granfric::EventDriven ed;
  // did window w leave the core as it is now (its kept queue goes on), and w takes it
  bool core_kept_by(const void *w) const { return core_user == w; }
  void core_used_by(const void *w) { core_user = w; }
  // the core no longer holds what a window left (something else used or changed it)
  void drop_core();
  // the core's configuration and start; its exceptions become LAMMPS errors, of all ranks
  // when collective (every rank runs the same core), else of one
  void configure_core(const granfric::EDOptions &o, bool collective = true);
  void start_core(bool collective);
  void core_failed(const std::exception &e, bool collective);

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
  bool epoch_due = true;                 // a new epoch at the next window
  bool epoch_starts() const;             // must the next window start a new epoch?
  void begin_epoch(double t0);           // a new epoch at this window (absolute start t0)
  double epoch_time(bigint step) const { return (double) (step - epoch_step) * epoch_dt; }
  // this window's start and end in epoch time
  double window_start() const;
  double window_end() const;

  // ---- a sheared box (Lees-Edwards, check_box_changes): the images' shift as a line in
  // absolute time, xy + rate (t - t_anchor), anchored at the first window of a sheared run and
  // kept across runs and in restart files while fix deform goes on at the same rate (to 1e-12)
  // and the tilt stays on the line (to 1e-9 of the box, up to box flips). So a run continued
  // from a restart file takes the same shift and rate as the uninterrupted one, whatever the
  // rounding of fix deform's own tilt, which it recomputes from its start at every run.
  struct ShearAnchor {
    bool set = false;
    double xy = 0.0, t = 0.0, rate = 0.0;
  } shear;
  // at a window that starts at absolute time t0: the anchor checked, or set at the first
  // window of a run (an error elsewhere: fix deform does not change xy at a constant rate)
  void anchor_shear(double t0);
  double shear_shift_at(double t) const { return shear.xy + shear.rate * (t - shear.t); }
  double shear_rate() const;             // (the anchor's, or fix deform's before the first window)
  // the tilt and its rate with which the last window wrote the atoms (an atom y periods off
  // is written xy further in x and the rate faster in vx): the anchored shift at the window's
  // end, on the branch of the box's tilt (flips); and the box's tilt then, with which
  // Domain::pbc() wraps atoms later in that step (fix deform changes it at the step's end)
  double view_xy = 0.0, view_u = 0.0, pbc_xy = 0.0;

  // ---- per atom
  HardsphereAtomStates atoms;
  // owned atom i as a window takes it: its stored state (exact) or LAMMPS's atom at the
  // start of an epoch
  AtomRecord atom_record(int i, bool exact) const { return atoms.record(i, exact, epoch_clock); }
  // owned atom i is core particle e at the window's end: its stored state (several ranks),
  // last collision time and tallies (where kept); off: its periods, partner: the last
  // partner's ID (0: none), wx, wv: what the window wrote into x and v
  void take_back(int i, int e, const double *off, double partner, const double *wx, const double *wv)
  {
    if (atoms.stored()) atoms.store_state(ed, i, e, off, partner, wx, wv);
    if (atoms.has_tlast()) atoms.store_tlast(ed, i, e, epoch_clock);
    if (atoms.has_tallies()) atoms.store_tally(ed, i, e, epoch_clock);
  }

  // ---- kicks: those of the window [t0, t0 + dt) (collective: every rank plans them alike),
  // then given to the core whose slots hold the atoms tags
  std::vector<PlannedKick> plan_kicks(double t0, double dt);
  void schedule_kicks(const std::vector<PlannedKick> &plan, const std::vector<tagint> &tags,
                      const std::vector<int> &masks);
  // (a window redone takes its kicks again)
  std::vector<long> kick_counters() const;
  void rewind_kicks(const std::vector<long> &counters);

  // ---- overlapping atoms, checked once per run after the first window's start, and after
  // atoms were added (at step added_at, -1: none); partial windows sum over the ranks
  bool check_overlaps = false;
  bigint added_at = -1;
  void report_overlaps(bool partial);

  // ---- counters
  double totals[NVECTOR];                // running totals (restart)
  granfric::EDStats last;                // the last step's, summed over the ranks
  granfric::EDStats cum;                 // everything since the fix was created
  double cum_time = 0.0;                 // elapsed simulated time covered by cum
  double wstep[6] = {0, 0, 0, 0, 0, 0};  // the step's global collision virial (this rank's share)
  // the window's statistics (identical on every rank) into the totals, the virial and the walls
  void finish_window(double dt);

  // ---- per-collision rows (asked for by computes): the core's records of the window, and
  // the rows with IDs, masks and absolute times
  struct CollisionRow {
    double t;
    tagint id[2];
    int mask[2];
    int wall;    // 0: a pair; k: the k-th wall fix
    granfric::EDCollisionRecord c;
  };
  bool want_rows = false;
  std::vector<granfric::EDCollisionRecord> clog;
  std::vector<CollisionRow> rows;
  // the core records collisions into clog if rows are wanted
  void record_collisions();
  // the rows of clog, with the IDs and masks of the core's particles (by core index)
  template <class TAGS>
  void keep_rows(const TAGS &tags, const std::vector<int> &masks)
  {
    ed.record_collisions(nullptr);
    rows.clear();
    for (const auto &c : clog) {
      const bool wall = c.j < 0;
      rows.push_back({epoch_clock + c.t, {(tagint) tags[c.i], wall ? 0 : (tagint) tags[c.j]},
                      {masks[c.i], wall ? 0 : masks[c.j]}, wall ? -c.j : 0, c});
    }
  }

 private:
  const void *core_user = nullptr;       // the window that last left the core
  double epoch_dt = 0.0;                 // the epoch's step length
  // the configuration of the last run (a new run with another one starts a new epoch)
  granfric::EDOptions run_options;
  std::vector<granfric::LawParams> run_laws;
  int run_ntypes = -1;
};

}    // namespace LAMMPS_NS

#endif
