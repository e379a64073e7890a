// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: fix hardsphere/ed (see fix_hardsphere_ed.h and doc/fix_hardsphere_ed.rst)
------------------------------------------------------------------------- */

#include "fix_hardsphere_ed.h"

#include "hardsphere_domain_window.h"
#include "hardsphere_gather_window.h"
#include "hardsphere_host.h"
#include "hardsphere_run_state.h"

#include "atom.h"
#include "citeme.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "modify.h"
#include "pair_hardsphere.h"
#include "respa.h"
#include "update.h"

#include <algorithm>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

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

FixHardsphereED::FixHardsphereED(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg)
{
  if (lmp->citeme) lmp->citeme->add(cite_granfric);
  HardsphereRunState::Settings set;
  double reach = 1.2;
  bool check_windows = true;
  int iarg = 3;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "gravity") == 0) {
      if (iarg + 4 > narg) utils::missing_cmd_args(FLERR, "fix hardsphere/ed gravity", error);
      for (int d = 0; d < 3; d++) set.gravity[d] = utils::numeric(FLERR, arg[iarg + 1 + d], false, lmp);
      iarg += 4;
    } else if (strcmp(arg[iarg], "tc") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix hardsphere/ed tc", error);
      set.tc = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (set.tc < 0.0)
        error->all(FLERR, "Fix hardsphere/ed tc = {} must be >= 0 (0: TC model off)", set.tc);
      iarg += 2;
    } else if (strcmp(arg[iarg], "maxevents") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix hardsphere/ed maxevents", error);
      set.maxevents = utils::bnumeric(FLERR, arg[iarg + 1], false, lmp);
      if (set.maxevents < 1)
        error->all(FLERR, "Fix hardsphere/ed maxevents = {} must be >= 1", set.maxevents);
      iarg += 2;
    } else if (strcmp(arg[iarg], "maxcross") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix hardsphere/ed maxcross", error);
      set.maxcross = utils::bnumeric(FLERR, arg[iarg + 1], false, lmp);
      if (set.maxcross < 1 || set.maxcross > 2000000000L)
        error->all(FLERR, "Fix hardsphere/ed maxcross = {} must be 1 to 2e9", set.maxcross);
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
      set.allow_overlap = choice("overlap", arg[iarg + 1], {"error", "allow"}) == 1;
      iarg += 2;
    } else {
      error->all(FLERR, "Unknown fix hardsphere/ed keyword: {} (allowed: gravity, tc, maxevents, maxcross, "
                 "parallel, reach, check, overlap)", arg[iarg]);
    }
  }
  if (domain->dimension == 2 && set.gravity[2] != 0.0)
    error->all(FLERR, "Fix hardsphere/ed gravity must have gz = 0 in a 2d simulation");

  time_integrate = 1;
  // the collision virial of each step goes into LAMMPS's pressure (fix_modify virial no: not)
  GRANFRIC_FIX_VIRIAL;
  vector_flag = 1;
  size_vector = NVECTOR;
  global_freq = 1;
  extvector = 0;
  restart_global = 1;
  // per-atom restart data (the last collision times) only with the TC model: LAMMPS announces
  // per-atom data in the file's header for every fix with this flag, but the atoms' records
  // hold them only for fixes with the restart callback (added below), and a file that announced
  // them without holding them would give the next fix with that ID uninitialized values
  restart_peratom = set.tc > 0.0 ? 1 : 0;

  // per-atom arrays (LAMMPS takes callbacks only from a fix's constructor): the last collision
  // times, kept only for the TC model, the stored states on several ranks (for domain windows,
  // and for undo_rounding in both modes), and the tallies, allocated when first asked for
  run = new HardsphereRunState(lmp, comm->nprocs > 1, set.tc);
  run->settings = set;
  gwin = new HardsphereGatherWindow(*run);
  dwin = new HardsphereDomainWindow(*run, reach, check_windows);
  atom->add_callback(host::GROW);
  if (set.tc > 0.0) atom->add_callback(host::RESTART);
  FixHardsphereED::grow_arrays(atom->nmax);
  GRANFRIC_MAXEXCHANGE(run->atoms.per_atom());
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
  if (run && run->atoms.has_tlast()) atom->delete_callback(id, host::RESTART);
  atom->delete_callback(id, host::GROW);
  delete run;
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
  if (run->atoms.has_tallies()) return;
  run->atoms.request_tallies();
  GRANFRIC_MAXEXCHANGE(run->atoms.per_atom());
}

