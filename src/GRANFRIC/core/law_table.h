// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the table of collision laws.
//
// One entry per law: its name (the LAMMPS pair style is hardsphere/<name>, the C API and the
// Python tools use the same names), its coefficients in the order a user gives them, each with
// its admissible range, and the map from the coefficients to LawParams (collision.h). Every
// host reads the laws from here: the pair styles (and the walls through them), the C API and
// through it the Python tools.
#ifndef GRANFRIC_CORE_LAW_TABLE_H
#define GRANFRIC_CORE_LAW_TABLE_H

#include "collision.h"

namespace granfric {

struct LawCoeff {
  const char *name;
  double lo, hi;        // the admissible closed range
  bool inf_ok;          // "inf" is admissible (then hi = INF)
  const char *range;    // the range in words, for messages
};

struct LawSpec {
  static constexpr int MAXCOEFF = 4;
  const char *name;
  LawKind kind;
  int ncoeff;
  LawCoeff coeff[MAXCOEFF];
  // the first coefficient sets the normal restitution (r, or qn for jz); its value for an
  // elastic normal motion, which a restitution model that does not use it (NULL) takes
  double elastic_normal;
  const char *coeff_names;     // the coefficients' names in order, separated by blanks
  // a condition on the coefficients together, in words (nullptr: none), and whether c meets it
  const char *joint;
  bool (*joint_ok)(const double *c);
  LawParams (*make)(const double *c);
};

// the laws, by their index (LawKind's order); NLAWS of them
constexpr int NLAWS = 3;
const LawSpec &law_spec(int index);
inline const LawSpec &law_spec(LawKind k) { return law_spec((int) k); }
// the law called name, or nullptr
const LawSpec *find_law(const char *name);

// A normal restitution model that replaces the constant one of any law: the keyword that follows
// the law's coefficients, its own coefficients with their ranges, and what it makes of the law
// (viscoelastic.h, collision.h):
//   viscoelastic vref                 the law's normal restitution (r, or 1 - 2 qn) is the one
//                                     at normal impact speed vref; delta ~ |g_n|^(1/5)
//   viscoelastic/material Y nu A      from the material (Young's modulus, Poisson's ratio,
//                                     dissipative constant) and each pair's sizes and masses;
//                                     the law's normal coefficient is given as NULL
struct RestitutionSpec {
  static constexpr int MAXCOEFF = 3;
  const char *name;
  int ncoeff;
  LawCoeff coeff[MAXCOEFF];
  const char *coeff_names;
  bool normal_null;    // the law's normal coefficient must be NULL (it is not used)
  // sets the viscoelastic fields of law (made from the law's coefficients) from c; returns
  // nullptr, or why the two do not go together
  const char *(*apply)(LawParams &law, const double *c);
};
constexpr int NRESTITUTION = 2;
const RestitutionSpec &restitution_spec(int index);
// the model called name, or nullptr
const RestitutionSpec *find_restitution(const char *name);
// -1 if coefficients c of model s are admissible, else the index of the first that is not
int first_bad_restitution_coeff(const RestitutionSpec &s, const double *c);

// Whether coefficients c of law s are admissible: -1 if they are; k in 0 .. ncoeff-1 if
// coefficient k lies outside its range (or is not a number); ncoeff if they break the joint
// condition
int first_bad_coeff(const LawSpec &s, const double *c);

}    // namespace granfric

#endif
