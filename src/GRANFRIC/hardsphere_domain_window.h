/* -*- c++ -*- ----------------------------------------------------------
   SPDX-License-Identifier: GPL-2.0-or-later
   Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
   GRANFRIC: the domain-decomposed window of fix hardsphere/ed (keyword parallel domain).

   Each rank runs the window for its owned atoms plus copies of every other atom within a shell
   around them, then checks that the result is exact (see hardsphere_domain_window.cpp). The
   class owns the state kept from one window to the next (the core's slots, matched to atoms by
   ID) and does one stage per method.
------------------------------------------------------------------------- */

#ifndef LMP_GRANFRIC_HARDSPHERE_DOMAIN_WINDOW_H
#define LMP_GRANFRIC_HARDSPHERE_DOMAIN_WINDOW_H

#include "pointers.h"

#include "atom_record.h"

#include "event_driven.h"
#include "hardsphere_window_parts.h"
#include "id_map.h"
#include "host_compat.h"

#include <cstdint>
#include <vector>

namespace LAMMPS_NS {

class HardsphereRunState;

class HardsphereDomainWindow : protected Pointers {
 protected:
  GRANFRIC_HOST_ERROR    // (under LIGGGHTS: LAMMPS's error calls)

 public:
  // reach: the safety factor on the path bound v_max dt (keyword reach); check: a window with
  // a conflict is repaired or redone (keyword check yes), else kept
  HardsphereDomainWindow(HardsphereRunState &run, double reach, bool check);
  // one window [t0, t0 + dt) of the owned atoms, conflicts repaired among the ranks involved;
  // false: a conflict not repaired (or not checked for), nothing was changed (the caller redoes
  // the window gathered)
  bool run(double t0, double dt);
  // the last window's repair: its rounds, and the ranks' windows redone in them (summed over
  // the ranks and rounds, the same on every rank)
  int repair_rounds() const { return rounds; }
  long windows_redone() const { return nredone; }
  // the adaptive factor on the reach (>= 1; kept in restart files): it doubles after a
  // window whose guard failed (kicks or walls made atoms faster than the bound) or that was
  // not repaired, and narrows slowly while windows pass; the same on every rank (the shells of
  // the ranks in a conflict widen on their own, see own_factor)
  double reach_factor() const { return widen; }
  void set_reach_factor(double f) { widen = f; }
  // the most repair rounds of one window (the shell of a rank widens by 2^rounds)
  static constexpr int MAX_ROUNDS = 12;
  double memory_usage() const;

 private:
  // a rank's region: its owned atoms' bounding box widened by its shell W
  struct Region {
    double lo[3], hi[3];
    bool whole[3];    // the whole periodic length in this dimension (no images)
    double W;
    bool widened;     // the rank widened its shell in this round of a repair
  };

  HardsphereRunState &state;    // (the fix's)
  granfric::EventDriven &ed;
  const double reach;
  const bool check_windows;
  double widen = 1.0;

  // ---- the window's stages, in order
  bool new_epoch(double t0);
  void bound_reach(double dt);
  void make_regions(bool widened);
  void send_copies();
  void simulate(double dt);    // find_copies ... influence_times
  void find_copies();
  void order_by_id();
  void sort_by_id(std::vector<int> &atoms);    // atoms (indices) in the order of their IDs
  void load_core();
  void watch_events();
  bool advance();
  bool guard(double dt);
  void influence_times();
  void publish_histories();
  int compare_histories();
  bool checked(long *global, bool redid);
  bool repair(double dt, bool everyone);
  void commit();
  void sum_statistics();

  // ---- helpers of the stages
  bool can_keep(granfric::EDOptions &o);
  void keep_core();
  void fresh_core(granfric::EDOptions &o);
  bool inside(const Region &R, const double *x, int *s) const;
  double gap_to(const double *x, int r) const;
  long tag_of(int a) const;
  int mask_of(int a) const;
  AtomRecord record_of(int a) const;
  void frame_of(int a, const double *off, int *f) const;
  void set_framed();
  int partner_slot(const AtomRecord &r) const;
  bool slot_holds(int a, int sl, int *f) const;
  bool links_held(int sl, const int *f, double partner, const double *poff) const;
  void event_of(int e, int m, double *out) const;
  long exchange(const std::vector<double> &send, std::vector<double> &recv);
  bool guard_atom(int i, double s2, double dt);
  double shell(double f) const;

