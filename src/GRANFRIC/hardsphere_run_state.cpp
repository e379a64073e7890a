// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: the state of a run of fix hardsphere/ed (see hardsphere_run_state.h)
------------------------------------------------------------------------- */

#include "hardsphere_run_state.h"

#include "hardsphere_host.h"
#include "pair_hardsphere.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "force.h"
#include "update.h"

#include <algorithm>
#include <cmath>

using namespace LAMMPS_NS;

HardsphereRunState::HardsphereRunState(LAMMPS *lmp, bool stored, double tc) :
    Pointers(lmp), atoms(lmp, stored, tc > 0.0)
{
  settings.tc = tc;
  for (double &t : totals) t = 0.0;
}

/* ---------------------------------------------------------------- the core's configuration */

granfric::EDOptions HardsphereRunState::core_options() const
{
  granfric::EDOptions o;
  o.dim = domain->dimension;
  for (int d = 0; d < 3; d++) {
    o.lo[d] = domain->boxlo[d];
    o.hi[d] = domain->boxhi[d];
    o.periodic[d] = domain->periodicity[d];
  }
  o.gravity = granfric::Vec3(settings.gravity[0], settings.gravity[1], settings.gravity[2]);
  o.tc = settings.tc;
  o.max_collisions = settings.maxevents;
  o.max_crossings = settings.maxcross;
  o.gamma_bins = settings.gamma_bins;
  for (auto *w : walls) o.walls.push_back(w->wall());
  o.shape.assign(atom->ntypes + 1, 0.4);
  for (int t = 1; t <= atom->ntypes; t++) o.shape[t] = pair->shape_factor(t);
  // a triclinic box is sheared in xy (check_box_changes): Lees-Edwards images, moving at the
  // tilt's rate when fix deform changes it
  o.shear = domain->triclinic;
  o.shear_rate = domain->triclinic ? shear_rate() : 0.0;
  return o;
}

double HardsphereRunState::shear_rate() const
{
  const double u = domain->h_rate[5];
  return shear.set && std::fabs(u - shear.rate) <= 1e-12 * std::fabs(shear.rate) ? shear.rate : u;
}

void HardsphereRunState::anchor_shear(double t0)
{
  const double u = domain->h_rate[5], Lx = domain->prd[0];
  if (shear.set) {
    double d = domain->xy - shear_shift_at(t0);
    d -= std::round(d / Lx) * Lx;
    if (shear_rate() == shear.rate && std::fabs(d) <= 1e-9 * Lx) return;
    if (update->ntimestep - 1 != update->beginstep)
      error->all(FLERR, "Fix hardsphere/ed: the box's xy tilt {} (rate {}) left the line of the "
                 "sheared images ({} at rate {}): fix deform must change xy at a constant rate "
                 "(styles final, delta, vel or erate, not trate, wiggle or variable)", domain->xy,
                 u, shear_shift_at(t0), shear.rate);
  }
  shear = {true, domain->xy, t0, u};
  drop_core();    // (a new line: a new epoch)
}

std::vector<granfric::LawParams> HardsphereRunState::law_table() const
{
  const int nt = atom->ntypes;
  std::vector<granfric::LawParams> laws((nt + 1) * (nt + 1));
  for (int i = 1; i <= nt; i++)
    for (int j = 1; j <= nt; j++) laws[i * (nt + 1) + j] = pair->law(i, j);
  return laws;
}

// A new run may bring new coefficients, a new box, new walls or new atoms. The epoch (and the
// event queue) of the last run goes on only if the core's configuration is the same in every
// respect; the atoms themselves are compared at the first window (as between steps).
// Vibrating and shaking walls depend on the absolute time, which reset_timestep can change:
// always a new epoch then.
void HardsphereRunState::new_run()
{
  const granfric::EDOptions o = core_options();
  const std::vector<granfric::LawParams> laws = law_table();
  bool vibrating = false;
  for (const auto &w : o.walls) vibrating = vibrating || w.vibrating() || w.shaking();
  const bool same = !vibrating && run_ntypes == atom->ntypes &&
      granfric::EventDriven::same_configuration(o, atom->ntypes, laws, run_options, run_ntypes, run_laws);
  if (!same) {
    configure_core(o);
    drop_core();
  }
  run_options = o;
  run_laws = laws;
  run_ntypes = atom->ntypes;
  check_overlaps = true;    // (a kept queue continues an exact trajectory: nothing to check)
  added_at = -1;
}

