/* -*- c++ -*- ----------------------------------------------------------
   SPDX-License-Identifier: GPL-2.0-or-later
   Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
   GRANFRIC: what fix hardsphere/ed keeps per atom, with the atoms (they migrate with them).

   - the stored states (several ranks only): each atom's position and velocity as the core that
     last owned it left them, so that a window on another rank, or one built afresh, continues
     it exactly (AtomRecord), and what the last window wrote into LAMMPS's arrays;
   - the last collision times of the TC model (tc > 0 only);
   - the per-atom tallies of the last step (when a compute or LAMMPS asks for them).
   The fix's per-atom callbacks (grow, copy, exchange, restart) hand their work to this class.
------------------------------------------------------------------------- */

#ifndef LMP_GRANFRIC_HARDSPHERE_ATOM_STATES_H
#define LMP_GRANFRIC_HARDSPHERE_ATOM_STATES_H

#include "pointers.h"

#include "atom_record.h"

#include "event_driven.h"

#include <cmath>

namespace LAMMPS_NS {
namespace hardsphere {
  class FarWrap;
}

class HardsphereAtomStates : protected Pointers {
 public:
  // a stored state's fields: XS_X, XS_V at time XS_T (epoch time; NaN: none yet), the periods
  // between the core's frame and LAMMPS's (XS_OFF), the last partner's ID (0: none) and its
  // image shift, the last collision time (epoch time); XS_WX, XS_WV, XS_WW: the x, v and
  // omega the last window wrote into LAMMPS's arrays, as written (NaN: not written with this
  // state), and the atom's radius, mass and type then (XS_BODY), so that the next window sees
  // that nothing else changed the atom without flying its state forward
  enum { XS_X = 0, XS_V = 3, XS_T = 6, XS_OFF = 7, XS_PARTNER = 10, XS_POFF = 11, XS_TLAST = 14,
         XS_WX = 15, XS_WV = 18, XS_WW = 21, XS_BODY = 24, XS_SIZE = 27 };
  // a tally's fields: the atom's collision virial (6), its pair and wall collisions, its
  // translational and rotational energy change in pair collisions, its energy change in wall
  // collisions (energy units), and the time of its last collision since the tallies began
  // (-1: none)
  enum { T_VIRIAL = 0, T_COLL = 6, T_WALL, T_DETR, T_DEROT, T_DEWALL, T_LAST, NTALLY };

  // what a serial window wrote into a sheared box's atoms (kept_written): x (3) and v_x
  enum { WR_X = 0, WR_VX = 3, WR_SIZE = 4 };

  // stored: keep stored states; tc: keep last collision times
  HardsphereAtomStates(LAMMPS *lmp, bool stored, bool tc);
  ~HardsphereAtomStates() override;
  HardsphereAtomStates(const HardsphereAtomStates &) = delete;
  HardsphereAtomStates &operator=(const HardsphereAtomStates &) = delete;

  // ---- the fix's per-atom callbacks
  void grow(int nmax);
  void copy(int i, int j);
  int pack(int i, double *buf) const;
  int unpack(int i, const double *buf);
  int per_atom() const;                       // doubles per atom in an exchange
  double memory_usage() const;
  void request_tallies();                     // from now on (allocated once)

  // a serial run in a sheared box keeps what its windows wrote into x and v_x (not in
  // exchanges: an atom that arrives has none), for undo_rounding, which then needs neither the
  // core nor its order; from now on (allocated once)
  void keep_written();
  bool keeps_written() const { return wrote != nullptr; }
  void store_written(int i, const double *x, double vx)
  {
    double *r = wrote[i];
    r[WR_X] = x[0], r[WR_X + 1] = x[1], r[WR_X + 2] = x[2], r[WR_VX] = vx;
  }

  bool stored() const { return xstate != nullptr; }
  bool has_tlast() const { return tlast != nullptr; }
  bool has_tallies() const { return atally != nullptr; }
  double *state(int i) const { return xstate[i]; }
  const double *tally(int i) const { return atally[i]; }
  double &last_collision(int i) const { return tlast[i]; }    // (absolute time; -inf: none)

  // ---- what windows read and write
  // owned atom i as a window takes it: its stored state (exact) or LAMMPS's atom at the start
  // of an epoch that began at absolute time clock
  AtomRecord record(int i, bool exact, double clock) const;
  // owned atom i from core particle e of ed (off: its periods; partner: the last partner's ID,
  // 0: none; wx, wv: what the window wrote into x and v, or null; its omega and body are
  // read from LAMMPS's arrays, where the window wrote them)
  void store_state(const granfric::EventDriven &ed, int i, int e, const double *off, double partner,
                   const double *wx = nullptr, const double *wv = nullptr);
  // the last collision time of core particle e (epoch time, epoch at clock) for atom i
  void store_tlast(const granfric::EventDriven &ed, int i, int e, double clock);
  // owned atom i's tallies of the step from core particle e
  void store_tally(const granfric::EventDriven &ed, int i, int e, double clock);
  // do owned atoms 0..n-1 still hold what the last window wrote (their states at epoch time
  // T0, flown under gravity g)? LAMMPS may have wrapped some into the box: their periods
  // follow
  bool states_hold(int n, double T0, const double *g, const hardsphere::FarWrap &wrap);
  // a new epoch: every atom's periods back to 0
  void clear_periods(int n);
  // the epoch time XS_WX and XS_WV hold (NaN: none)
  double written_at = NAN;

  // LAMMPS's balance and fix balance (shift) may round positions (FarWrap::match). Before
  // each neighbour list, every atom moved only so is put back where it was (undo_rounding):
  // where the last window wrote it, or, before the first window, where it was when the run
  // (or the balance command) began (note_positions at epoch time now, kept in XS_WX;
  // written_at then holds no time). So the positions a new epoch takes, and those of dumps
  // and restart files, are the serial run's bits.
  // In a sheared box (triclinic, Lees-Edwards: sheared) LAMMPS rounds every position when it
  // reneighbors, and an atom wrapped through a y face changes its x velocity by fix deform's
  // rate: both are put back as written with the tilt xy and its rate u (hardsphere::ShearWrap;
  // pbc_xy: the box's tilt when they were written), from the stored states or from what a
  // serial run kept (keep_written)
  void note_positions(double now);
  void undo_rounding(bool sheared, double pbc_xy, double xy, double u);

 private:
  double **xstate = nullptr;    // (null unless stored)
  int xstate_n = 0;             // rows set (t = NaN: none yet, when grown)
  double **wrote = nullptr;     // (null unless keep_written)
  int wrote_n = 0;              // rows set (x = NaN: none, when grown)
  double *tlast = nullptr;      // (null unless tc)
  int tlast_n = 0;              // entries set (to -inf when grown)
  double **atally = nullptr;    // (null until asked for)
  int atally_n = 0;             // rows set (to zero when grown)
  bool state_holds(int i, double T0, const granfric::Vec3 &g, const hardsphere::FarWrap &wrap);
};

}    // namespace LAMMPS_NS

#endif
