// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: fix hardsphere/ed (see fix_hardsphere_ed.h and doc/fix_hardsphere_ed.rst)
------------------------------------------------------------------------- */

#include "fix_hardsphere_ed.h"

#include "hardsphere_domain_window.h"
#include "hardsphere_gather_window.h"
#include "hardsphere_host.h"

#include "hardsphere_window_parts.h"

#include "atom.h"
#include "citeme.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "input.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "pair_hardsphere.h"
#include "respa.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

using namespace LAMMPS_NS;
using namespace FixConst;
using granfric::INF;

// what LAMMPS lists at the end of a run that used GRANFRIC (see CITATION.cff)
static const char cite_granfric[] =
    "GRANFRIC package: exact event-driven rough hard spheres and discs for LAMMPS\n\n"
    "@Misc{GRANFRIC,\n"
    " author = {{The GRANFRIC developers}},\n"
    " title = {{GRANFRIC}: exact event-driven rough hard spheres and discs for {LAMMPS}},\n"
    " year = 2026,\n"
    " note = {Version 0.1, GPL-2.0-or-later}\n"
    "}\n\n";

/* ---------------------------------------------------------------------- */

FixHardsphereED::FixHardsphereED(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), tc(0.0), maxevents(1000000), tlast(nullptr), pair(nullptr), cum_time(0.0),
    gamma_bins(0), gwin(nullptr), dwin(nullptr), parallel(DOMAIN), reach(1.2), widen(1.0)
{
  if (lmp->citeme) lmp->citeme->add(cite_granfric);
  gwin = new HardsphereGatherWindow(*this);
  dwin = new HardsphereDomainWindow(*this);
  gravity[0] = gravity[1] = gravity[2] = 0.0;
  int iarg = 3;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "gravity") == 0) {
      if (iarg + 4 > narg) utils::missing_cmd_args(FLERR, "fix hardsphere/ed gravity", error);
      for (int d = 0; d < 3; d++) gravity[d] = utils::numeric(FLERR, arg[iarg + 1 + d], false, lmp);
      iarg += 4;
    } else if (strcmp(arg[iarg], "tc") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix hardsphere/ed tc", error);
      tc = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (tc < 0.0)
        error->all(FLERR, "Fix hardsphere/ed tc = {} must be >= 0 (0: TC model off)", tc);
      iarg += 2;
    } else if (strcmp(arg[iarg], "maxevents") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix hardsphere/ed maxevents", error);
      maxevents = utils::bnumeric(FLERR, arg[iarg + 1], false, lmp);
      if (maxevents < 1)
        error->all(FLERR, "Fix hardsphere/ed maxevents = {} must be >= 1", maxevents);
      iarg += 2;
    } else if (strcmp(arg[iarg], "parallel") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix hardsphere/ed parallel", error);
      parallel = choice("parallel", arg[iarg + 1], {"domain", "gather"}) == 0 ? DOMAIN : GATHER;
      iarg += 2;
    } else if (strcmp(arg[iarg], "reach") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix hardsphere/ed reach", error);
      reach = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(reach >= 1.0))
        error->all(FLERR, "Fix hardsphere/ed reach = {} must be >= 1 (the ghost shell is "
                   "reach * v_max * dt wide, plus the contact distance)", reach);
      iarg += 2;
    } else if (strcmp(arg[iarg], "check") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix hardsphere/ed check", error);
      check_windows = choice("check", arg[iarg + 1], {"yes", "no"}) == 0;
      iarg += 2;
    } else if (strcmp(arg[iarg], "overlap") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix hardsphere/ed overlap", error);
      allow_overlap = choice("overlap", arg[iarg + 1], {"error", "allow"}) == 1;
      iarg += 2;
    } else {
      error->all(FLERR, "Unknown fix hardsphere/ed keyword: {} (allowed: gravity, tc, maxevents, "
                 "parallel, reach, check, overlap)", arg[iarg]);
    }
  }
  if (domain->dimension == 2 && gravity[2] != 0.0)
    error->all(FLERR, "Fix hardsphere/ed gravity must have gz = 0 in a 2d simulation");

  time_integrate = 1;
  // the collision virial of each step goes into LAMMPS's pressure (fix_modify virial no: not)
  GRANFRIC_FIX_VIRIAL;
  vector_flag = 1;
  size_vector = NVECTOR;
  global_freq = 1;
  extvector = 0;
  restart_global = 1;
  restart_peratom = 1;
  for (double &t : totals) t = 0.0;

  // per-atom arrays (LAMMPS takes callbacks only from a fix's constructor): the last collision
  // times, kept only for the TC model, and the tallies, allocated when first asked for
  atom->add_callback(host::GROW);
  if (tc > 0.0) atom->add_callback(host::RESTART);
  // (the stored states, on several ranks: for domain windows, and for undo_rounding in both
  // modes)
  if (comm->nprocs > 1) memory->create(xstate, 1, XS_SIZE, "hardsphere/ed:xstate");
  FixHardsphereED::grow_arrays(atom->nmax);
  GRANFRIC_MAXEXCHANGE((tlast ? 1 : 0) + (xstate ? XS_SIZE : 0));
}

// the place of value among the allowed values of keyword, or an error that lists them
int FixHardsphereED::choice(const char *keyword, const std::string &value,
                            const std::vector<std::string> &allowed) const
{
  for (size_t k = 0; k < allowed.size(); k++)
    if (allowed[k] == value) return (int) k;
  error->all(FLERR, "Fix hardsphere/ed {} {} is not available (allowed: {})", keyword, value,
             utils::join_words(allowed, ", "));
  return -1;
}

FixHardsphereED::~FixHardsphereED()
{
  if (GRANFRIC_COPYMODE) return;
  delete gwin;
  delete dwin;
  if (tlast) atom->delete_callback(id, host::RESTART);
  atom->delete_callback(id, host::GROW);
  memory->destroy(tlast);
  memory->destroy(atally);
  memory->destroy(xstate);
}

