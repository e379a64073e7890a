// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: fix hardsphere/ed, gathered windows (see hardsphere_gather_window.h)
------------------------------------------------------------------------- */

#include "hardsphere_gather_window.h"

#include "hardsphere_host.h"
#include "hardsphere_run_state.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <cstring>
#include <utility>

using namespace LAMMPS_NS;

static constexpr int NPACK = AtomRecordAt::SIZE;    // (doubles per atom in a message)

HardsphereGatherWindow::HardsphereGatherWindow(HardsphereRunState &r) :
    Pointers(r.instance()), state(r), ed(r.ed)
{
}

// (redo: the window again after a domain window had a conflict; the atoms come from their
// stored states, see HardsphereAtomStates)
void HardsphereGatherWindow::run(double t0, double dt, bool redo)
{
  // (the stored states hold from the second window of an epoch on)
  const bool exact = redo && state.epoch_step != update->ntimestep - 1;
  gather(exact);
  order_by_id();
  for (int d = 0; d < 3; d++) wper[d] = domain->periodicity[d] ? domain->prd[d] : 0.0;
  const double T0 = state.window_start();
  const bool was_sheared = sheared;
  sheared = domain->triclinic;
  if (sheared != was_sheared) valid = false;
  if (sheared) state.anchor_shear(t0);
  const bool epoch = !exact && (redo || state.epoch_starts() || !can_reuse(T0));
  if (epoch) state.begin_epoch(t0);    // (again after a domain window began it: the same)
  if (epoch || exact)
    fresh_core(exact);
  else
    state.check_overlaps = false;
  state.core_used_by(this);
  const double T1 = state.window_end();
  schedule_kicks(t0, dt);
  advance(T1);
  take_back(T1);
}

// atom k of the gathered system: on one rank the atom arrays are the system, read in place
AtomRecord HardsphereGatherWindow::record(int k) const
{
  return comm->nprocs > 1 ? AtomRecord::read(&recvbuf[(size_t) k * NPACK]) : state.atom_record(k, false);
}

// On several ranks every rank packs its atoms and gathers everybody's. On one rank the atom
// arrays are the system: they are read in place (no copy).
void HardsphereGatherWindow::gather(bool exact)
{
  const int nlocal = atom->nlocal, nprocs = comm->nprocs;
  int total = nlocal * NPACK;
  if (nprocs == 1) {
    displs.assign(1, 0);
  } else {
    sendbuf.resize((size_t) nlocal * NPACK);
    for (int i = 0; i < nlocal; i++) state.atom_record(i, exact).write(&sendbuf[(size_t) i * NPACK]);
    total = allgather(sendbuf, recvbuf);
  }
  ntotal = total / NPACK;
  // core particle s is this rank's atom order[s] - myfirst if that lies in [0, nlocal)
  myfirst = displs[comm->me] / NPACK;
}

// every rank's send buffer, concatenated in rank order into recv (counts and displs say where
// each rank's part lies); the doubles received are counted; returns the total
int HardsphereGatherWindow::allgather(const std::vector<double> &send, std::vector<double> &recv)
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
  state.totals[HardsphereRunState::STEP_COMM] += (double) total * (nprocs - 1);
  return total;
}

// order by atom ID; LAMMPS changes the storage order only when it reneighbors, so the last
// step's order usually still holds
void HardsphereGatherWindow::order_by_id()
{
  // (the IDs read in place: this runs for every atom and step)
  const double *rb = recvbuf.data();
  const tagint *tag = atom->tag;
  const bool gathered = comm->nprocs > 1;
  auto id = [=](int k) { return gathered ? (tagint) rb[(size_t) k * NPACK + AtomRecordAt::TAG] : tag[k]; };
  bool same_order = (int) order.size() == ntotal;
  for (int s = 0; same_order && s < ntotal; s++) same_order = id(order[s]) == otags[s];
  if (same_order) return;
  order.resize(ntotal);
  for (int k = 0; k < ntotal; k++) order[k] = k;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return id(a) < id(b); });
  // the same atoms as the core's if the sorted tags are the same
  bool same = same_atoms && (int) otags.size() == ntotal;
  otags.resize(ntotal);
  for (int s = 0; s < ntotal; s++) {
    const tagint t = id(order[s]);
    same = same && otags[s] == t;
    otags[s] = t;
  }
  same_atoms = same;
}