void FixHardsphereED::request_gamma_bins(int nbins)
{
  int &bins = run->settings.gamma_bins;
  if (bins && bins != nbins)
    error->all(FLERR, "Fix hardsphere/ed {}: computes asked for {} and {} impact-angle bins; use "
               "one bin count per fix", id, bins, nbins);
  bins = nbins;
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
  for (int k = 0; k < 6; k++) virial[k] = run->wstep[k];
  if (!vflag_atom || !run->atoms.has_tallies()) return;
  const double scale = force->mvv2e / update->dt;
  for (int i = 0; i < atom->nlocal; i++) {
    const double *t = run->atoms.tally(i);
    for (int k = 0; k < 6; k++) vatom[i][k] = t[Tally::T_VIRIAL + k] * scale;
  }
}

void FixHardsphereED::initial_integrate_respa(int vflag, int ilevel, int)
{
  if (ilevel == nlevels_respa - 1) initial_integrate(vflag);
}

/* ---------------------------------------------------------------------- */

void FixHardsphereED::init()
{
  run->pair = dynamic_cast<PairHardsphere *>(force->pair);
  if (!run->pair)
    error->all(FLERR,
               "Fix hardsphere/ed requires pair style hardsphere/rough, hardsphere/walton or "
               "hardsphere/jz (found {})",
               force->pair_style ? force->pair_style : "none");
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag)
    error->all(FLERR, "Fix hardsphere/ed requires atom_style sphere (radius, mass, omega)");
  if (igroup != 0)
    error->all(FLERR, "Fix hardsphere/ed must be applied to group all (it moves every atom)");
  // (a window of length dt <= 0 would move the atoms backward or not at all)
  if (!(update->dt > 0.0))
    error->all(FLERR, "Fix hardsphere/ed requires a positive timestep (timestep = {}): the step "
               "is the window in which the atoms move forward", update->dt);
  check_box_changes();
  // with run_style respa the window is the outermost step (collisions need no forces)
  nlevels_respa = 0;
  if (utils::strmatch(update->integrate_style, "^respa"))
    nlevels_respa = (dynamic_cast<Respa *>(update->integrate))->nlevels;
  find_window_parts();
  check_walls_cross();
  refuse_rerun();
  warn_ignored_inputs();
  run->atoms.note_positions(run->epoch_time(update->ntimestep));
  if (comm->nprocs > 1 && parallel == DOMAIN && domain->triclinic && comm->me == 0)
    error->warning(FLERR,
                   "Fix hardsphere/ed: a sheared (triclinic) box runs gathered windows on every "
                   "rank (parallel domain does not take sheared images yet): exact, no parallel "
                   "speedup");
  if (comm->nprocs > 1 && parallel == GATHER && comm->me == 0)
    error->warning(FLERR,
                   "Fix hardsphere/ed parallel gather on {} MPI ranks: every rank processes the "
                   "whole window (exact, no parallel speedup)", comm->nprocs);
}

// the fixes that act inside the windows (kicks, walls), found by their interface; fixes
// that would act on the atoms beside this one are refused; every non-periodic dimension needs
// a wall
void FixHardsphereED::find_window_parts()
{
  run->kicks.clear();
  run->walls.clear();
  for (const auto &f : host::fixes(modify)) {
    if (f == this) continue;
    if (auto *k = dynamic_cast<HardsphereDriving *>(f)) run->kicks.push_back(k);
    if (auto *w = dynamic_cast<HardsphereWallPart *>(f)) run->walls.push_back(w);
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
    for (auto *w : run->walls)
      if (w->dimension() == d) wall = true;
    if (!wall)
      error->all(FLERR, "Fix hardsphere/ed: the non-periodic dimension {} needs a fix "
                 "hardsphere/wall (at least on one side)", "xyz"[d]);
  }
}