FixHardsphereED *FixHardsphereED::lookup(LAMMPS *lmp, const std::string &id, const char *who)
{
  auto *f = host::fix_by_id(lmp->modify, id);
  if (!f) host::errors(lmp)->all(FLERR, "{}: fix ID {} does not exist", who, id);
  auto *ed = dynamic_cast<FixHardsphereED *>(f);
  if (!ed) host::errors(lmp)->all(FLERR, "{}: fix {} is of style {}, not hardsphere/ed", who, id, f->style);
  return ed;
}

int FixHardsphereED::setmask()
{
  return INITIAL_INTEGRATE | INITIAL_INTEGRATE_RESPA | POST_FORCE | POST_FORCE_RESPA | PRE_NEIGHBOR;
}

void FixHardsphereED::request_atom_tallies()
{
  if (atally) return;
  memory->create(atally, atom->nmax, NTALLY, "hardsphere/ed:atally");
  atally_n = 0;
  grow_arrays(atom->nmax);
  GRANFRIC_MAXEXCHANGE((tlast ? 1 : 0) + (xstate ? XS_SIZE : 0) + NTALLY);
}

void FixHardsphereED::post_force_respa(int vflag, int ilevel, int)
{
  if (ilevel == nlevels_respa - 1) post_force(vflag);    // (the outermost level, as the window)
}

// After LAMMPS moved and sorted the atoms (their tallies went with them): the step's virial,
// global and per atom (the tallies hold each atom's share)
void FixHardsphereED::post_force(int vflag)
{
  GRANFRIC_V_INIT(vflag);
  for (int k = 0; k < 6; k++) virial[k] = wstep[k];
  if (!vflag_atom || !atally) return;
  const double scale = force->mvv2e / update->dt;
  for (int i = 0; i < atom->nlocal; i++)
    for (int k = 0; k < 6; k++) vatom[i][k] = atally[i][T_VIRIAL + k] * scale;
}

void FixHardsphereED::initial_integrate_respa(int vflag, int ilevel, int)
{
  if (ilevel == nlevels_respa - 1) initial_integrate(vflag);
}

/* ---------------------------------------------------------------------- */

void FixHardsphereED::init()
{
  pair = dynamic_cast<PairHardsphere *>(force->pair);
  if (!pair)
    error->all(FLERR,
               "Fix hardsphere/ed requires pair style hardsphere/rough, hardsphere/walton or "
               "hardsphere/jz (found {})",
               force->pair_style ? force->pair_style : "none");
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag)
    error->all(FLERR, "Fix hardsphere/ed requires atom_style sphere (radius, mass, omega)");
  if (igroup != 0)
    error->all(FLERR, "Fix hardsphere/ed must be applied to group all (it moves every atom)");
  if (domain->triclinic) error->all(FLERR, "Fix hardsphere/ed does not support triclinic boxes");
  // (a window of length dt <= 0 would move the atoms backward or not at all)
  if (!(update->dt > 0.0))
    error->all(FLERR, "Fix hardsphere/ed requires a positive timestep (timestep = {}): the step "
               "is the window in which the atoms move forward", update->dt);
  // a shrink-wrapped non-periodic boundary may move (the fix's edge cells extend outward), and
  // fix balance may move the subdomains, but no fix may change the box (deform, barostats)
  balancing = false;
  for (const auto &f : host::fixes(modify)) {
    balancing = balancing || host::moves_subdomains(f);
    if (host::changes_box(f))
      error->all(FLERR, "Fix hardsphere/ed does not support a box whose size or shape changes "
                 "during the run (fix {} {}): the hard-sphere windows need a fixed box (fix "
                 "balance, which moves only the subdomain boundaries, is supported)", f->id, f->style);
  }
  // with run_style respa the window is the outermost step (collisions need no forces)
  nlevels_respa = 0;
  if (utils::strmatch(update->integrate_style, "^respa"))
    nlevels_respa = (dynamic_cast<Respa *>(update->integrate))->nlevels;
  kicks.clear();
  walls.clear();
  for (const auto &f : host::fixes(modify)) {
    if (f == this) continue;
    if (auto *k = dynamic_cast<HardsphereDriving *>(f)) kicks.push_back(k);
    if (auto *w = dynamic_cast<HardsphereWallPart *>(f)) walls.push_back(w);
    if (utils::strmatch(f->style, "^gravity"))
      error->all(FLERR,
                 "Fix {} (gravity) acts together with fix hardsphere/ed {}: use the gravity "
                 "keyword of fix hardsphere/ed instead",
                 f->id, id);
    // (soft granular walls, LAMMPS's or LIGGGHTS's, and LIGGGHTS's meshes they use)
    if (utils::strmatch(f->style, "^wall/gran") || utils::strmatch(f->style, "^mesh/surface"))
      error->all(FLERR,
                 "Fix {} ({}) is a soft granular wall, which the hard particles of fix "
                 "hardsphere/ed {} do not feel: use fix hardsphere/wall",
                 f->id, f->style, id);
    if (f->time_integrate)
      error->all(FLERR,
                 "Fix {} ({}) integrates the same atoms as fix hardsphere/ed {}: hard particles "
                 "must be moved by fix hardsphere/ed alone",
                 f->id, f->style, id);
  }
  for (int d = 0; d < domain->dimension; d++) {
    if (domain->periodicity[d]) continue;
    bool wall = false;
    for (auto *w : walls)
      if (w->dimension() == d) wall = true;
    if (!wall)
      error->all(FLERR, "Fix hardsphere/ed: the non-periodic dimension {} needs a fix "
                 "hardsphere/wall (at least on one side)", "xyz"[d]);
  }
  check_walls_cross();
  refuse_rerun();
  warn_ignored_inputs();
  note_positions();
  if (comm->nprocs > 1 && parallel == GATHER && comm->me == 0)
    error->warning(FLERR,
                   "Fix hardsphere/ed parallel gather on {} MPI ranks: every rank processes the "
                   "whole window (exact, no parallel speedup)", comm->nprocs);
}