// Keep the event queue of the previous window when nothing outside this fix touched the atoms
// since then: same atoms, and positions, velocities and spins bit for bit what this window
// wrote (every rank sees the same gathered data, so all decide alike). What was written is
// recomputed from the core, with the same arithmetic, rather than stored.
bool HardsphereGatherWindow::can_reuse(double T0)
{
  bool reuse = valid && state.core_kept_by(this) && ed.size() == ntotal && same_atoms && noff == domain->dimension &&
      (int) offset.size() == noff * ntotal;
  const hardsphere::FarWrap wrap(domain);
  const hardsphere::ShearWrap shear(domain, state.pbc_xy, state.view_xy, state.view_u);
  for (int s = 0; reuse && s < ntotal; s++) {
    if (s + AHEAD < ntotal) ed.prefetch_particle(s + AHEAD);
    reuse = reusable(s, T0, wrap, shear);
  }
  return reuse;
}

// does core particle s hold this window's atom (its position up to the periods LAMMPS wrapped,
// which update its offsets)?
inline __attribute__((always_inline)) bool HardsphereGatherWindow::reusable(int s, double T0,
                                                                            const hardsphere::FarWrap &wrap,
                                                                            const hardsphere::ShearWrap &shear)
{
  const int k = order[s];
  // this window's x, v, omega of the atom (in place on one rank)
  const double *bx, *bv, *bw;
  if (comm->nprocs == 1) {
    bx = atom->x[k];
    bv = atom->v[k];
    bw = atom->omega[k];
    if (!ed.is_body(s, atom->radius[k], atom->rmass[k], atom->type[k])) return false;
  } else {
    const double *r = &recvbuf[(size_t) k * NPACK];
    bx = r + AtomRecordAt::XL;
    bv = r + AtomRecordAt::V;
    bw = r + AtomRecordAt::W;
    if (!ed.is_body(s, r[AtomRecordAt::RADIUS], r[AtomRecordAt::MASS], (int) r[AtomRecordAt::TYPE]))
      return false;
  }
  double w[9];
  written_state(s, T0, w);
  if (sheared) return reusable_sheared(s, bx, bv, bw, w, shear);
  for (int d = 0; d < 3; d++)
    if (bv[d] != w[3 + d] || bw[d] != w[6 + d]) return false;
  // positions: what this window wrote, or that shifted by one period by Domain::pbc()
  for (int d = 0; d < 3; d++) {
    int8_t &stored = offset[(size_t) s * noff + d];
    int off = d < noff ? stored : 0;
    if (!wrap.holds(d, bx[d], w[d], off) || off < -OFFSET_MAX || off > OFFSET_MAX) return false;
    if (d < noff) stored = (int8_t) off;
  }
  return true;
}

// reusable() in a sheared box: the atom as hardsphere::ShearWrap recognises it (the tilt and
// the x velocity across the y faces, the rounding of a triclinic box's positions), its offsets
// following the periods LAMMPS wrapped
bool HardsphereGatherWindow::reusable_sheared(int s, const double *bx, const double *bv, const double *bw,
                                              const double *w, const hardsphere::ShearWrap &wrap)
{
  for (int d = 0; d < 3; d++)
    if (bw[d] != w[6 + d]) return false;
  if (bv[1] != w[4] || bv[2] != w[5]) return false;
  if (wrap.unwrapped(bx, bv[0], w, w[3])) return true;    // (periods unchanged)
  int k[3];
  double c[3], cvx;
  if (!wrap.match(bx, bv[0], w, w[3], k, c, cvx)) return false;
  int8_t *stored = &offset[(size_t) s * noff];
  int off[3];
  for (int d = 0; d < noff; d++) {
    off[d] = stored[d] + k[d];
    if (off[d] < -OFFSET_MAX || off[d] > OFFSET_MAX) return false;
  }
  for (int d = 0; d < noff; d++) stored[d] = (int8_t) off[d];
  return true;
}

// a sheared box: what an atom k periods up in y is written as, x less k times the tilt and v_x
// less k times its rate (out of line: the loops over all atoms only test for it)
__attribute__((noinline)) void HardsphereGatherWindow::shear_view(int k, double *w) const
{
  w[0] -= k * state.view_xy;
  w[3] -= k * state.view_u;
}