void FixHardsphereED::setup(int vflag)
{
  // no collision before the first step: the virial LAMMPS reads at the run's start is zero
  for (double &w : run->wstep) w = 0.0;
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
  check_atoms_at_rest_on_walls();
  warn_settling_bed();
  warned_fast = warned_piling = false;
  run->new_run();
}

void FixHardsphereED::undo_rounding()
{
  // (after a restart file was written the next window starts from the atoms as the file holds
  // them, as a run that reads it does: see resync_for_restart)
  if (resync) return;
  if (run->atoms.stored() || (domain->triclinic && run->atoms.keeps_written()))
    run->atoms.undo_rounding(domain->triclinic, run->pbc_xy, run->view_xy, run->view_u);
  else
    gwin->undo_rounding();
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
  run->drop_core();
}

/* ----------------------------------------------------------------------
   one window per step: domain-decomposed (parallel domain on several ranks) unless it has a
   conflict, else gathered
------------------------------------------------------------------------- */

void FixHardsphereED::initial_integrate(int vflag)
{
  GRANFRIC_V_INIT(vflag);    // (vflag_atom: LAMMPS needs per-atom virials at the end of this step)
  if (vflag_atom) request_atom_tallies();
  run->ed.tally_particles(run->atoms.has_tallies());
  const double dt = update->dt;
  const double t0 = window_start_time();
  double *totals = run->totals;
  totals[HardsphereRunState::STEP_CONFLICTS] = totals[HardsphereRunState::STEP_COMM] = 0.0;
  totals[HardsphereRunState::STEP_PREDICTED] = totals[HardsphereRunState::STEP_COPIES] = 0.0;
  if (resync) resync_for_restart();
  if (atom->natoms != plane_checked) {
    // atoms added or deleted during the run (fix deposit, fix pour, fix evaporate): the new
    // ones must lie in the plane, and must not overlap others
    check_plane();
    run->check_overlaps = true;
    run->added_at = update->ntimestep - 1;    // (this window starts where that step ended)
  }
  if (parallel == DOMAIN && comm->nprocs > 1 && !domain->triclinic) {
    const bool done = dwin->run(t0, dt);
    totals[HardsphereRunState::REPAIR_ROUNDS] += dwin->repair_rounds();
    totals[HardsphereRunState::RANKS_REDONE] += (double) dwin->windows_redone();
    if (done) {
      totals[HardsphereRunState::DOMAIN_WINDOWS] += 1.0;
      if (dwin->repair_rounds() > 0) totals[HardsphereRunState::WINDOWS_REDONE] += 1.0;
    } else {
      totals[HardsphereRunState::WINDOWS_REDONE] += 1.0;    // not repaired: redone gathered
      gwin->run(t0, dt, true);
    }
  } else {
    gwin->run(t0, dt, false);
  }
  run->finish_window(dt);
  warn_fast_atoms();
  warn_piling_collisions();
}

double FixHardsphereED::compute_vector(int n)
{
  return run->totals[n];
}

/* ---------------------------------------------------------------------- per-atom state */

double FixHardsphereED::memory_usage()
{
  return run->atoms.memory_usage() + (double) run->ed.memory_bytes() + gwin->memory_usage() +
      dwin->memory_usage();
}

void FixHardsphereED::grow_arrays(int nmax)
{
  run->atoms.grow(nmax);
}

void FixHardsphereED::copy_arrays(int i, int j, int)
{
  run->atoms.copy(i, j);
}