void HardsphereRunState::drop_core()
{
  core_user = nullptr;
  epoch_due = true;
}

void HardsphereRunState::configure_core(const granfric::EDOptions &o, bool collective)
{
  try {
    ed.configure(o, atom->ntypes, law_table());
  } catch (std::exception &e) {
    core_failed(e, collective);
  }
}

void HardsphereRunState::start_core(bool collective)
{
  try {
    ed.start();
  } catch (std::exception &e) {
    core_failed(e, collective);
  }
}

void HardsphereRunState::core_failed(const std::exception &e, bool collective)
{
  drop_core();
  if (collective) error->all(FLERR, "Fix hardsphere/ed: {}", e.what());
  error->one(FLERR, "Fix hardsphere/ed: {}", e.what());
}

/* ---------------------------------------------------------------- epochs */

bool HardsphereRunState::epoch_starts() const
{
  const bigint first = update->ntimestep - 1;    // (this window's first step)
  return epoch_due || update->dt != epoch_dt || first < epoch_step || first - epoch_step >= EPOCH_WINDOWS;
}

void HardsphereRunState::begin_epoch(double t0)
{
  epoch_step = update->ntimestep - 1;
  epoch_clock = t0;
  epoch_dt = update->dt;
  epoch_due = false;
  atoms.written_at = NAN;
}

double HardsphereRunState::window_start() const
{
  return epoch_time(update->ntimestep - 1);
}

double HardsphereRunState::window_end() const
{
  return epoch_time(update->ntimestep);
}

/* ---------------------------------------------------------------- kicks */

// the kicks of every fix hardsphere/kick in [t0, t0 + dt) in time order; the momentum shift of
// each kick is summed over all ranks (collective: every rank calls this for the same window)
std::vector<PlannedKick> HardsphereRunState::plan_kicks(double t0, double dt)
{
  const int dim = domain->dimension;
  std::vector<PlannedKick> all;
  // (epoch times: kicks of this window stay in [T0, T1) whatever the rounding)
  const double T0 = window_start(), T1 = window_end();
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
// masks (each rank alone; tags and masks stay alive through the window)
void HardsphereRunState::schedule_kicks(const std::vector<PlannedKick> &plan,
                                        const std::vector<tagint> &tags, const std::vector<int> &masks)
{
  const int dim = domain->dimension;
  std::vector<double> times(plan.size());
  for (size_t m = 0; m < plan.size(); m++) times[m] = plan[m].t;
  ed.set_global_events(times, [this, plan, dim, &tags, &masks](int g) {
    kicks[plan[g].fix]->apply(ed, tags, masks, plan[g].k, dim, plan[g].dvcm);
  });
}

std::vector<long> HardsphereRunState::kick_counters() const
{
  std::vector<long> c(kicks.size());
  for (size_t f = 0; f < kicks.size(); f++) c[f] = kicks[f]->kick_counter();
  return c;
}

void HardsphereRunState::rewind_kicks(const std::vector<long> &counters)
{
  for (size_t f = 0; f < kicks.size(); f++) kicks[f]->rewind(counters[f]);
}

/* ---------------------------------------------------------------- overlaps */

void HardsphereRunState::report_overlaps(bool partial)
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
  if (!settings.allow_overlap) {
    drop_core();
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

/* ---------------------------------------------------------------- counters and rows */

// the collision counts include wall collisions, as the core's sliding, TC-elastic and
// energy-creating counts do
void HardsphereRunState::finish_window(double dt)
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

void HardsphereRunState::record_collisions()
{
  clog.clear();
  ed.record_collisions(want_rows ? &clog : nullptr);
}