// what this window writes for core particle s at window time t: position in LAMMPS's frame
// (less the stored periods; in a sheared box y's also less the tilt in x and its rate in the x
// velocity), velocity, spin
inline __attribute__((always_inline)) void HardsphereGatherWindow::written_state(int s, double t,
                                                                                  double *w) const
{
  ed.state(s, t, w, w + 3, w + 6);
  const int8_t *off = &offset[(size_t) s * noff];
  if (sheared && off[1]) shear_view(off[1], w);
  for (int d = 0; d < noff; d++)
    if (off[d]) w[d] -= off[d] * wper[d];    // (not periodic: wper = 0 and off = 0)
}

// the core afresh from the gathered atoms, in the order of their IDs: at the start of an
// epoch from LAMMPS's atoms, else from their stored states (exact), which it continues
void HardsphereGatherWindow::fresh_core(bool exact)
{
  state.configure_core(state.core_options());
  // (sheared: the images' shift at epoch time 0, on the anchored line)
  if (sheared) ed.set_shear_shift(state.shear_shift_at(state.epoch_clock));
  ed.resize(ntotal);
  noff = domain->dimension;
  offset.assign((size_t) ntotal * noff, 0);
  keys.resize(ntotal);
  for (int s = 0; s < ntotal; s++) {
    const AtomRecord r = record(order[s]);
    r.to_particle(ed.particle(s));
    ed.particle(s).t_last = r.tlast;
    for (int d = 0; d < noff; d++) offset[(size_t) s * noff + d] = (int8_t) r.off[d];
    keys[s] = (long) otags[s];
  }
  for (int s = 0; exact && s < ntotal; s++) {
    // (the last partner by its ID: otags is sorted)
    const AtomRecord r = record(order[s]);
    const auto at = std::lower_bound(otags.begin(), otags.end(), (tagint) r.partner);
    const int p = r.partner > 0.0 && at != otags.end() && *at == (tagint) r.partner ? (int) (at - otags.begin()) : -1;
    const int poff[3] = {(int) r.poff[0], (int) r.poff[1], (int) r.poff[2]};
    ed.set_last_partner(s, p, poff);
  }
  same_atoms = true;
  ed.set_accounting({keys.data(), nullptr});
  ed.set_clock(state.epoch_clock);
  if (exact) {
    try {
      ed.start_at(state.window_start());
    } catch (std::exception &e) {
      state.core_failed(e, true);
    }
  } else {
    state.start_core(true);
    state.report_overlaps(false);
  }
  state.totals[HardsphereRunState::QUEUE_REBUILDS] += 1.0;
  state.totals[HardsphereRunState::STEP_PREDICTED] = (double) ntotal;
}

// kicks of fix hardsphere/kick at their exact times inside the window (and the masks the
// collision rows report)
void HardsphereGatherWindow::schedule_kicks(double t0, double dt)
{
  if (state.kicks.empty() && !state.want_rows) return;
  cmask.resize(ntotal);
  for (int s = 0; s < ntotal; s++) {
    const int k = order[s];
    cmask[s] = comm->nprocs > 1 ? (int) recvbuf[(size_t) k * NPACK + AtomRecordAt::MASK] : atom->mask[k];
  }
  if (!state.kicks.empty()) state.schedule_kicks(state.plan_kicks(t0, dt), otags, cmask);
}

