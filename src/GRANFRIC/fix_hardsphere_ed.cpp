// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: fix hardsphere/ed (see fix_hardsphere_ed.h and doc/fix_hardsphere_ed.rst)
------------------------------------------------------------------------- */

#include "fix_hardsphere_ed.h"

#include "hardsphere_host.h"

#include "fix_hardsphere_kick.h"
#include "fix_hardsphere_wall.h"

#include "atom.h"
#include "citeme.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
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

static constexpr int NPACK = AtomRecordAt::SIZE;    // (doubles per atom in a message)

/* ---------------------------------------------------------------------- */

FixHardsphereED::FixHardsphereED(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), tc(0.0), maxevents(1000000), tlast(nullptr), pair(nullptr), cum_time(0.0),
    gamma_bins(0), queue_valid(false), prev_dt(0.0), parallel(DOMAIN), reach(1.2), widen(1.0)
{
  if (lmp->citeme) lmp->citeme->add(cite_granfric);
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
  virial_global_flag = 1;
  virial_peratom_flag = 1;
  thermo_virial = 1;
  vector_flag = 1;
  size_vector = NVECTOR;
  global_freq = 1;
  extvector = 0;
  restart_global = 1;
  restart_peratom = 1;
  for (double &t : totals) t = 0.0;

  // per-atom arrays (LAMMPS takes callbacks only from a fix's constructor): the last collision
  // times, kept only for the TC model, and the tallies, allocated when first asked for
  atom->add_callback(Atom::GROW);
  if (tc > 0.0) {
    FixHardsphereED::grow_arrays(atom->nmax);
    maxexchange = 1;
    atom->add_callback(Atom::RESTART);
  }
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
  if (copymode) return;
  if (tlast) atom->delete_callback(id, Atom::RESTART);
  atom->delete_callback(id, Atom::GROW);
  memory->destroy(tlast);
  memory->destroy(atally);
}

FixHardsphereED *FixHardsphereED::lookup(LAMMPS *lmp, const std::string &id, const char *who)
{
  auto *f = lmp->modify->get_fix_by_id(id);
  if (!f) lmp->error->all(FLERR, "{}: fix ID {} does not exist", who, id);
  auto *ed = dynamic_cast<FixHardsphereED *>(f);
  if (!ed) lmp->error->all(FLERR, "{}: fix {} is of style {}, not hardsphere/ed", who, id, f->style);
  return ed;
}

int FixHardsphereED::setmask()
{
  return INITIAL_INTEGRATE | INITIAL_INTEGRATE_RESPA | POST_FORCE | POST_FORCE_RESPA;
}

void FixHardsphereED::request_atom_tallies()
{
  if (atally) return;
  memory->create(atally, atom->nmax, NTALLY, "hardsphere/ed:atally");
  atally_n = 0;
  grow_arrays(atom->nmax);
  maxexchange = (tlast ? 1 : 0) + NTALLY;
}

void FixHardsphereED::post_force_respa(int vflag, int ilevel, int)
{
  if (ilevel == nlevels_respa - 1) post_force(vflag);    // (the outermost level, as the window)
}