void FixHardsphereED::setup(int vflag)
{
  // no collision before the first step: the virial LAMMPS reads at the run's start is zero
  for (double &w : wstep) w = 0.0;
  post_force(vflag);
  const double *radius = atom->radius;
  const tagint point = first_atom([&](int i) { return !(radius[i] > 0.0); });
  if (point != NOATOM)
    error->all(FLERR, "Fix hardsphere/ed requires every atom to have a radius > 0 (atom {} has "
               "diameter {})", point, 2.0 * atom_value(point, [&](int i) { return radius[i]; }));
  check_box_fits_atoms();
  check_plane();
  check_atoms_between_walls();
  check_scales();
  // A new run may bring new coefficients, a new box, new walls or new atoms. The epoch (and the
  // event queue) of the last run goes on only if the core's configuration is the same in every
  // respect; the atoms themselves are compared at the first window (as between steps).
  // Vibrating walls depend on the absolute time, which reset_timestep can change: always a new
  // epoch then.
  const granfric::EDOptions o = core_options();
  const std::vector<granfric::LawParams> laws = law_table();
  bool vibrating = false;
  for (const auto &w : o.walls) vibrating = vibrating || w.vibrating();
  const bool same = !vibrating && run_ntypes == atom->ntypes &&
      granfric::EventDriven::same_configuration(o, atom->ntypes, laws, run_options, run_ntypes, run_laws);
  if (!same) {
    configure_core(o);
    invalidate_windows();
  }
  run_options = o;
  run_laws = laws;
  run_ntypes = atom->ntypes;
  check_overlaps = true;    // (a kept queue continues an exact trajectory: nothing to check)
  added_at = -1;
}

// the lowest ID of the atoms (over all ranks) for which bad(local index) holds, or NOATOM
tagint FixHardsphereED::first_atom(const std::function<bool(int)> &bad) const
{
  tagint who = NOATOM;
  for (int i = 0; i < atom->nlocal; i++)
    if (bad(i)) who = std::min(who, atom->tag[i]);
  MPI_Allreduce(MPI_IN_PLACE, &who, 1, MPI_LMP_TAGINT, MPI_MIN, world);
  return who;
}

// value(local index) of atom who, from the rank that owns it (collective)
double FixHardsphereED::atom_value(tagint who, const std::function<double(int)> &value) const
{
  double v = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->tag[i] == who) v = value(i);
  MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_SUM, world);
  return v;
}

// Absurd speeds, accelerations, steps and wall temperatures end at the start of the run, not
// after the event cap's maxevents x atoms cell crossings (minutes): the atoms' paths in one
// step (speed, gravity, the speed a vibrating or thermal wall gives) summed over the atoms, in
// the largest diameters (the narrowest cells), against that cap; and thermal walls under
// gravity (check_thermal_walls).
void FixHardsphereED::check_scales() const
{
  // (over all atoms: the summed speed, the largest mass, radius and inverse mass)
  double sum = 0.0, mx[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < atom->nlocal; i++) {
    const double *v = atom->v[i];
    sum += std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    mx[0] = std::max(mx[0], atom->rmass[i]);
    mx[1] = std::max(mx[1], atom->radius[i]);
    mx[2] = std::max(mx[2], 1.0 / atom->rmass[i]);
  }
  MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_DOUBLE, MPI_SUM, world);
  MPI_Allreduce(MPI_IN_PLACE, mx, 3, MPI_DOUBLE, MPI_MAX, world);
  const double n = (double) atom->natoms;
  if (n == 0.0) return;
  check_thermal_walls(mx[0], mx[1]);
  const double dt = update->dt, g = std::hypot(gravity[0], gravity[1], gravity[2]);
  double wmax = 0.0, tmax = 0.0;    // the fastest wall's speed, the hottest wall's temperature
  for (auto *w : walls) {
    const granfric::EDWall e = w->geometry();
    wmax = std::max(wmax, e.speed_bound());
    tmax = std::max(tmax, e.T);
  }
  const double vwall = std::max(2.0 * wmax, tmax > 0.0 ? 5.0 * std::sqrt(tmax * mx[2]) : 0.0);
  const double mean = (sum / n + vwall) * dt + 0.5 * g * dt * dt;    // per atom and step
  if (!(mean / (2.0 * mx[1]) <= (double) maxevents))
    error->all(FLERR, "Fix hardsphere/ed: the atoms would travel {:.3g} diameters per step on "
               "average (mean speed {:.3g}, {:.3g} from walls that vibrate or are thermal, gravity "
               "{:.3g}, timestep {:.3g}), "
               "more cells than the event cap maxevents = {} allows each atom in a step: lower "
               "the speeds, the walls' speed or temperature, gravity or the timestep", mean / (2.0 * mx[1]),
               sum / n, vwall, g, dt, maxevents);
}

// A thermal wall under gravity toward it holds the grains it re-emits at rest (T = 0) or
// nearly (they hop less than a millionth of a diameter high, or maxevents times and more per
// step): refused (mmax, amax: the heaviest mass, the largest radius)
void FixHardsphereED::check_thermal_walls(double mmax, double amax) const
{
  const double dt = update->dt;
  for (auto *w : walls) {
    const granfric::EDWall e = w->geometry();
    const double toward = e.side < 0 ? -gravity[e.dim] : gravity[e.dim];
    if (e.T < 0.0 || !(toward > 0.0)) continue;
    // a grain re-emitted at T hops for about 2 sqrt(T/m)/g, kT/(m g) high
    const double hop = 2.0 * std::sqrt(e.T / mmax) / toward, height = e.T / (mmax * toward);
    if (hop * maxevents > dt && height > 1e-6 * 2.0 * amax) continue;
    const std::string why = e.T == 0.0
        ? std::string("the grains it re-emits stay at rest on it")
        : host::format("a grain of mass {} it re-emits hops {:.3g} diameters high, for {:.3g} (about {:.3g} "
                       "times per step of {}): it stays practically at rest on the wall", mmax,
                       height / (2.0 * amax), hop, dt / hop, dt);
    error->all(FLERR, "Fix hardsphere/wall {} (thermal at T = {}) under gravity {} toward it: {}, "
               "which event-driven motion can only follow by colliding without end. Give it a "
               "temperature at which the grains hop at least a millionth of a diameter high and "
               "for longer than a step / maxevents = {:.3g}", w->wall_id(),
               e.T * force->mvv2e / force->boltz, toward, why, dt / maxevents);
  }
}