int FixHardsphereED::pack_exchange(int i, double *buf)
{
  return run->atoms.pack(i, buf);
}

int FixHardsphereED::unpack_exchange(int nlocal, double *buf)
{
  return run->atoms.unpack(nlocal, buf);
}

void FixHardsphereED::write_restart(FILE *fp)
{
  // (every rank: see resync_for_restart) A run that reads this file anchors the elapsed time at
  // this step (read_restart sets the step count); this run does the same, so that both compute
  // the window start times, and with them kick and wall times, with the same rounding.
  resync = true;
  update->update_time();
  // A sheared box's atoms into the box first, as Domain::pbc() wraps them (with remap v): a run
  // that reads the file remaps positions into the box but leaves velocities as they are, which
  // for an atom outside in y would keep its image's velocity. (The file is written before the
  // atoms are packed; the write_restart command itself does the same before.)
  if (domain->triclinic && domain->deform_vremap) {
    domain->x2lamda(atom->nlocal);
    domain->pbc();
    domain->lamda2x(atom->nlocal);
  }
  if (comm->me == 0) {
    // layout: -RESTART_FORMAT, the number of totals, the totals, the shell factor of domain
    // windows (which decides which copies a rank's window holds, and so its conflicts), the
    // simulation time and its step (see restart), the anchor of a sheared box's images (set or
    // not, tilt, time, rate: HardsphereRunState::ShearAnchor)
    const double head[2] = {-RESTART_FORMAT, (double) NVECTOR};
    const auto &a = run->shear;
    const double tail[7] = {dwin->reach_factor(), update->atime, (double) update->atimestep,
                            a.set ? 1.0 : 0.0, a.xy, a.t, a.rate};
    int size = (NVECTOR + 9) * sizeof(double);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(head, sizeof(double), 2, fp);
    fwrite(run->totals, sizeof(double), NVECTOR, fp);
    fwrite(tail, sizeof(double), 7, fp);
  }
}

void FixHardsphereED::restart(char *buf)
{
  // the totals (files with fewer entries leave the new ones at 0); files of the first format
  // start with the count and end with the totals, those of the second add the shell factor
  const auto *d = reinterpret_cast<const double *>(buf);
  const double format = d[0] < 0.0 ? -d[0] : 1.0;
  if (format > 1.0) d++;
  const int nsaved = (int) d[0], n = std::min(nsaved, (int) NVECTOR);
  memcpy(run->totals, d + 1, n * sizeof(double));
  if (format > 1.0) dwin->set_reach_factor(d[1 + nsaved]);
  // The windows' times (kicks, the phase of vibrating and shaking walls) are the simulation
  // time. LAMMPS's read_restart restores it; LIGGGHTS 3.8's starts it again from 0. If this
  // file's step is the current one and the host's time there differs from the writing run's,
  // the host's clock is set back to that time.
  if (format >= 3.0) {
    const double t = d[2 + nsaved];
    const bigint step = (bigint) d[3 + nsaved];
    if (update->ntimestep == step && hardsphere::time_at_step(update, step) != t) {
      update->atime = t;
      update->atimestep = step;
    }
  }
  // the line of a sheared box's images, as the writing run has it (fourth format on)
  if (format >= 4.0) {
    const double *a = d + 4 + nsaved;
    run->shear = {a[0] != 0.0, a[1], a[2], a[3]};
  }
  // (the rebuild count continues too: the step after the file was written starts afresh in
  // the writing run as in this one, see resync_for_restart)
}

int FixHardsphereED::pack_restart(int i, double *buf)
{
  buf[0] = 2;
  buf[1] = run->atoms.last_collision(i);
  return 2;
}

void FixHardsphereED::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  m++;
  // (a fix without the TC model drops them)
  if (run->atoms.has_tlast()) run->atoms.last_collision(nlocal) = extra[nlocal][m];
}

int FixHardsphereED::size_restart(int)
{
  return 2;
}

int FixHardsphereED::maxsize_restart()
{
  return 2;
}
