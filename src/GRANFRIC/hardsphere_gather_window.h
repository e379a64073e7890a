/* -*- c++ -*- ----------------------------------------------------------
   SPDX-License-Identifier: GPL-2.0-or-later
   Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
   GRANFRIC: the gathered window of fix hardsphere/ed (serial runs, keyword parallel gather,
   and the redo of a domain window that had a conflict).

   Every rank gathers the whole system, ordered by atom ID (so the result depends neither on
   the number of ranks nor on atom sorting), runs the core and takes back its owned atoms. The
   core's event queue is kept from one window to the next while nothing but this window changed
   the atoms. The class owns that state and does one stage per method.
------------------------------------------------------------------------- */

#ifndef LMP_GRANFRIC_HARDSPHERE_GATHER_WINDOW_H
#define LMP_GRANFRIC_HARDSPHERE_GATHER_WINDOW_H

#include "pointers.h"

#include "atom_record.h"

#include "event_driven.h"
#include "host_compat.h"

#include <cstdint>
#include <string>
#include <vector>

namespace LAMMPS_NS {

class HardsphereRunState;
namespace hardsphere {
  class FarWrap;
  class ShearWrap;
}

class HardsphereGatherWindow : protected Pointers {
 protected:
  GRANFRIC_HOST_ERROR    // (under LIGGGHTS: LAMMPS's error calls)

 public:
  explicit HardsphereGatherWindow(HardsphereRunState &run);
  // one window [t0, t0 + dt) of the whole system (redo: after a domain window's conflict)
  void run(double t0, double dt, bool redo);
  // serial runs: put back every atom that LAMMPS moved only by rounding (balance) where this
  // window wrote it, if the core still holds the atoms (runs on several ranks, and serial runs
  // in a sheared box, do it from what they kept, HardsphereAtomStates::undo_rounding)
  void undo_rounding();
  double memory_usage() const;

 private:
  HardsphereRunState &state;    // (the fix's)
  granfric::EventDriven &ed;

  // ---- the window's stages, in order
  void gather(bool exact);
  int allgather(const std::vector<double> &send, std::vector<double> &recv);
  void order_by_id();
  bool can_reuse(double T0);
  void fresh_core(bool exact);
  void schedule_kicks(double t0, double dt);
  void advance(double T1);
  void take_back(double T1);

  // ---- helpers of the stages
  AtomRecord record(int k) const;    // atom k of the gathered system
  bool reusable(int s, double T0, const hardsphere::FarWrap &wrap, const hardsphere::ShearWrap &shear);
  void written_state(int s, double t, double *w) const;
  void keep_atom(int i, int s, const int8_t *stored, const double *w);
  std::string endless_collisions() const;

  int ntotal = 0;                 // atoms in the system
  int myfirst = 0;                // index of this rank's first atom in the gathered system

  // ---- kept from one window to the next
  bool valid = false;             // the core continues the last window (if the run's state
                                  // says this window left it)
  std::vector<long> keys;         // the core particles' atom IDs (EDAccounting::key)
  std::vector<int> order;         // index in recvbuf (or the atom arrays) by ID
  std::vector<tagint> otags;      // the IDs in that order (= the core's order)
  bool same_atoms = false;        // otags unchanged since the core's last start
  // periods between the core's frame and LAMMPS's, per core particle and dimension (noff),
  // within +-OFFSET_MAX: a window that would go beyond ends with the queue dropped, so the next
  // one starts afresh from LAMMPS's positions with the offsets back at 0
  std::vector<int8_t> offset;
  static constexpr int OFFSET_MAX = 100;
  // how many core particles ahead the walks over all of them ask the memory for their records
  // (EventDriven::prefetch_particle; performance only)
  static constexpr int AHEAD = 16;
  int noff = 3;
  double wper[3] = {0, 0, 0};     // period per offset (0: not periodic)
  // A sheared box (Lees-Edwards): an atom whose y offset is k lies, in LAMMPS's frame, k times
  // the tilt further in x and moves k times the tilt's rate slower in x (as written with
  // HardsphereRunState::view_xy and view_u)
  bool sheared = false;
  void shear_view(int k, double *w) const;
  bool reusable_sheared(int s, const double *bx, const double *bv, const double *bw, const double *w,
                        const hardsphere::ShearWrap &wrap);

  // ---- scratch
  std::vector<double> sendbuf, recvbuf;
  std::vector<int> cmask;         // atom masks in core order
  std::vector<int> counts, displs;    // where each rank's part of recvbuf lies
};

}    // namespace LAMMPS_NS

#endif