// rerun computes from snapshots, between which hard particles collide: the collisions (their
// counts, the energy they dissipate, the collisional part of the pressure) cannot be had from
// them, and the run would report none without a word
void FixHardsphereED::refuse_rerun() const
{
  const char *command = host::running_command(input);
  if (command && strcmp(command, "rerun") == 0)
    error->all(FLERR, "Fix hardsphere/ed {} cannot be used with rerun: hard-sphere collisions "
               "happen between the snapshots, so neither their counts nor the collisional part "
               "of the pressure can be computed from them (unfix {} to evaluate computes of "
               "single configurations, such as compute hardsphere/temp; average the pressure in "
               "the run itself)", id, id);
}

// What acts on the atoms through forces has no effect on hard particles, which move only by
// free flight, gravity, collisions, walls and kicks: a fix that adds or changes forces (fix
// viscous, langevin, addforce, spring/self, freeze, setforce, ...), or pair exclusions (every
// pair of hard particles collides). Warned, not refused: such a fix may be meant for other
// output, and it changes nothing here.
void FixHardsphereED::warn_ignored_inputs() const
{
  if (comm->me != 0) return;
  for (int k = 0; k < modify->nfix; k++) {
    const Fix *f = modify->fix[k];
    if (f == this || utils::strmatch(f->style, "^hardsphere/") || utils::strmatch(f->style, "^enforce2d")) continue;
    if (modify->fmask[k] & POST_FORCE)
      error->warning(FLERR, "Fix {} ({}) acts through forces, which the hard particles of fix "
                     "hardsphere/ed {} do not feel: it has no effect on their motion (they move "
                     "by free flight, the gravity keyword, collisions, fix hardsphere/wall and fix "
                     "hardsphere/kick)", f->id, f->style, id);
  }
  if (host::pairs_excluded(neighbor))
    error->warning(FLERR, "neigh_modify exclude has no effect on fix hardsphere/ed {}: every pair "
                   "of hard particles collides", id);
}

// In 2d the core moves discs in the plane z = 0 and spins them about z: an atom off that plane
// (set ... z, fix deposit or pour with a region of some thickness in z), moving in z or
// spinning about x or y would collide as a sphere in 3d. Checked at every run's start and when
// the number of atoms changed (atoms added during the run).
void FixHardsphereED::check_plane()
{
  plane_checked = atom->natoms;
  if (domain->dimension != 2) return;
  double **x = atom->x, **v = atom->v, **omega = atom->omega;
  const tagint who = first_atom([&](int i) {
    return x[i][2] != 0.0 || v[i][2] != 0.0 || omega[i][0] != 0.0 || omega[i][1] != 0.0;
  });
  if (who == NOATOM) return;
  double at[4];    // (z, vz, omega_x, omega_y of atom who)
  for (int d = 0; d < 4; d++)
    at[d] = atom_value(who, [&](int i) { return d == 0 ? x[i][2] : d == 1 ? v[i][2] : omega[i][d - 2]; });
  error->all(FLERR, "Fix hardsphere/ed: atom {} is not a disc in the plane of the 2d simulation "
             "(z = {}, vz = {}, omega = ({}, {}, .)): every atom must lie at z = 0 with vz = 0 "
             "and spin about z only (the set and velocity commands set them; fix deposit and "
             "fix pour need a region with z from 0 to 0 in 2d)", who, at[0], at[1], at[2], at[3]);
}

// a lower wall at or above an upper wall of the same dimension leaves no room between them
void FixHardsphereED::check_walls_cross() const
{
  for (auto *lo : walls)
    for (auto *hi : walls) {
      const granfric::EDWall a = lo->geometry(), b = hi->geometry();
      if (a.dim != b.dim || a.side > 0 || b.side < 0 || a.pos + a.A < b.pos) continue;
      error->all(FLERR, "Fix hardsphere/wall {} ({} at {}{}) is not below fix hardsphere/wall {} "
                 "({} at {}): the lower wall must lie below the upper one", lo->wall_id(), lo->face(),
                 a.pos, a.A > 0.0 ? host::format(" + amplitude {}", a.A) : "", hi->wall_id(), hi->face(),
                 b.pos);
    }
}

// every box length at least the largest diameter (the cells of the core are that wide); the
// error names an atom of that diameter
void FixHardsphereED::check_box_fits_atoms() const
{
  double amax = 0.0;
  for (int i = 0; i < atom->nlocal; i++) amax = std::max(amax, atom->radius[i]);
  MPI_Allreduce(MPI_IN_PLACE, &amax, 1, MPI_DOUBLE, MPI_MAX, world);
  for (int d = 0; d < domain->dimension; d++) {
    if (domain->prd[d] >= 2.0 * amax * (1.0 + 1e-10)) continue;
    const tagint who = first_atom([&](int i) { return atom->radius[i] == amax; });
    error->all(FLERR, "Fix hardsphere/ed: atom {} has diameter {}, longer than the box in {} ({} "
               "from {} to {}): every box length must be at least the largest diameter", who,
               2.0 * amax, "xyz"[d], domain->prd[d], domain->boxlo[d], domain->boxhi[d]);
  }
}

