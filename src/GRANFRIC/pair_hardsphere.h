/* -*- c++ -*- ----------------------------------------------------------
   SPDX-License-Identifier: GPL-2.0-or-later
   Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
   GRANFRIC: hard-sphere collision laws as LAMMPS pair styles.

   pair_style hardsphere/rough  [inertia Q] [inertia/type I Q ...]   pair_coeff I J r beta
   pair_style hardsphere/walton [inertia Q] [inertia/type I Q ...]   pair_coeff I J r mu rtmax
   pair_style hardsphere/jz     [inertia Q] [inertia/type I Q ...]   pair_coeff I J qn qt kappa_s kappa_d
   Q = sphere | disc | a number 0 < q <= 1; I = a type or a range of types

   The pair styles compute no forces: they own the collision law of each type pair (used by
   fix hardsphere/ed and the other GRANFRIC styles), the contact distance a_i + a_j, the
   neighbor request, mixing, write_data and restart. single() reports what a collision of the
   pair would do now (for compute pair/local).
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(hardsphere/rough,PairHardsphereRough);
PairStyle(hardsphere/walton,PairHardsphereWalton);
PairStyle(hardsphere/jz,PairHardsphereJZ);
// clang-format on
#else

#ifndef LMP_GRANFRIC_PAIR_HARDSPHERE_H
#define LMP_GRANFRIC_PAIR_HARDSPHERE_H

#include "pair.h"

#include "collision.h"
#include "host_compat.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class PairHardsphere : public Pair {
 protected:
  GRANFRIC_HOST_ERROR    // (under LIGGGHTS: LAMMPS's error calls)

 public:
  // number of single() extra values, see single()
  static constexpr int NSINGLE = 8;

  PairHardsphere(class LAMMPS *, granfric::LawKind);
  ~PairHardsphere() override;

  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  void write_restart(FILE *) override;
  void read_restart(GRANFRIC_RESTART_ARGS) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(GRANFRIC_RESTART_ARGS) override;
  void write_data(FILE *) override;
  void write_data_all(FILE *) override;
  double single(int, int, int, int, double, double, double, double &) override;
  void *extract(const char *, int &) override;
  double memory_usage() override;

  // interface for the GRANFRIC fixes and computes
  const granfric::LawParams &law(int itype, int jtype) const { return params[itype][jtype]; }
  // the shape factor I/(m a^2) of atoms of type itype (inertia, or inertia/type for that type)
  double shape_factor(int itype) const;
  // true when every type has the shape factor of the inertia keyword
  bool one_shape() const { return type_shapes.empty(); }
  granfric::LawKind kind() const { return lawkind; }
  // law parameters for particle-wall contacts of type itype when a wall names none: I,I's
  const granfric::LawParams &wall_law(int itype) const { return params[itype][itype]; }
  // parse the law's coefficients from arg[0..narg-1] (the law's, then optionally a normal
  // restitution model and its values) into raw; 'who' names the command in errors
  granfric::LawParams parse_law(const std::string &who, int narg, char **arg, double *raw) const;
  static constexpr int NVALUES = 8;    // the size of raw: the law's and the model's values
  int ncoeff() const { return nraw; }
  const char *coeff_names() const;

 protected:
  granfric::LawKind lawkind;
  int nraw;                       // number of pair_coeff values of this law
  double qshape;                  // shape factor I/(m a^2)
  int inertia_style;              // SPHERE, DISC or NUMBER, for messages and restart
  // inertia/type: a type or range of types (as pair_coeff takes them) and its shape factor,
  // in the order given (a later one overrides an earlier one for the types both name)
  struct TypeShape {
    std::string types;
    double q;
    bool disc;
  };
  std::vector<TypeShape> type_shapes;
  std::vector<double> qtype;    // the shape factor per type, resolved at init_style
  double ***raw;                  // raw pair_coeff values per type pair, for write_data/restart
  granfric::LawParams **params;   // law per type pair
  double *onerad, *maxrad;        // largest radius per type, locally and globally
  double last_cut = 0.0;          // the largest cut-off while there were atoms
  int restart_format = 1;         // of the restart file being read

  void allocate();
  static bool type_range(const std::string &text, int ntypes, int &lo, int &hi);
  void resolve_shapes();
  void set_law(int i, int j);
  void mix(int i, int j);
};

// the three styles: PairHardsphere with its law (LAMMPS creates a pair style from LAMMPS * alone)
class PairHardsphereRough : public PairHardsphere {
 public:
  PairHardsphereRough(class LAMMPS *lmp) : PairHardsphere(lmp, granfric::LawKind::ROUGH) {}
};
class PairHardsphereWalton : public PairHardsphere {
 public:
  PairHardsphereWalton(class LAMMPS *lmp) : PairHardsphere(lmp, granfric::LawKind::WALTON) {}
};
class PairHardsphereJZ : public PairHardsphere {
 public:
  PairHardsphereJZ(class LAMMPS *lmp) : PairHardsphere(lmp, granfric::LawKind::JZ) {}
};

}    // namespace LAMMPS_NS

#endif
#endif