  // ---- this window (set by the stages)
  int nlocal = 0, dim = 3, nghost = 0, ncopy = 0, nwatch = 0;
  double step = 0.0;             // the window's length
  bool epoch_now = false;        // the window starts an epoch (atoms from LAMMPS)
  double T0 = 0.0, T1 = 0.0;     // its start and end in epoch time
  long received = 0;             // doubles this rank received
  granfric::EDOptions base;      // the fix's core options
  double gmx[2] = {0, 0};        // the largest speed bound and radius over all ranks
  double mybb[6];                // this rank's bounding box
  double vwall = 0.0, g = 0.0;   // the fastest wall's speed bound, |gravity|
  double D = 0.0, W = 0.0;       // the reach and the shell width (this rank's)
  double factor = 1.0;           // this rank's shell in this window: shell(factor)
  bool all_widened = false;      // every rank widened (a guard failed)
  int conflicts_here = 0;        // copies in conflict here
  bool blamed_here = false;      // a copy of an atom owned here was in conflict elsewhere
  std::vector<int> owner, blame, blamed;    // each copy's owner; ranks blamed, by and for this
  bool core_failed = false, guard_failed = false;
  int rounds = 0;                // the repair's rounds
  long nredone = 0;              // and the windows redone in them, over all ranks
  std::vector<PlannedKick> kplan; // the window's kicks
  double s2lim = 0.0;            // squared speed above which the core lists an atom (guard)
  std::vector<double> bb;        // every rank's bounding box
  std::vector<Region> reg;       // every rank's region
  bool keep = false;             // the core of the last window was kept
  long repredicted = 0, owned_changed = 0;
  std::vector<long> kick_from;   // each kick fix's counter before the window
  std::vector<tagint> kick_tags; // the slots' atom IDs for the kicks

  // ---- kept from one window to the next
  bool valid = false;            // (if the run's state says this window left the core)
  bigint last_natoms = -1;
  double own_factor = 1.0;       // this rank's shell factor at the start of a window
  double grid_lo[3] = {0, 0, 0}, grid_hi[3] = {0, 0, 0};    // the kept cell grid (open dims)
  bool grid_whole[3] = {false, false, false};
  bool framed[3] = {false, false, false};       // frame_of()'s dimensions (set_framed)
  granfric::IdMap slot_of_tag;                  // slot of each atom ID here
  std::vector<int> free_slots;
  std::vector<long> stag;                       // each slot's atom ID (-1: empty)
  std::vector<int> smask;                       // each slot's group mask (0: empty)
  std::vector<int> lslot;                       // slot of each owned atom (this window)
  std::vector<uint8_t> sowned, sowned_prev;     // slot owned in this / the last window
  std::vector<int> sseen;                       // slot matched in this window (stamp)
  int stamp = 0;
  std::vector<int> aorder;                      // the window's atoms in the order of their IDs
  std::vector<int> anew;                        // atoms without a slot (keep_core)
  std::vector<uint64_t> akeys;                  // (sort_by_id: ID and atom packed, sorted)

  // ---- scratch of every window, kept to spare their allocation: atoms sent (flags and
  // list), the slot of each atom, the copies' slots, their records in drecv and image shifts,
  // the watched slots (copies, then sent atoms) and each slot's place among them (-1: none),
  // the events of each watched slot (evlist from start), influence times, where each copy's
  // history was received, slots to empty; the sent atoms' records once each (srec: a vector
  // of its own, so that it keeps its size from window to window and is not filled anew)
  std::vector<double> srec, dsend, drecv, hsend, hrecv;
  std::vector<granfric::EDEvent> history;
  std::vector<char> sent;
  std::vector<int> sendlist, wlist, widx, rm, inslot, evlist, cslot, gsrc, start, fill, gshift;
  std::vector<double> tstar;
  std::vector<long> published;
  std::vector<uint8_t> watch;
  // the atoms for each other rank: to_rank[to_start[m] ...] go to rank to_dest[m]; each sent
  // atom's place in sendlist (by atom, -1: not sent), where its history starts in the window's
  // own histories; doubles for each rank and where they start
  std::vector<int> to_rank, to_start, to_dest, send_index, scounts, sdispls;
  // where each rank's part of the last received buffer lies (exchange)
  std::vector<int> rcounts, rdispls;
  std::vector<size_t> hist_at;
};

}    // namespace LAMMPS_NS

#endif
