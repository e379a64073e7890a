// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: fix hardsphere/wall (see the header and doc/fix_hardsphere_wall.rst)
------------------------------------------------------------------------- */

#include "fix_hardsphere_wall.h"

#include "hardsphere_host.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "modify.h"
#include "pair_hardsphere.h"
#include "update.h"

#include <cmath>
#include <cstring>
#include <set>
#include <string>

using namespace LAMMPS_NS;

FixHardsphereWall::FixHardsphereWall(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), dim(1), side(-1), edge(false), pos(0.0), temperature(-1.0), seed(1),
    amplitude(0.0), omega(0.0), sine(false)
{
  if (narg < 5) utils::missing_cmd_args(FLERR, "fix hardsphere/wall face pos", error);
  const std::string face = arg[3];
  const char *faces[] = {"xlo", "xhi", "ylo", "yhi", "zlo", "zhi"};
  int f = -1;
  for (int k = 0; k < 6; k++)
    if (face == faces[k]) f = k;
  if (f < 0)
    error->all(FLERR, "Fix hardsphere/wall face {} is not one of xlo, xhi, ylo, yhi, zlo, zhi",
               face);
  dim = f / 2;
  side = (f % 2) ? +1 : -1;
  if (dim == 2 && domain->dimension == 2)
    error->all(FLERR, "Fix hardsphere/wall face {} is not allowed in a 2d simulation", face);
  if (domain->periodicity[dim])
    error->all(FLERR, "Fix hardsphere/wall face {} needs a non-periodic boundary in {} "
               "(boundary f or m)", face, "xyz"[dim]);
  if (strcmp(arg[4], "EDGE") == 0)
    edge = true;
  else
    pos = utils::numeric(FLERR, arg[4], false, lmp);
  int iarg = 5;
  std::set<std::string> given;    // (a keyword given twice would override or add silently)
  while (iarg < narg) {
    if (!given.insert(arg[iarg]).second)
      error->all(FLERR, "Fix hardsphere/wall keyword {} is given twice: give each keyword once",
                 arg[iarg]);
    if (strcmp(arg[iarg], "coeffs") == 0) {
      // (every word up to the next keyword: a value that is not a number is reported as such
      // when the coefficients are checked against the pair style's law)
      iarg++;
      auto keyword = [](const char *w) {
        for (const char *k : {"coeffs", "thermal", "vibrate", "slide", "shake"})
          if (strcmp(w, k) == 0) return true;
        return false;
      };
      while (iarg < narg && !keyword(arg[iarg])) coeffs.emplace_back(arg[iarg++]);
      if (coeffs.empty())
        error->all(FLERR, "Fix hardsphere/wall coeffs needs the law's coefficients, as pair_coeff "
                   "takes them");
    } else if (strcmp(arg[iarg], "vibrate") == 0) {
      if (iarg + 4 > narg)
        utils::missing_cmd_args(FLERR, "fix hardsphere/wall vibrate sine|parabolic A omega", error);
      if (strcmp(arg[iarg + 1], "parabolic") == 0)
        sine = false;
      else if (strcmp(arg[iarg + 1], "sine") == 0)
        sine = true;
      else
        error->all(FLERR, "Fix hardsphere/wall vibrate {} is not available (allowed: sine, "
                   "parabolic)", arg[iarg + 1]);
      amplitude = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
      omega = utils::numeric(FLERR, arg[iarg + 3], false, lmp);
      if (!(amplitude > 0.0))
        error->all(FLERR, "Fix hardsphere/wall vibrate amplitude A = {} must be > 0", amplitude);
      if (!(omega > 0.0))
        error->all(FLERR, "Fix hardsphere/wall vibrate angular frequency = {} must be > 0", omega);
      iarg += 4;
    } else if (strcmp(arg[iarg], "thermal") == 0) {
      if (iarg + 3 > narg) utils::missing_cmd_args(FLERR, "fix hardsphere/wall thermal T seed", error);
      temperature = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      seed = utils::bnumeric(FLERR, arg[iarg + 2], false, lmp);
      // (at T = 0 the wall stops every grain that hits it dead: grains pile up at rest on it,
      // and one pushed into it by another is stopped again, without end)
      if (!(temperature > 0.0))
        error->all(FLERR, "Fix hardsphere/wall thermal T = {} must be > 0: a wall at T = 0 "
                   "would stop every grain that hits it dead, so that grains pile up at rest on "
                   "it and one pushed into it by another is stopped again, colliding without end "
                   "(a small T absorbs nearly all the energy of the grains that hit it)", temperature);
      if (seed <= 0) error->all(FLERR, "Fix hardsphere/wall thermal seed = {} must be > 0", seed);
      iarg += 3;
    } else if (strcmp(arg[iarg], "slide") == 0) {
      if (iarg + 4 > narg) utils::missing_cmd_args(FLERR, "fix hardsphere/wall slide vx vy vz", error);
      for (int d = 0; d < 3; d++) slide[d] = utils::numeric(FLERR, arg[iarg + 1 + d], false, lmp);
      check_slide(face);
      iarg += 4;
    } else if (strcmp(arg[iarg], "shake") == 0) {
      if (iarg + 4 > narg) utils::missing_cmd_args(FLERR, "fix hardsphere/wall shake dim A omega", error);
      parse_shake(face, arg[iarg + 1], arg[iarg + 2], arg[iarg + 3]);
      iarg += 4;
    } else {
      error->all(FLERR, "Unknown fix hardsphere/wall keyword: {} (allowed: coeffs, thermal, "
                 "vibrate, slide, shake)", arg[iarg]);
    }
  }
  if (amplitude > 0.0 && temperature >= 0.0)
    error->all(FLERR, "Fix hardsphere/wall: a thermal wall cannot vibrate");
  vector_flag = 1;
  size_vector = 10;
  global_freq = 1;
  extvector = 0;
  restart_global = 1;
}