// the window itself; a core that fails stops the run with what went wrong
void HardsphereGatherWindow::advance(double T1)
{
  ed.set_accounting({keys.data(), nullptr});    // (keys: the atom IDs)
  ed.record_events(nullptr);
  state.record_collisions();
  try {
    state.last = ed.advance_to(T1);
  } catch (granfric::EventCapError &e) {
    valid = false;
    if (e.kind == granfric::EventCapError::CROSSINGS)
      error->all(FLERR,
                 "Fix hardsphere/ed: {} cell crossings within step {} exceed maxcross x atoms "
                 "= {}; atom {} was crossing at speed {:.6g}: atoms move far faster than the system's "
                 "scale (did a collision law create energy, e.g. hardsphere/jz with kappa_d > "
                 "kappa_s, does a moving wall pump energy in without bound, e.g. a fast vibrating "
                 "wall with elastic collisions, or does an atom start much faster than the others? "
                 "Raise maxcross only if such speeds are meant)",
                 e.n, update->ntimestep, e.n - 1, (tagint) otags[e.i], e.speed);
    const std::string partner = e.j < 0 ? host::format("fix hardsphere/wall {}", state.walls[-1 - e.j]->wall_id())
                                        : host::format("atom {}", (tagint) otags[e.j]);
    error->all(FLERR,
               "Fix hardsphere/ed: atom {} had {} collisions within step {} (maxevents {}), the "
               "last one with {} at time {}: {}",
               (tagint) otags[e.i], e.n, update->ntimestep, state.settings.maxevents, partner,
               state.epoch_clock + e.t, endless_collisions());
  } catch (std::exception &e) {
    state.core_failed(e, true);
  }
  // (every rank ran every collision: rank 0 keeps the rows)
  if (comm->me != 0) state.clog.clear();
  state.keep_rows(otags, cmask);
}

// Why a particle can collide without end, from what the collision laws allow: laws that create
// energy can run away; inelastic ones collapse (the TC model prevents it); when every law
// conserves energy neither applies, and what is left is a particle caged among neighbours it
// overlaps (overlap allow) or one far lighter than its neighbours. A bed on a floor under
// gravity cools without end even with the TC model, so there the advice is a thermal floor.
std::string HardsphereGatherWindow::endless_collisions() const
{
  bool creating = false, elastic = true, floor = false;
  std::vector<granfric::LawParams> laws = state.law_table();
  for (auto *w : state.walls) {
    const granfric::EDWall e = w->wall();
    laws.insert(laws.end(), e.laws.begin() + 1, e.laws.end());
    floor = floor || (e.T < 0.0 && e.toward(state.settings.gravity) > 0.0);
  }
  for (const auto &law : laws) {
    creating = creating || law.can_create_energy();
    elastic = elastic && law.conserves_energy();
  }
  const double tc = state.settings.tc;
  if (creating)
    return "a collision law here can create energy (hardsphere/jz with kappa_d > kappa_s), which "
           "can run away; use kappa_d <= kappa_s, or raise maxevents if the energy stays bounded";
  if (elastic)
    return std::string("every collision law here conserves energy, so this is no inelastic "
                       "collapse: ") +
        (state.settings.allow_overlap ? "atoms that overlap their neighbours (overlap allow) can "
                                        "be caged by them, or "
                                      : "") +
        "a particle far lighter than its neighbours collides far more often than they do; check "
        "the initial configuration and the masses, or raise maxevents";
  const std::string bed = floor ? "; a bed on a floor that is not thermal cools under gravity without "
                                  "end, colliding ever more often, which the TC model slows but does "
                                  "not stop: make the floor thermal at a small temperature (see the fix "
                                  "hardsphere/wall page, 'Grains at rest on a floor')"
                                : "";
  return tc > 0.0 ? host::format("inelastic collapse despite the TC model (tc {}): raise tc or maxevents{}", tc, bed)
                  : "inelastic collapse. Use the TC model (keyword tc) or raise maxevents" + bed;
}

