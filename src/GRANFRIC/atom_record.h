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

// An atom as a window needs it: packed on its owner, sent to other ranks in messages of
// doubles (SIZE per atom), read there. The layout is this struct; the positions of single
// fields in a message (AtomRecordAt) follow from it.
// Within one time origin of the windows (an epoch, see HardsphereRunState::begin_epoch) an atom
// is the core's stored state, exactly as the core that owns it keeps it: position and velocity
// at the atom's own time t (its last collision or kick, in epoch time), in the core's frame
// (unwrapped since the epoch began: LAMMPS's position plus off periods), and the last partner,
// so that every core that holds the atom predicts and collides it with the same operands.
// At the start of an epoch it is LAMMPS's atom (t = 0, off = 0, no last partner).
struct AtomRecord {
  double tag;                   // atom ID
  double xl[3];                 // position in LAMMPS's frame at the window start
  double x[3], v[3], w[3];      // stored position and velocity (at t), angular velocity
  double t;                     // the time of x and v (epoch time)
  double radius, mass, type;
  double tlast;                 // last collision time (epoch time; -inf: none)
  double mask;                  // group bits
  double off[3];                // periods between the core's frame and LAMMPS's
  double partner;               // the ID of the last partner (0: none)
  double poff[3];               // its image shift (core frames), see EventDriven::set_last_partner
  // the record at b (SIZE doubles of a message), and writing this one there
  static AtomRecord read(const double *b)
  {
    AtomRecord r;
    std::memcpy(&r, b, sizeof r);
    return r;
  }
  void write(double *b) const { std::memcpy(b, this, sizeof *this); }
  // the core's particle p takes this atom's stored state and body (not its last-collision time)
  void to_particle(granfric::EDParticle p) const
  {
    p.x = granfric::Vec3(x[0], x[1], x[2]);
    p.v = granfric::Vec3(v[0], v[1], v[2]);
    p.t = t;
    p.w = granfric::Vec3(w[0], w[1], w[2]);
    p.a = radius;
    p.m = mass;
    p.type = (int) type;
  }
  // does particle p hold this atom's state and body, bit for bit?
  bool held_by(granfric::EDParticleView p) const;
};

// does particle p hold the state x, v (at t; last collision at tlast) and the body w, radius,
// mass, type, bit for bit? (x, v, w: three doubles each; x and v compared as bits, so a zero
// of the other sign counts as a change)
inline bool holds_atom(granfric::EDParticleView p, const double *x, const double *v, double t,
                       double tlast, const double *w, double radius, double mass, double type)
{
  static_assert(sizeof(granfric::Vec3) == 3 * sizeof(double), "a Vec3 is three doubles");
  return std::memcmp(&p.x, x, sizeof p.x) == 0 && std::memcmp(&p.v, v, sizeof p.v) == 0 && p.t == t &&
      p.w.x == w[0] && p.w.y == w[1] && p.w.z == w[2] && p.a == radius && p.m == mass &&
      p.type == (int) type && p.t_last == tlast;
}

inline bool AtomRecord::held_by(granfric::EDParticleView p) const
{
  return holds_atom(p, x, v, t, tlast, w, radius, mass, type);
}

// where the fields lie in a record of a message, in doubles
struct AtomRecordAt {
  static constexpr int SIZE = sizeof(AtomRecord) / sizeof(double);
  static constexpr int TAG = offsetof(AtomRecord, tag) / sizeof(double);
  static constexpr int XL = offsetof(AtomRecord, xl) / sizeof(double);
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
