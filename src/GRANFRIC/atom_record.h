/* -*- c++ -*- ----------------------------------------------------------
   SPDX-License-Identifier: GPL-2.0-or-later
   Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
   GRANFRIC: one atom as the windows of fix hardsphere/ed take it.
------------------------------------------------------------------------- */

#ifndef LMP_GRANFRIC_ATOM_RECORD_H
#define LMP_GRANFRIC_ATOM_RECORD_H

#include "event_driven.h"

#include <cstddef>
#include <cstring>

namespace LAMMPS_NS {

// An atom as a window needs it: packed on its owner from LAMMPS's arrays, sent to other ranks
// in messages of doubles (SIZE per atom), read there. The layout is this struct; the positions
// of single fields in a message (AtomRecordAt) follow from it.
struct AtomRecord {
  double tag;                   // atom ID
  double x[3], v[3], w[3];      // position, velocity, angular velocity
  double radius, mass, type;
  double tlast;                 // last collision time relative to the window start (-inf: none)
  double mask;                  // group bits
  // the record at b (SIZE doubles of a message), and writing this one there
  static AtomRecord read(const double *b)
  {
    AtomRecord r;
    std::memcpy(&r, b, sizeof r);
    return r;
  }
  void write(double *b) const { std::memcpy(b, this, sizeof *this); }
  // the core's particle p takes this atom's state and body (not its last-collision time)
  void to_particle(granfric::EDParticle p) const
  {
    p.x = granfric::Vec3(x[0], x[1], x[2]);
    p.v = granfric::Vec3(v[0], v[1], v[2]);
    p.w = granfric::Vec3(w[0], w[1], w[2]);
    p.a = radius;
    p.m = mass;
    p.type = (int) type;
  }
};

// where the fields lie in a record of a message, in doubles
struct AtomRecordAt {
  static constexpr int SIZE = sizeof(AtomRecord) / sizeof(double);
  static constexpr int TAG = offsetof(AtomRecord, tag) / sizeof(double);
  static constexpr int X = offsetof(AtomRecord, x) / sizeof(double);
  static constexpr int V = offsetof(AtomRecord, v) / sizeof(double);
  static constexpr int W = offsetof(AtomRecord, w) / sizeof(double);
  static constexpr int RADIUS = offsetof(AtomRecord, radius) / sizeof(double);
  static constexpr int MASS = offsetof(AtomRecord, mass) / sizeof(double);
  static constexpr int TYPE = offsetof(AtomRecord, type) / sizeof(double);
  static constexpr int MASK = offsetof(AtomRecord, mask) / sizeof(double);
};
static_assert(sizeof(AtomRecord) % sizeof(double) == 0, "a record is a whole number of doubles");

}    // namespace LAMMPS_NS

#endif