// a wall slides within its plane (in 2d within the x-y plane), at a finite speed
void FixHardsphereWall::check_slide(const std::string &face) const
{
  for (int d = 0; d < 3; d++)
    if (!std::isfinite(slide[d]))
      error->all(FLERR, "Fix hardsphere/wall slide velocity ({}, {}, {}) must be finite", slide[0],
                 slide[1], slide[2]);
  if (slide[dim] != 0.0)
    error->all(FLERR, "Fix hardsphere/wall slide velocity ({}, {}, {}) has a component v{} = {} "
               "along the normal of face {}: a wall slides within its plane (to move it along its "
               "normal, use vibrate)", slide[0], slide[1], slide[2], "xyz"[dim], slide[dim], face);
  if (domain->dimension == 2 && slide[2] != 0.0)
    error->all(FLERR, "Fix hardsphere/wall slide velocity ({}, {}, {}) has vz = {} in a 2d "
               "simulation: a wall slides within the x-y plane", slide[0], slide[1], slide[2], slide[2]);
}

// an oscillation within the wall's plane: along a dimension of the simulation other than the
// wall's normal, with a positive amplitude and angular frequency
void FixHardsphereWall::parse_shake(const std::string &face, const std::string &d, const char *A,
                                    const char *w)
{
  const bool twod = domain->dimension == 2;
  shake_dim = d == "x" ? 0 : d == "y" ? 1 : d == "z" && !twod ? 2 : -1;
  if (shake_dim < 0 || shake_dim == dim)
    error->all(FLERR, "Fix hardsphere/wall shake {} is not available for face {} (allowed: a "
               "dimension within the wall's plane, {}{}; to move the wall along its normal, use "
               "vibrate)", d, face, dim == 0 ? "y" : "x", twod ? "" : dim == 2 ? " or y" : " or z");
  shake_A = utils::numeric(FLERR, A, false, lmp);
  shake_omega = utils::numeric(FLERR, w, false, lmp);
  if (!(shake_A > 0.0))
    error->all(FLERR, "Fix hardsphere/wall shake amplitude A = {} must be > 0", shake_A);
  if (!(shake_omega > 0.0))
    error->all(FLERR, "Fix hardsphere/wall shake angular frequency = {} must be > 0", shake_omega);
}

int FixHardsphereWall::setmask()
{
  return 0;    // collisions are processed by fix hardsphere/ed
}