// no atom reaches behind a wall at the start of the run (its center at least its radius from
// the plane, on the inner side, up to rounding); the error names the atom with the lowest ID
void FixHardsphereED::check_atoms_between_walls() const
{
  const double t = window_start_time() + update->dt;    // (the time the next window starts)
  for (auto *w : walls) {
    const granfric::EDWall g = w->geometry();
    double p, vw, aw;
    g.motion(t, p, vw, aw);
    // (a margin for rounding: 1e-9 of the diameter, 1e-12 of the wall's coordinate)
    const tagint who = first_atom([&](int i) {
      const double a = atom->radius[i], gap = g.side * (p - atom->x[i][g.dim]);
      return gap < a - 2e-9 * a - 1e-12 * std::fabs(p);
    });
    if (who == NOATOM) continue;
    double at[4];    // (position and radius of atom who)
    for (int d = 0; d < 4; d++)
      at[d] = atom_value(who, [&](int i) { return d < 3 ? atom->x[i][d] : atom->radius[i]; });
    error->all(FLERR, "Fix hardsphere/ed: atom {} at ({}, {}, {}) with radius {} reaches behind "
               "fix hardsphere/wall {} ({} at {}): every atom must start between the walls, "
               "at least its radius away from each", who, at[0], at[1], at[2], at[3], w->wall_id(),
               w->face(), p);
  }
}

// once per run, after the first window's start: overlapping atoms (usually a mistake in the
// initial configuration) are an error, or a warning with overlap allow; partial windows sum
// over the ranks
void FixHardsphereED::report_overlaps(bool partial)
{
  if (!check_overlaps) return;
  check_overlaps = false;
  long ki, kj;
  double depth;
  double n = (double) ed.overlaps(1e-9, ki, kj, depth);
  struct {
    double depth;
    int rank;
  } in{depth, comm->me}, out = in;
  if (partial) {
    MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPI_DOUBLE, MPI_SUM, world);
    MPI_Allreduce(&in, &out, 1, MPI_DOUBLE_INT, MPI_MAXLOC, world);
    long keys[2] = {ki, kj};
    MPI_Bcast(keys, 2, MPI_LONG, out.rank, world);
    ki = keys[0];
    kj = keys[1];
  }    // (the keys are the atom IDs)
  if (n == 0) return;
  const std::string when = added_at < 0 ? std::string("at the start of the run")
                                        : host::format("after atoms were added at step {}", added_at);
  if (!allow_overlap) {
    invalidate_windows();
    error->all(FLERR,
               "Fix hardsphere/ed: atoms {} and {} overlap by {:.6g} {} ({} overlapping pairs in "
               "all). Remove them with delete_atoms overlap, create atoms with create_atoms ... "
               "overlap (or fix deposit ... near), or let overlapping pairs separate with keyword "
               "overlap allow", ki, kj, out.depth, when, (long) n);
  }
  if (comm->me == 0)
    error->warning(FLERR,
                   "Fix hardsphere/ed: {} pairs of atoms overlap {} (deepest: atoms {} and {} by "
                   "{:.6g}); approaching overlapping pairs collide at once, receding ones separate "
                   "(overlap allow)",
                   (long) n, when, ki, kj, out.depth);
}

void FixHardsphereED::request_gamma_bins(int nbins)
{
  if (gamma_bins && gamma_bins != nbins)
    error->all(FLERR, "Fix hardsphere/ed {}: computes asked for {} and {} impact-angle bins; use "
               "one bin count per fix", id, gamma_bins, nbins);
  gamma_bins = nbins;
}

granfric::EDOptions FixHardsphereED::core_options() const
{
  granfric::EDOptions o;
  o.dim = domain->dimension;
  for (int d = 0; d < 3; d++) {
    o.lo[d] = domain->boxlo[d];
    o.hi[d] = domain->boxhi[d];
    o.periodic[d] = domain->periodicity[d];
  }
  o.gravity = granfric::Vec3(gravity[0], gravity[1], gravity[2]);
  o.tc = tc;
  o.max_collisions = maxevents;
  o.gamma_bins = gamma_bins;
  for (auto *w : walls) o.walls.push_back(w->wall());
  o.shape.assign(atom->ntypes + 1, pair->shape_factor());
  return o;
}

std::vector<granfric::LawParams> FixHardsphereED::law_table() const
{
  const int nt = atom->ntypes;
  std::vector<granfric::LawParams> laws((nt + 1) * (nt + 1));
  for (int i = 1; i <= nt; i++)
    for (int j = 1; j <= nt; j++) laws[i * (nt + 1) + j] = pair->law(i, j);
  return laws;
}

void FixHardsphereED::configure_core(const granfric::EDOptions &o, bool collective)
{
  try {
    ed.configure(o, atom->ntypes, law_table());
  } catch (std::exception &e) {
    core_failed(e, collective);
  }
}

void FixHardsphereED::start_core(bool collective)
{
  try {
    ed.start();
  } catch (std::exception &e) {
    core_failed(e, collective);
  }
}

void FixHardsphereED::invalidate_windows()
{
  gwin->invalidate();
  dwin->invalidate();
  epoch_due = true;
}

bool FixHardsphereED::epoch_starts() const
{
  const bigint first = update->ntimestep - 1;    // (this window's first step)
  return epoch_due || update->dt != epoch_dt || first < epoch_step || first - epoch_step >= EPOCH_WINDOWS;
}

void FixHardsphereED::begin_epoch(double t0)
{
  epoch_step = update->ntimestep - 1;
  epoch_clock = t0;
  epoch_dt = update->dt;
  epoch_due = false;
  written_at = NAN;
}

void FixHardsphereED::core_failed(const std::exception &e, bool collective)
{
  invalidate_windows();
  if (collective) error->all(FLERR, "Fix hardsphere/ed: {}", e.what());
  error->one(FLERR, "Fix hardsphere/ed: {}", e.what());
}

