/* -*- c++ -*- ----------------------------------------------------------
   SPDX-License-Identifier: GPL-2.0-or-later
   Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
   GRANFRIC: what fix hardsphere/ed asks of the fixes that act inside its windows.

   A fix that drives the atoms (fix hardsphere/kick) or bounds them (fix hardsphere/wall)
   implements one of these interfaces and holds its parameters; fix hardsphere/ed finds such
   fixes among the defined ones by the interface and includes none of their headers.
------------------------------------------------------------------------- */

#ifndef LMP_GRANFRIC_HARDSPHERE_WINDOW_PARTS_H
#define LMP_GRANFRIC_HARDSPHERE_WINDOW_PARTS_H

#include "lmptype.h"

#include "event_driven.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

// global events at given times inside a window (random kicks)
class HardsphereDriving {
 public:
  // the kicks k at absolute times in [t0, t1), consumed
  virtual void kicks_in(double t0, double t1, std::vector<double> &times, std::vector<long> &index) = 0;
  // the next kick's index, and setting it back (a window that is redone takes its kicks again)
  virtual long kick_counter() const = 0;
  virtual void rewind(long k) = 0;
  // the velocity shift of kick k that keeps the driven atoms' momentum (collective; the same
  // bits on any number of ranks)
  virtual granfric::Vec3 momentum_shift(long k, int dim) const = 0;
  // the typical speed the kicks of one step of length dt give an atom (dim dimensions)
  virtual double speed_scale(double dt, int dim) const = 0;
  // kick k applied to the core's particles: tag[e], mask[e] of core particle e
  virtual void apply(granfric::EventDriven &ed, const std::vector<tagint> &tag,
                     const std::vector<int> &mask, long k, int dim, const granfric::Vec3 &dvcm) const = 0;

 protected:
  ~HardsphereDriving() = default;    // (the fix is deleted as a fix)
};

// one kick of a window as planned: its epoch time, the fix (its place among the driving fixes),
// the kick's index and the velocity shift that keeps the momentum
struct PlannedKick {
  double t;
  int fix;
  long k;
  granfric::Vec3 dvcm;
};

// a plane wall of the core
class HardsphereWallPart {
 public:
  virtual const char *wall_id() const = 0;        // the fix's ID
  virtual int dimension() const = 0;              // normal to x, y or z (0, 1, 2)
  virtual std::string face() const = 0;           // e.g. "ylo"
  virtual granfric::EDWall geometry() const = 0;  // position and motion only
  // the wall for the core, with its collision laws (after the fix's init())
  virtual granfric::EDWall wall() const = 0;
  // one step's collisions with the wall: their number, the momentum they gave the wall (3
  // values), the energy the wall gave the particles, the step length
  virtual void tally(long hits, const double *impulse, double work, double dt) = 0;

 protected:
  ~HardsphereWallPart() = default;    // (the fix is deleted as a fix)
};

}    // namespace LAMMPS_NS

#endif