// State at the end of the window in LAMMPS's frame: the core's unwrapped position less the
// periods LAMMPS wrapped (pbc() at reneighboring keeps doing that, with the image flags). An
// atom more than half a box outside (a step longer than a box crossing) is wrapped here and its
// image flags follow. The same arithmetic on every rank, and as written_state's. For windows
// on several ranks each atom keeps its stored state (HardsphereAtomStates).
void HardsphereGatherWindow::take_back(double T1)
{
  const int nlocal = atom->nlocal;
  const hardsphere::FarWrap wrap(domain);
  if (sheared) {    // (the anchored shift at the window's end, on the branch of the box's tilt)
    const double xy = state.shear_shift_at(state.epoch_clock + T1);
    state.view_xy = xy - std::round((xy - domain->xy) / domain->prd[0]) * domain->prd[0];
    state.view_u = state.shear.rate;
    state.pbc_xy = domain->xy;
  }
  bool offsets_full = false;    // an offset left its range: the next window starts afresh
  // (sheared: y first, whose offset moves x by the tilt and the x velocity by its rate)
  const int dims[3] = {sheared ? 1 : 0, sheared ? (noff == 3 ? 2 : 0) : 1, sheared ? 0 : 2};
  const bool per_atom = state.atoms.per_atom() > 0;    // (read once)
  // (a serial run in a sheared box keeps what it writes: see undo_rounding)
  if (sheared && comm->nprocs == 1 && !state.atoms.stored()) state.atoms.keep_written();
  const bool written = state.atoms.keeps_written();
  for (int s = 0; s < ntotal; s++) {
    if (s + AHEAD < ntotal) ed.prefetch_particle(s + AHEAD);
    const int i = order[s] - myfirst;    // its owned atom, or none
    int8_t *stored = &offset[(size_t) s * noff];
    int dimg[3] = {0, 0, 0};
    double w[9];
    ed.state(s, T1, w, w + 3, w + 6);
    for (int m = 0; m < noff; m++) {
      const int d = dims[m];
      int off = stored[d];
      double tilt = 0.0;    // (sheared: the box's x extent at the atom's height, see FarWrap)
      if (sheared && d == 0) {
        if (stored[1]) shear_view(stored[1], w);
        tilt = (w[1] - domain->boxlo[1]) * (domain->xy / domain->prd[1]);
      }
      w[d] = wrap.written(d, w[d], off, tilt);
      dimg[d] = off - stored[d];
      if (off < -OFFSET_MAX || off > OFFSET_MAX) offsets_full = true;
      stored[d] = (int8_t) std::max(-OFFSET_MAX, std::min(OFFSET_MAX, off));
    }
    if (i < 0 || i >= nlocal) continue;
    hardsphere::shift_image(atom->image[i], dimg);
    memcpy(atom->x[i], w, 3 * sizeof(double));
    memcpy(atom->v[i], w + 3, 3 * sizeof(double));
    memcpy(atom->omega[i], w + 6, 3 * sizeof(double));
    if (written) state.atoms.store_written(i, w, w[3]);
    if (per_atom) keep_atom(i, s, stored, w);
  }
  valid = !offsets_full;
  if (offsets_full) state.epoch_due = true;
}

// what the fix keeps of owned atom i, core particle s, at the window's end (with its periods
// stored and its x and v as written, w): its stored state, last collision time and tallies
void HardsphereGatherWindow::keep_atom(int i, int s, const int8_t *stored, const double *w)
{
  double off[3] = {0.0, 0.0, 0.0};
  for (int d = 0; d < noff; d++) off[d] = stored[d];
  const int p = state.atoms.stored() ? ed.last_partner(s) : -1;
  state.take_back(i, s, off, p < 0 ? 0.0 : (double) otags[p], w, w + 3);
}

// LAMMPS's balance (and fix balance) take every position to the box's fractional coordinates
// and back, which may round it in the last place (FarWrap::match). Runs on several ranks put
// such atoms back from their stored states; a serial run keeps none, but its core still holds
// what this window wrote at the end of the last step (written_state), the same numbers. So a
// new epoch begins from the same positions whatever the number of ranks. (A serial run in a
// sheared box, rounded at every reneighboring, keeps what it wrote instead: take_back,
// HardsphereAtomStates::keep_written.)
void HardsphereGatherWindow::undo_rounding()
{
  if (comm->nprocs > 1 || sheared || !valid || !state.core_kept_by(this) || ed.size() != atom->nlocal)
    return;
  ntotal = atom->nlocal;
  order_by_id();
  if (!same_atoms || (int) offset.size() != noff * ntotal) return;
  const double T = state.epoch_time(update->ntimestep);    // (the last window's end)
  const hardsphere::FarWrap wrap(domain);
  for (int s = 0; s < ntotal; s++) {
    double w[9], *x = atom->x[order[s]];
    written_state(s, T, w);
    for (int d = 0; d < 3; d++) {
      int k;
      double c;
      if (x[d] != w[d] && wrap.match(d, x[d], w[d], k, c)) x[d] = c;
    }
  }
}

double HardsphereGatherWindow::memory_usage() const
{
  auto bytes = [](const auto &vec) { return (double) vec.capacity() * sizeof(vec[0]); };
  return bytes(sendbuf) + bytes(recvbuf) + bytes(order) + bytes(otags) + bytes(offset) + bytes(cmask);
}