// every rank's send buffer, concatenated in rank order into recv (counts and displs say where
// each rank's part lies); the doubles received are counted; returns the total
int FixHardsphereED::allgather(const std::vector<double> &send, std::vector<double> &recv)
{
  const int nprocs = comm->nprocs;
  counts.resize(nprocs);
  displs.resize(nprocs);
  int mysize = (int) send.size(), total = 0;
  MPI_Allgather(&mysize, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
  for (int p = 0; p < nprocs; p++) {
    displs[p] = total;
    total += counts[p];
  }
  recv.resize(total);
  MPI_Allgatherv(send.data(), mysize, MPI_DOUBLE, recv.data(), counts.data(), displs.data(),
                 MPI_DOUBLE, world);
  totals[STEP_COMM] += (double) total * (nprocs - 1);
  return total;
}

// owned atom i as a window takes it: its stored state in the epoch (exact), or LAMMPS's atom
// at the start of an epoch
AtomRecord FixHardsphereED::atom_record(int i, bool exact) const
{
  AtomRecord r;
  r.tag = (double) atom->tag[i];
  const double *xs = exact ? xstate[i] : nullptr;
  for (int d = 0; d < 3; d++) {
    r.xl[d] = atom->x[i][d];
    r.x[d] = xs ? xs[XS_X + d] : atom->x[i][d];
    r.v[d] = xs ? xs[XS_V + d] : atom->v[i][d];
    r.w[d] = atom->omega[i][d];
    r.off[d] = xs ? xs[XS_OFF + d] : 0.0;
    r.poff[d] = xs ? xs[XS_POFF + d] : 0.0;
  }
  r.t = xs ? xs[XS_T] : 0.0;
  r.radius = atom->radius[i];
  r.mass = atom->rmass[i];
  r.type = (double) atom->type[i];
  r.tlast = xs ? xs[XS_TLAST] : tlast_since(i, epoch_clock);
  r.mask = (double) atom->mask[i];
  r.partner = xs ? xs[XS_PARTNER] : 0.0;
  return r;
}

void FixHardsphereED::store_state(int i, int e, const double *off, double partner,
                                  const double *wx, const double *wv)
{
  const auto p = std::as_const(ed).particle(e);
  double *xs = xstate[i];
  p.x.to(xs + XS_X);
  p.v.to(xs + XS_V);
  xs[XS_T] = p.t;
  for (int d = 0; d < 3; d++) xs[XS_OFF + d] = off[d];
  xs[XS_PARTNER] = partner;
  const int *po = ed.last_offset(e);
  for (int d = 0; d < 3; d++) xs[XS_POFF + d] = partner > 0.0 ? po[d] : 0.0;
  xs[XS_TLAST] = p.t_last;
  if (wx) {
    for (int d = 0; d < 3; d++) {    // (element by element: copy_n of three called memcpy)
      xs[XS_WX + d] = wx[d];
      xs[XS_WV + d] = wv[d];
    }
  } else {
    xs[XS_WX] = NAN;    // (states_hold compares this first)
  }
}

bool FixHardsphereED::states_hold(int n, double T0, const hardsphere::FarWrap &wrap)
{
  // (an atom that holds the x and v written at T0 passes at once: the full test would compute
  // them again from its stored state, with its periods as they are. The rows lie one after
  // another, as LAMMPS allocates per-atom arrays)
  const bool written = T0 == written_at;
  const double *xa = n > 0 ? atom->x[0] : nullptr, *va = n > 0 ? atom->v[0] : nullptr;
  const double *xs = n > 0 ? xstate[0] : nullptr;
  for (int i = 0; i < n; i++, xa += 3, va += 3, xs += XS_SIZE) {
    if (written && xa[0] == xs[XS_WX] && xa[1] == xs[XS_WX + 1] && xa[2] == xs[XS_WX + 2] &&
        va[0] == xs[XS_WV] && va[1] == xs[XS_WV + 1] && va[2] == xs[XS_WV + 2])
      continue;
    if (!state_holds(i, T0, wrap)) return false;
  }
  return true;
}

bool FixHardsphereED::state_holds(int i, double T0, const hardsphere::FarWrap &wrap)
{
  double *xs = xstate[i];
  if (std::isnan(xs[XS_T])) return false;
  const double *xa = atom->x[i], *va = atom->v[i];
  const granfric::Vec3 x(xs[XS_X], xs[XS_X + 1], xs[XS_X + 2]), v(xs[XS_V], xs[XS_V + 1], xs[XS_V + 2]);
  const granfric::Vec3 g(gravity[0], gravity[1], gravity[2]);
  const double dt = T0 - xs[XS_T];
  const granfric::Vec3 xw = granfric::EventDriven::flight_x(x, v, dt, g, granfric::norm2(g) != 0.0);
  const granfric::Vec3 vw = granfric::EventDriven::flight_v(v, dt, g);
  for (int d = 0; d < 3; d++) {
    if (va[d] != vw[d]) return false;
    int off = (int) xs[XS_OFF + d];
    if (!wrap.holds(d, xa[d], wrap.written(d, xw[d], off), off)) return false;
    xs[XS_OFF + d] = off;
  }
  return true;
}

void FixHardsphereED::note_positions()
{
  if (!xstate || written_at == epoch_time(update->ntimestep)) return;
  const hardsphere::FarWrap wrap(domain);
  for (int i = 0; i < atom->nlocal; i++) {
    double *wx = xstate[i] + XS_WX;
    const double *x = atom->x[i];
    bool same = !std::isnan(wx[0]);
    for (int d = 0; d < 3 && same; d++) {
      int k;
      double c;
      same = wrap.match(d, x[d], wx[d], k, c);
    }
    if (!same)
      for (int d = 0; d < 3; d++) wx[d] = x[d];
  }
  written_at = NAN;
}

void FixHardsphereED::undo_rounding()
{
  if (!xstate) return;
  const hardsphere::FarWrap wrap(domain);
  for (int i = 0; i < atom->nlocal; i++) {
    const double *wx = xstate[i] + XS_WX;
    double *x = atom->x[i];
    if (std::isnan(wx[0])) continue;
    for (int d = 0; d < 3; d++) {
      int k;
      double c;
      if (x[d] != wx[d] && wrap.match(d, x[d], wx[d], k, c)) x[d] = c;
    }
  }
}

// the kicks of every fix hardsphere/kick in [t0, t0 + dt) in time order; the momentum shift of
// each kick is summed over all ranks (collective: every rank calls this for the same window)
std::vector<PlannedKick> FixHardsphereED::plan_kicks(double t0, double dt)
{
  const int dim = domain->dimension;
  std::vector<PlannedKick> all;
  // (epoch times: kicks of this window stay in [T0, T1) whatever the rounding)
  const double T0 = epoch_time(update->ntimestep - 1), T1 = epoch_time(update->ntimestep);
  const double last = std::nextafter(T1, -granfric::INF);
  for (int f = 0; f < (int) kicks.size(); f++) {
    std::vector<double> times;
    std::vector<long> index;
    kicks[f]->kicks_in(t0, t0 + dt, times, index);
    for (size_t m = 0; m < times.size(); m++)
      all.push_back({std::min(std::max(times[m] - epoch_clock, T0), last), f, index[m],
                     kicks[f]->momentum_shift(index[m], dim)});
  }
  std::stable_sort(all.begin(), all.end(),
                   [](const PlannedKick &a, const PlannedKick &b) { return a.t < b.t; });
  return all;
}

// the planned kicks as global events of the core, applied to core particles with IDs tags and
// masks (each rank alone)
void FixHardsphereED::schedule_kicks(const std::vector<PlannedKick> &plan,
                                     const std::vector<tagint> &tags, const std::vector<int> &masks)
{
  const int dim = domain->dimension;
  std::vector<double> times(plan.size());
  for (size_t m = 0; m < plan.size(); m++) times[m] = plan[m].t;
  ed.set_global_events(times, [this, plan, dim, &tags, &masks](int g) {
    kicks[plan[g].fix]->apply(ed, tags, masks, plan[g].k, dim, plan[g].dvcm);
  });
}

// wrapped here: x jumped by whole periods, the image flags count them
void FixHardsphereED::wrap_image(imageint &image, const int *dimg)
{
  imageint xb = (image & IMGMASK) - IMGMAX + dimg[0];
  imageint yb = (image >> IMGBITS & IMGMASK) - IMGMAX + dimg[1];
  imageint zb = (image >> IMG2BITS) - IMGMAX + dimg[2];
  image = ((imageint) (xb + IMGMAX) & IMGMASK) | (((imageint) (yb + IMGMAX) & IMGMASK) << IMGBITS) |
      (((imageint) (zb + IMGMAX) & IMGMASK) << IMG2BITS);
}

double FixHardsphereED::window_start_time() const
{
  return hardsphere::time_at_step(update, update->ntimestep - 1);
}

// After a restart file is written, the next window starts from the atoms exactly as a run that
// reads the file does: positions remapped into the box as read_restart remaps them, a new cell
// grid and new predictions from those positions, the clock anchored at the restart step (see
// write_restart). The kept event queue would continue with other rounding (its particles'
// states are lazy, its predictions older), so a run continued from the file would leave the
// uninterrupted one in the last bits, and chaos would make it another trajectory. This way both
// are the same, bit for bit, at the cost of one rebuild per restart file.
void FixHardsphereED::resync_for_restart()
{
  resync = false;
  for (int i = 0; i < atom->nlocal; i++) domain->remap(atom->x[i], atom->image[i]);
  invalidate_windows();
}

/* ----------------------------------------------------------------------
   one window per step: domain-decomposed (parallel domain on several ranks) unless it has a
   conflict, else gathered
------------------------------------------------------------------------- */

void FixHardsphereED::initial_integrate(int vflag)
{
  GRANFRIC_V_INIT(vflag);    // (vflag_atom: LAMMPS needs per-atom virials at the end of this step)
  if (vflag_atom) request_atom_tallies();
  ed.tally_particles(atally != nullptr);
  const double dt = update->dt;
  const double t0 = window_start_time();
  totals[STEP_CONFLICTS] = totals[STEP_COMM] = totals[STEP_PREDICTED] = totals[STEP_COPIES] = 0.0;
  if (resync) resync_for_restart();
  if (atom->natoms != plane_checked) {
    // atoms added or deleted during the run (fix deposit, fix pour, fix evaporate): the new
    // ones must lie in the plane, and must not overlap others
    check_plane();
    check_overlaps = true;
    added_at = update->ntimestep - 1;    // (this window starts where that step ended)
  }
  if (parallel == DOMAIN && comm->nprocs > 1) {
    // the reach widens after a guard failed (kicks or walls made atoms faster than the bound)
    // and narrows slowly while windows pass; the same on every rank (the shells of the ranks
    // in a conflict widen on their own, see HardsphereDomainWindow)
    const bool done = dwin->run(t0, dt);
    const int rounds = dwin->repair_rounds();
    totals[REPAIR_ROUNDS] += rounds;
    totals[RANKS_REDONE] += (double) dwin->windows_redone();
    if (done) {
      totals[DOMAIN_WINDOWS] += 1.0;
      if (rounds > 0) totals[WINDOWS_REDONE] += 1.0;
      widen = dwin->guard_widened() ? MIN(64.0, 2.0 * widen) : MAX(1.0, widen * 0.99);
      finish_window(dt);
      return;
    }
    totals[WINDOWS_REDONE] += 1.0;    // not repaired: the whole window again, gathered
    widen = MIN(64.0, 2.0 * widen);
    gwin->run(t0, dt, true);
    finish_window(dt);
    return;
  }
  gwin->run(t0, dt, false);
  finish_window(dt);
}

// owned atom i is core particle s of the window that began at t0: its tallies of the step
void FixHardsphereED::store_tally(int i, int s)
{
  const auto &p = ed.particle_tally(s);
  double *a = atally[i];
  for (int k = 0; k < 6; k++) a[T_VIRIAL + k] = p.virial[k];
  a[T_COLL] = p.collisions;
  a[T_WALL] = p.wall_collisions;
  a[T_DETR] = p.dE_tr * force->mvv2e;
  a[T_DEROT] = p.dE_rot * force->mvv2e;
  a[T_DEWALL] = p.dE_wall * force->mvv2e;
  if (p.t_last > -INF) a[T_LAST] = epoch_clock + p.t_last;
}

// the window's statistics (identical on every rank) into the running totals; the collision
// counts include wall collisions, as the core's sliding, TC-elastic and energy-creating counts do
void FixHardsphereED::finish_window(double dt)
{
  totals[COMM] += totals[STEP_COMM];
  cum.add(last);
  cum_time += dt;
  const double all = (double) last.collisions + (double) last.wall_collisions;
  totals[STEP_COLLISIONS] = all;
  totals[COLLISIONS] += all;
  totals[DISSIPATED] -= last.dE * force->mvv2e;
  totals[SLIDING] += (double) last.sliding;
  totals[MAX_ONE_PARTICLE] = (double) last.max_collisions_one_particle;
  totals[TC_ELASTIC] += (double) last.tc_elastic;
  totals[ENERGY_CREATING] += (double) last.energy_created;
  totals[INJECTED] += last.injected * force->mvv2e;
  totals[WALL_COLLISIONS] += (double) last.wall_collisions;
  totals[DISSIPATED] -= last.dE_wall * force->mvv2e;
  totals[WALL_ENERGY] += last.dE_wall * force->mvv2e;
  // the step's collision virial, sum of r (x) dP over its collisions divided by its length: the
  // time average of the impulsive forces' virial over the window (last holds the whole system's
  // on every rank; compute pressure sums the ranks' shares, so rank 0 gives it all)
  for (int k = 0; k < 6; k++) wstep[k] = comm->me == 0 ? last.virial[k] * force->mvv2e / dt : 0.0;
  // each wall's share (the core's walls are in the order of the wall fixes)
  for (size_t k = 0; k < walls.size() && k < last.wall_hits.size(); k++)
    walls[k]->tally(last.wall_hits[k], &last.wall_impulse[3 * k], last.wall_work[k], dt);
}

double FixHardsphereED::compute_vector(int n)
{
  return totals[n];
}

/* ---------------------------------------------------------------------- per-atom state */

double FixHardsphereED::memory_usage()
{
  return (tlast ? (double) atom->nmax * sizeof(double) : 0.0) +
      (xstate ? (double) atom->nmax * XS_SIZE * sizeof(double) : 0.0) +
      (atally ? (double) atom->nmax * NTALLY * sizeof(double) : 0.0) + (double) ed.memory_bytes() +
      gwin->memory_usage() + dwin->memory_usage();
}

// per-atom arrays: the last collision times of the TC model (tc > 0) and the tallies (when asked)
void FixHardsphereED::grow_arrays(int nmax)
{
  if (tc > 0.0) {
    memory->grow(tlast, nmax, "hardsphere/ed:tlast");
    for (int i = tlast_n; i < nmax; i++) tlast[i] = -INF;    // (new atoms: no collision yet)
    tlast_n = std::max(tlast_n, nmax);
  }
  if (xstate) {
    memory->grow(xstate, nmax, XS_SIZE, "hardsphere/ed:xstate");
    for (int i = xstate_n; i < nmax; i++) xstate[i][XS_T] = xstate[i][XS_WX] = NAN;    // (none yet)
    xstate_n = std::max(xstate_n, nmax);
  }
  if (atally) {
    memory->grow(atally, nmax, NTALLY, "hardsphere/ed:atally");
    for (int i = atally_n; i < nmax; i++)
      for (int k = 0; k < NTALLY; k++) atally[i][k] = k == T_LAST ? -1.0 : 0.0;
    atally_n = std::max(atally_n, nmax);
  }
}

void FixHardsphereED::copy_arrays(int i, int j, int)
{
  if (tlast) tlast[j] = tlast[i];
  if (xstate) memcpy(xstate[j], xstate[i], XS_SIZE * sizeof(double));
  if (atally) memcpy(atally[j], atally[i], NTALLY * sizeof(double));
}

int FixHardsphereED::pack_exchange(int i, double *buf)
{
  int m = 0;
  if (tlast) buf[m++] = tlast[i];
  if (xstate)
    for (int k = 0; k < XS_SIZE; k++) buf[m++] = xstate[i][k];
  if (atally)
    for (int k = 0; k < NTALLY; k++) buf[m++] = atally[i][k];
  return m;
}

int FixHardsphereED::unpack_exchange(int nlocal, double *buf)
{
  int m = 0;
  if (tlast) tlast[nlocal] = buf[m++];
  if (xstate)
    for (int k = 0; k < XS_SIZE; k++) xstate[nlocal][k] = buf[m++];
  if (atally)
    for (int k = 0; k < NTALLY; k++) atally[nlocal][k] = buf[m++];
  return m;
}

void FixHardsphereED::write_restart(FILE *fp)
{
  // (every rank: see resync_for_restart) A run that reads this file anchors the elapsed time at
  // this step (read_restart sets the step count); this run does the same, so that both compute
  // the window start times, and with them kick and wall times, with the same rounding.
  resync = true;
  update->update_time();
  if (comm->me == 0) {
    // layout: -RESTART_FORMAT, the number of totals, the totals, the shell factor of domain
    // windows (which decides which copies a rank's window holds, and so its conflicts)
    const double head[2] = {-RESTART_FORMAT, (double) NVECTOR};
    int size = (NVECTOR + 3) * sizeof(double);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(head, sizeof(double), 2, fp);
    fwrite(totals, sizeof(double), NVECTOR, fp);
    fwrite(&widen, sizeof(double), 1, fp);
  }
}

void FixHardsphereED::restart(char *buf)
{
  // the totals (files with fewer entries leave the new ones at 0); files of the first format
  // start with the count and end with the totals
  const auto *d = reinterpret_cast<const double *>(buf);
  const bool extras = d[0] == -RESTART_FORMAT;
  if (extras) d++;
  const int n = std::min((int) d[0], (int) NVECTOR);
  memcpy(totals, d + 1, n * sizeof(double));
  if (extras) widen = d[1 + (int) d[0]];
  // (the rebuild count continues too: the step after the file was written starts afresh in
  // the writing run as in this one, see resync_for_restart)
}

int FixHardsphereED::pack_restart(int i, double *buf)
{
  buf[0] = 2;
  buf[1] = tlast[i];
  return 2;
}

void FixHardsphereED::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  m++;
  if (tlast) tlast[nlocal] = extra[nlocal][m];    // (a fix without the TC model drops them)
}

int FixHardsphereED::size_restart(int)
{
  return 2;
}

int FixHardsphereED::maxsize_restart()
{
  return 2;
}