void FixHardsphereWall::init()
{
  hardsphere::require_ed(lmp, style, id, "processes the collisions with it");
  auto *pair = dynamic_cast<PairHardsphere *>(force->pair);
  if (!pair) error->all(FLERR, "Fix hardsphere/wall {} needs a hardsphere pair style", id);
  if (!coeffs.empty() && (int) coeffs.size() < pair->ncoeff())
    error->all(FLERR, "Fix hardsphere/wall {} coeffs: {} values given, pair style {} takes {} ({})",
               id, coeffs.size(), force->pair_style, pair->ncoeff(), pair->coeff_names());
  if (!coeffs.empty()) {
    // parsed (and checked, with any warning) once per run
    std::vector<char *> a;
    for (auto &c : coeffs) a.push_back(const_cast<char *>(c.c_str()));
    double raw[PairHardsphere::NVALUES];
    own_law = pair->parse_law(std::string("Fix hardsphere/wall ") + id + " coeffs", (int) a.size(), a.data(), raw);
  }
  const double p = edge ? (side < 0 ? domain->boxlo[dim] : domain->boxhi[dim]) : pos;
  if (p < domain->boxlo[dim] || p > domain->boxhi[dim])
    error->all(FLERR, "Fix hardsphere/wall {} position {} lies outside the box ({} to {})", id, p,
               domain->boxlo[dim], domain->boxhi[dim]);
  // a vibrating wall carries atoms with it: in a fixed boundary (f) the centres of the atoms it
  // touches (at least the smallest radius from it) must stay in the box, or LAMMPS loses them
  if (amplitude > 0.0 && domain->boundary[dim][side < 0 ? 0 : 1] == 1) {
    double amin = granfric::INF;
    for (int i = 0; i < atom->nlocal; i++) amin = std::min(amin, atom->radius[i]);
    MPI_Allreduce(MPI_IN_PLACE, &amin, 1, MPI_DOUBLE, MPI_MIN, world);
    const double reach = side < 0 ? p - amplitude + amin : p + amplitude - amin;
    if (amin < granfric::INF && (reach < domain->boxlo[dim] || reach > domain->boxhi[dim]))
      error->all(FLERR, "Fix hardsphere/wall {} (position {}, amplitude {}) carries the centres of "
                 "atoms of radius {} to {}, outside the box ({} to {} in {}, a fixed boundary), "
                 "where LAMMPS would lose them. Move the wall inward, enlarge the box, or use "
                 "boundary m", id, p, amplitude, amin, reach, domain->boxlo[dim], domain->boxhi[dim],
                 "xyz"[dim]);
  }
}

// the wall's geometry and motion (no collision law)
granfric::EDWall FixHardsphereWall::geometry() const
{
  granfric::EDWall w;
  w.dim = dim;
  w.side = side;
  w.pos = edge ? (side < 0 ? domain->boxlo[dim] : domain->boxhi[dim]) : pos;
  // a thermal wall draws velocities at T (energy units) from the Maxwellian of m v^2 / 2
  if (temperature >= 0.0) w.T = temperature * force->boltz / force->mvv2e;
  w.seed = (uint64_t) seed;
  w.A = amplitude;
  w.omega = omega;
  w.sine = sine;
  w.slide = granfric::Vec3(slide[0], slide[1], slide[2]);
  w.shake_dim = shake_dim;
  w.shake_A = shake_A;
  w.shake_omega = shake_omega;
  return w;
}

granfric::EDWall FixHardsphereWall::wall() const
{
  granfric::EDWall w = geometry();
  auto *pair = dynamic_cast<PairHardsphere *>(force->pair);
  const int nt = atom->ntypes;
  w.laws.resize(nt + 1);
  for (int t = 1; t <= nt; t++) w.laws[t] = coeffs.empty() ? pair->wall_law(t) : own_law;
  return w;
}

void FixHardsphereWall::tally(long hits, const double *impulse, double work, double dt)
{
  total_hits += (double) hits;
  total_work += work;
  total_time += dt;
  for (int d = 0; d < 3; d++) {
    step_force[d] = impulse[d] / dt;
    total_impulse[d] += impulse[d];
  }
}

// 1-2: the wall's position and velocity now; 3-5: the force on it averaged over the last step;
// 6-8: averaged since the fix was defined; 9: collisions with it; 10: energy it gave the particles
double FixHardsphereWall::compute_vector(int n)
{
  if (n < 2) {
    const granfric::EDWall w = geometry();
    double p, v, a;
    const double t = hardsphere::time_at_step(update, update->ntimestep);
    w.motion(t, p, v, a);
    return n == 0 ? p : v;
  }
  const double m2f = 1.0 / force->ftm2v;    // (momentum / time -> force units)
  if (n < 5) return step_force[n - 2] * m2f;
  if (n < 8) return total_time > 0.0 ? total_impulse[n - 5] / total_time * m2f : 0.0;
  return n == 8 ? total_hits : total_work * force->mvv2e;
}

void FixHardsphereWall::write_restart(FILE *fp)
{
  const double list[6] = {total_hits, total_impulse[0], total_impulse[1], total_impulse[2],
                          total_work, total_time};
  if (comm->me == 0) {
    const int size = sizeof(list);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list, sizeof(double), 6, fp);
  }
}

void FixHardsphereWall::restart(char *buf)
{
  const auto *list = (const double *) buf;
  total_hits = list[0];
  for (int d = 0; d < 3; d++) total_impulse[d] = list[1 + d];
  total_work = list[4];
  total_time = list[5];
}