// After LAMMPS moved and sorted the atoms (their tallies went with them): the step's virial,
// global and per atom (the tallies hold each atom's share)
void FixHardsphereED::post_force(int vflag)
{
  v_init(vflag);
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
  // a shrink-wrapped non-periodic boundary may move (the fix's edge cells extend outward), but
  // no fix may change the box (deform, barostats)
  for (const auto &f : modify->get_fix_list())
    if (f->box_change)
      error->all(FLERR, "Fix hardsphere/ed does not support a box changed during the run (fix {} "
                 "{})", f->id, f->style);
  // with run_style respa the window is the outermost step (collisions need no forces)
  nlevels_respa = 0;
  if (utils::strmatch(update->integrate_style, "^respa"))
    nlevels_respa = (dynamic_cast<Respa *>(update->integrate))->nlevels;
  kicks.clear();
  walls.clear();
  for (const auto &f : modify->get_fix_list()) {
    if (f == this) continue;
    if (auto *k = dynamic_cast<FixHardsphereKick *>(f)) kicks.push_back(k);
    if (auto *w = dynamic_cast<FixHardsphereWall *>(f)) walls.push_back(w);
    if (utils::strmatch(f->style, "^gravity"))
      error->all(FLERR,
                 "Fix {} (gravity) acts together with fix hardsphere/ed {}: use the gravity "
                 "keyword of fix hardsphere/ed instead",
                 f->id, id);
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
  check_atoms_between_walls();
  // A new run may bring new coefficients, a new box, new walls or new atoms. The event queue of
  // the last run is kept only if the core's configuration is the same in every respect; the
  // atoms themselves are compared at the first window (as between steps). Vibrating walls
  // depend on the absolute time, which reset_timestep can change: always start afresh then.
  const granfric::EDOptions o = core_options();
  bool vibrating = false;
  for (const auto &w : o.walls) vibrating = vibrating || w.vibrating();
  const bool same = queue_valid && !vibrating && ed.size() > 0 &&
      ed.configured_as(o, atom->ntypes, law_table());
  if (dom_valid) {
    // the core of the last domain window: its next window compares the configuration (with
    // its own cell grid) and every atom itself
    dom_valid = !vibrating;
  } else if (!same) {
    configure_core(o);
    queue_valid = false;
  }
  check_overlaps = true;    // (a kept queue continues an exact trajectory: nothing to check)
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

// a lower wall at or above an upper wall of the same dimension leaves no room between them
void FixHardsphereED::check_walls_cross() const
{
  for (auto *lo : walls)
    for (auto *hi : walls) {
      const granfric::EDWall a = lo->geometry(), b = hi->geometry();
      if (a.dim != b.dim || a.side > 0 || b.side < 0 || a.pos + a.A < b.pos) continue;
      error->all(FLERR, "Fix hardsphere/wall {} ({} at {}{}) is not below fix hardsphere/wall {} "
                 "({} at {}): the lower wall must lie below the upper one", lo->id, lo->face(),
                 a.pos, a.A > 0.0 ? fmt::format(" + amplitude {}", a.A) : "", hi->id, hi->face(),
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
               "at least its radius away from each", who, at[0], at[1], at[2], at[3], w->id,
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
  } else if (ki >= 0) {
    // gathered window: the keys are positions in atom-ID order
    ki = (long) otags[ki];
    kj = (long) otags[kj];
  }
  if (n == 0) return;
  if (!allow_overlap) {
    queue_valid = dom_valid = false;
    error->all(FLERR,
               "Fix hardsphere/ed: atoms {} and {} overlap by {:.6g} at the start of the run ({} "
               "overlapping pairs in all). Remove them with delete_atoms overlap, create atoms with "
               "create_atoms ... overlap, or let overlapping pairs separate with keyword overlap "
               "allow", ki, kj, out.depth, (long) n);
  }
  if (comm->me == 0)
    error->warning(FLERR,
                   "Fix hardsphere/ed: {} pairs of atoms overlap at the start of the run (deepest: "
                   "atoms {} and {} by {:.6g}); approaching overlapping pairs collide at once, "
                   "receding ones separate (overlap allow)",
                   (long) n, ki, kj, out.depth);
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

void FixHardsphereED::core_failed(const std::exception &e, bool collective)
{
  queue_valid = dom_valid = false;
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

// owned atom i as a window takes it (tlast relative to the window start t0)
AtomRecord FixHardsphereED::atom_record(int i, double t0) const
{
  AtomRecord r;
  r.tag = (double) atom->tag[i];
  for (int d = 0; d < 3; d++) {
    r.x[d] = atom->x[i][d];
    r.v[d] = atom->v[i][d];
    r.w[d] = atom->omega[i][d];
  }
  r.radius = atom->radius[i];
  r.mass = atom->rmass[i];
  r.type = (double) atom->type[i];
  r.tlast = tlast_since(i, t0);
  r.mask = (double) atom->mask[i];
  return r;
}

// the kicks of every fix hardsphere/kick in [t0, t0 + dt) as global events of the core, applied
// to core particles with IDs tags and masks; the momentum shift of each kick is summed over all
// ranks (collective: every rank calls this with the same kicks)
void FixHardsphereED::schedule_kicks(double t0, double dt, const std::vector<tagint> &tags,
                                     const std::vector<int> &masks)
{
  struct Kick {
    double t;
    int fix;
    long k;
    granfric::Vec3 dvcm;
  };
  const int dim = domain->dimension;
  std::vector<Kick> all;
  for (int f = 0; f < (int) kicks.size(); f++) {
    std::vector<double> times;
    std::vector<long> index;
    kicks[f]->kicks_in(t0, t0 + dt, times, index);
    for (size_t m = 0; m < times.size(); m++)
      all.push_back({times[m] - t0, f, index[m], kicks[f]->momentum_shift(index[m], dim)});
  }
  std::stable_sort(all.begin(), all.end(), [](const Kick &a, const Kick &b) { return a.t < b.t; });
  std::vector<double> times(all.size());
  for (size_t m = 0; m < all.size(); m++) times[m] = all[m].t;
  ed.set_global_events(times, [this, all, dim, &tags, &masks](int g) {
    kicks[all[g].fix]->apply(ed, tags, masks, all[g].k, dim, all[g].dvcm);
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

// what the gathered window writes for core particle s at window time t: position in LAMMPS's
// frame (less the stored periods), velocity, spin
void FixHardsphereED::written_state(int s, double t, double *w) const
{
  ed.state(s, t, w, w + 3, w + 6);
  const int8_t *off = &offset[(size_t) s * noff];
  for (int d = 0; d < noff; d++)
    if (off[d]) w[d] -= off[d] * wper[d];    // (not periodic: wper = 0 and off = 0)
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
  queue_valid = dom_valid = false;
}

/* ----------------------------------------------------------------------
   one window: gather the system (ordered by atom ID, so the result does not depend on the
   number of ranks or on atom sorting), run the core, take back the owned atoms
------------------------------------------------------------------------- */

void FixHardsphereED::initial_integrate(int vflag)
{
  v_init(vflag);    // (vflag_atom: LAMMPS needs per-atom virials at the end of this step)
  if (vflag_atom) request_atom_tallies();
  ed.tally_particles(atally != nullptr);
  const double dt = update->dt;
  const double t0 = window_start_time();
  totals[STEP_CONFLICTS] = totals[STEP_COMM] = totals[STEP_PREDICTED] = 0.0;
  if (resync) resync_for_restart();
  if (parallel == DOMAIN && comm->nprocs > 1) {
    // the shell widens after a conflict (in dense gases collision chains outrun v_max) and
    // narrows slowly while windows pass; the same on every rank (conflicts are global)
    if (window_domain(t0, dt)) {
      totals[DOMAIN_WINDOWS] += 1.0;
      widen = MAX(1.0, widen * 0.99);
      finish_window(dt);
      return;
    }
    totals[WINDOWS_REDONE] += 1.0;    // a conflict: the whole window again, gathered
    widen = MIN(64.0, 2.0 * widen);
  }
  window_gather(t0, dt);
  finish_window(dt);
}

void FixHardsphereED::window_gather(double t0, double dt)
{
  const int nlocal = atom->nlocal;
  double **x = atom->x, **v = atom->v, **omega = atom->omega;
  const double *radius = atom->radius, *rmass = atom->rmass;
  const int *type = atom->type;
  const tagint *tag = atom->tag;

  // On several ranks every rank packs its atoms and gathers everybody's. On one rank the atom
  // arrays are the system: they are read in place (no copy).
  const int nprocs = comm->nprocs, me = comm->me;
  const int *amask = atom->mask;
  auto record = [&](int k) {
    return nprocs > 1 ? AtomRecord::read(&recvbuf[(size_t) k * NPACK]) : atom_record(k, t0);
  };
  if (nprocs > 1) sendbuf.resize((size_t) nlocal * NPACK);
  for (int i = 0; i < nlocal && nprocs > 1; i++) atom_record(i, t0).write(&sendbuf[(size_t) i * NPACK]);
  int total = nlocal * NPACK;
  if (nprocs == 1) {
    displs.assign(1, 0);
  } else {
    total = allgather(sendbuf, recvbuf);
  }
  const int ntotal = total / NPACK;

  // order by atom ID; LAMMPS changes the storage order only when it reneighbors, so the last
  // step's order usually still holds
  auto tag_of = [&](int k) {
    return nprocs > 1 ? (tagint) recvbuf[(size_t) k * NPACK + AtomRecordAt::TAG] : tag[k];
  };
  bool same_order = (int) order.size() == ntotal;
  for (int s = 0; same_order && s < ntotal; s++) same_order = tag_of(order[s]) == otags[s];
  if (!same_order) {
    order.resize(ntotal);
    for (int k = 0; k < ntotal; k++) order[k] = k;
    std::sort(order.begin(), order.end(), [&](int a, int b) { return tag_of(a) < tag_of(b); });
    // the same atoms as the core's if the sorted tags are the same
    bool same = same_atoms && (int) otags.size() == ntotal;
    otags.resize(ntotal);
    for (int s = 0; s < ntotal; s++) {
      const tagint t = tag_of(order[s]);
      same = same && otags[s] == t;
      otags[s] = t;
    }
    same_atoms = same;
  }
  // core particle s is this rank's atom order[s] - myfirst if that lies in [0, nlocal)
  const int myfirst = displs[me] / NPACK;

  for (int d = 0; d < 3; d++) wper[d] = domain->periodicity[d] ? domain->prd[d] : 0.0;

  // Keep the event queue of the previous window when nothing outside this fix touched the
  // atoms since then: same atoms, and positions, velocities and spins bit for bit what this
  // fix wrote (every rank sees the same gathered data, so all decide alike). What was written
  // is recomputed from the core, with the same arithmetic, rather than stored.
  bool reuse = queue_valid && ed.size() == ntotal && same_atoms && noff == domain->dimension &&
      (int) offset.size() == noff * ntotal;
  for (int s = 0; reuse && s < ntotal; s++) {
    const int k = order[s];
    // this window's x, v, omega of the atom (in place on one rank)
    const double *bx, *bv, *bw;
    if (nprocs == 1) {
      bx = x[k];
      bv = v[k];
      bw = omega[k];
      reuse = ed.is_body(s, radius[k], rmass[k], type[k]);
    } else {
      const double *r = &recvbuf[(size_t) k * NPACK];
      bx = r + AtomRecordAt::X;
      bv = r + AtomRecordAt::V;
      bw = r + AtomRecordAt::W;
      reuse = ed.is_body(s, r[AtomRecordAt::RADIUS], r[AtomRecordAt::MASS], (int) r[AtomRecordAt::TYPE]);
    }
    if (!reuse) break;
    double w[9];
    written_state(s, prev_dt, w);
    for (int d = 0; reuse && d < 3; d++) reuse = bv[d] == w[3 + d] && bw[d] == w[6 + d];
    // positions: what this fix wrote, or that shifted by one period by Domain::pbc()
    for (int d = 0; reuse && d < 3; d++) {
      const double b = bx[d];
      if (b == w[d]) continue;
      int8_t &off = offset[(size_t) s * noff + d];
      if (!domain->periodicity[d] || d >= noff) {
        reuse = false;
      } else if (b == w[d] + domain->prd[d] && off > -OFFSET_MAX) {
        off--;
      } else if (b == MAX(w[d] - domain->prd[d], domain->boxlo[d]) && off < OFFSET_MAX) {
        off++;
      } else {
        reuse = false;    // (or the offset would leave its range: start afresh)
      }
    }
  }
  if (reuse) {
    ed.rebase(prev_dt);
    ed.set_clock(t0);
    check_overlaps = false;
  } else {
    configure_core(core_options());
    ed.resize(ntotal);
    for (int s = 0; s < ntotal; s++) {
      const AtomRecord r = record(order[s]);
      auto p = ed.particle(s);
      p.x = granfric::Vec3(r.x[0], r.x[1], r.x[2]);
      p.v = granfric::Vec3(r.v[0], r.v[1], r.v[2]);
      p.w = granfric::Vec3(r.w[0], r.w[1], r.w[2]);
      p.a = r.radius;
      p.m = r.mass;
      p.type = (int) r.type;
      p.t_last = r.tlast;
    }
    same_atoms = true;
    ed.set_clock(t0);
    start_core(true);
    report_overlaps(false);
    noff = domain->dimension;
    offset.assign((size_t) ntotal * noff, 0);
    totals[QUEUE_REBUILDS] += 1.0;
    totals[STEP_PREDICTED] = (double) ntotal;
  }

  // kicks of fix hardsphere/kick at their exact times inside the window
  if (!kicks.empty() || want_rows) {
    cmask.resize(ntotal);
    for (int s = 0; s < ntotal; s++) {
      const int k = order[s];
      cmask[s] = nprocs > 1 ? (int) recvbuf[(size_t) k * NPACK + AtomRecordAt::MASK] : amask[k];
    }
  }
  if (!kicks.empty()) schedule_kicks(t0, dt, otags, cmask);

  ed.set_accounting(granfric::EDAccounting());
  ed.record_events(nullptr);
  clog.clear();
  ed.record_collisions(want_rows ? &clog : nullptr);
  try {
    last = ed.advance_to(dt);
  } catch (granfric::EventCapError &e) {
    queue_valid = false;
    if (e.kind == granfric::EventCapError::CROSSINGS)
      error->all(FLERR,
                 "Fix hardsphere/ed: {} cell crossings within step {} exceed maxevents x atoms "
                 "= {}; atom {} was crossing at speed {:.6g}: atoms move far faster than the system's "
                 "scale (did a collision law create energy, e.g. hardsphere/jz with kappa_d > "
                 "kappa_s, or does an atom start much faster than the others?)",
                 e.n, update->ntimestep, e.n - 1, (tagint) otags[e.i], e.speed);
    bool creating = false;
    for (const auto &law : law_table()) creating = creating || law.can_create_energy();
    error->all(FLERR,
               "Fix hardsphere/ed: atom {} had {} collisions within step {} (maxevents {}), the "
               "last one with atom {} at time {}: {}",
               (tagint) otags[e.i], e.n, update->ntimestep, maxevents, (tagint) otags[e.j],
               t0 + e.t,
               creating ? "a collision law here can create energy (hardsphere/jz with kappa_d > "
                          "kappa_s), which can run away; use kappa_d <= kappa_s, or raise "
                          "maxevents if the energy stays bounded"
                        : "inelastic collapse. Use the TC model (keyword tc) or raise maxevents");
  } catch (std::exception &e) {
    core_failed(e, true);
  }
  // (every rank ran every collision: rank 0 keeps the rows)
  if (comm->me != 0) clog.clear();
  keep_rows(t0, otags, cmask);

  // State at the end of the window in LAMMPS's frame: the core's unwrapped position less the
  // periods LAMMPS wrapped (pbc() at reneighboring keeps doing that, with the image flags). An
  // atom more than half a box outside (a step longer than a box crossing) is wrapped here and
  // its image flags follow. The same arithmetic on every rank.
  imageint *image = atom->image;
  double wlo[3], whi[3];    // more than half a period outside the box (none if not periodic)
  for (int d = 0; d < 3; d++) {
    wlo[d] = domain->periodicity[d] ? domain->boxlo[d] - 0.5 * domain->prd[d] : -INF;
    whi[d] = domain->periodicity[d] ? domain->boxhi[d] + 0.5 * domain->prd[d] : INF;
  }
  // core particle s; i: its owned atom, or -1
  bool offsets_full = false;    // an offset left its range: the next window starts afresh
  // (the same arithmetic as written_state, with the offsets updated here)
  auto take_back = [&](int s, int i) {
    int8_t *stored = &offset[(size_t) s * noff];
    int dimg[3] = {0, 0, 0};
    double w[9];
    ed.state(s, dt, w, w + 3, w + 6);
    for (int d = 0; d < noff; d++) {
      int off = stored[d];
      double y = off ? w[d] - off * wper[d] : w[d];
      if (y < wlo[d] || y >= whi[d]) {
        const double L = domain->prd[d];
        dimg[d] = (int) std::floor((y - domain->boxlo[d]) / L);
        off += dimg[d];
        if (off < -OFFSET_MAX || off > OFFSET_MAX) offsets_full = true;
        stored[d] = (int8_t) std::max(-OFFSET_MAX, std::min(OFFSET_MAX, off));
        y = off ? w[d] - off * wper[d] : w[d];
      }
      w[d] = y;
    }
    if (i < 0) return;
    if (atally) store_tally(i, s, t0);
    shift_image(image[i], dimg);
    memcpy(x[i], w, 3 * sizeof(double));
    memcpy(v[i], w + 3, 3 * sizeof(double));
    memcpy(omega[i], w + 6, 3 * sizeof(double));
    if (tlast) set_tlast(i, std::as_const(ed).particle(s).t_last, t0);
  };
  for (int s = 0; s < ntotal; s++) {
    const int i = order[s] - myfirst;
    take_back(s, i >= 0 && i < nlocal ? i : -1);
  }
  queue_valid = !offsets_full;
  prev_dt = dt;
}

// the rows of the core's collision records of the window that began at t0, with the IDs and
// masks of its particles (by core index)
template <class TAGS>
void FixHardsphereED::keep_rows(double t0, const TAGS &tags, const std::vector<int> &masks)
{
  ed.record_collisions(nullptr);
  rows.clear();
  for (const auto &c : clog) {
    const bool wall = c.j < 0;
    rows.push_back({t0 + c.t, {(tagint) tags[c.i], wall ? 0 : (tagint) tags[c.j]},
                    {masks[c.i], wall ? 0 : masks[c.j]}, wall ? -c.j : 0, c});
  }
}

// (the domain windows' instance)
template void FixHardsphereED::keep_rows(double, const std::vector<long> &, const std::vector<int> &);

// owned atom i is core particle s of the window that began at t0: its tallies of the step
void FixHardsphereED::store_tally(int i, int s, double t0)
{
  const auto &p = ed.particle_tally(s);
  double *a = atally[i];
  for (int k = 0; k < 6; k++) a[T_VIRIAL + k] = p.virial[k];
  a[T_COLL] = p.collisions;
  a[T_WALL] = p.wall_collisions;
  a[T_DETR] = p.dE_tr * force->mvv2e;
  a[T_DEROT] = p.dE_rot * force->mvv2e;
  a[T_DEWALL] = p.dE_wall * force->mvv2e;
  if (p.t_last > -INF) a[T_LAST] = t0 + p.t_last;
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
  auto bytes = [](const auto &vec) { return (double) vec.capacity() * sizeof(vec[0]); };
  return (tlast ? (double) atom->nmax * sizeof(double) : 0.0) +
      (atally ? (double) atom->nmax * NTALLY * sizeof(double) : 0.0) + (double) ed.memory_bytes() + bytes(sendbuf) +
      bytes(recvbuf) + bytes(order) + bytes(otags) + bytes(offset) +
      bytes(cmask) + bytes(history) + bytes(dsend) + bytes(drecv) + bytes(hsend) +
      bytes(hrecv) + bytes(gtag) + bytes(gmask) + bytes(kick_tags) + bytes(dom_slot) +
      bytes(dom_free) + bytes(lslot) + bytes(sowned) + bytes(sowned_prev) + bytes(sseen) +
      bytes(dom_sent) + bytes(dom_inslot) + bytes(dom_evlist) + bytes(dom_cslot) + bytes(dom_watch) +
      bytes(dom_gsrc) + bytes(dom_start) + bytes(dom_fill) + bytes(dom_gshift) + bytes(dom_tstar) +
      bytes(dom_pub);
}

// per-atom arrays: the last collision times of the TC model (tc > 0) and the tallies (when asked)
void FixHardsphereED::grow_arrays(int nmax)
{
  if (tc > 0.0) {
    memory->grow(tlast, nmax, "hardsphere/ed:tlast");
    for (int i = tlast_n; i < nmax; i++) tlast[i] = -INF;    // (new atoms: no collision yet)
    tlast_n = std::max(tlast_n, nmax);
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
  if (atally) memcpy(atally[j], atally[i], NTALLY * sizeof(double));
}

int FixHardsphereED::pack_exchange(int i, double *buf)
{
  int m = 0;
  if (tlast) buf[m++] = tlast[i];
  if (atally)
    for (int k = 0; k < NTALLY; k++) buf[m++] = atally[i][k];
  return m;
}

int FixHardsphereED::unpack_exchange(int nlocal, double *buf)
{
  int m = 0;
  if (tlast) tlast[nlocal] = buf[m++];
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
    // windows (which decides which copies a rank's window holds, and so its rounding)
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
