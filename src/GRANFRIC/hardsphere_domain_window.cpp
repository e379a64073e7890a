// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// clang-format off
/* ----------------------------------------------------------------------
   GRANFRIC: fix hardsphere/ed, domain-decomposed windows (keyword parallel domain).

   Each rank runs the window for its owned atoms plus copies ("ghosts", not LAMMPS's ghosts) of
   every other atom within a shell of width W = 2 D + 2 a_max around its owned atoms, where D
   bounds the path any atom travels in the window. Whether the result is exact is then checked,
   not assumed:
   - guard: every owned atom's path (an upper bound from its exact flights) stayed <= D, so
     every atom that touched an owned atom was in the shell;
   - history: a ghost influenced the owned atoms up to a time t* (it collided with one, or with
     a ghost that did before that one's own influence, ...); its collisions up to t* (partners,
     times, velocities and spins after each) must equal those its owner computed.
   If the earliest wrong event anywhere belonged to an owned atom, its partner was a ghost whose
   history up to that time differs from its owner's (which is right up to then) - detected; or a
   partner was missing - impossible after the guard. So when every rank passes, every owned
   trajectory is the exact one. Otherwise the ranks that found a conflict repair it with their
   neighbours: they widen their shells and redo their windows, and all compare again (see
   repair()); only a window that no repair fixes is redone gathered (every rank runs the whole
   system), which is exact by construction. The fix counts all of them.
------------------------------------------------------------------------- */

#include "hardsphere_domain_window.h"

#include "hardsphere_host.h"
#include "hardsphere_run_state.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>
#include <utility>

using namespace LAMMPS_NS;
using granfric::EDEvent;
using granfric::INF;
using granfric::Vec3;

static constexpr int NPACK = AtomRecordAt::SIZE;    // (doubles per atom in a message)
// per event of a published history: window time, partner tag (-1 - k: wall k), v and omega after
static constexpr int NEV = 8;

namespace {
// the shift (in periods) that brings coordinate x into [lo, hi] in a dimension, or false
bool image_in(double x, double lo, double hi, bool periodic, double L, int &s)
{
  for (int k : {0, -1, 1}) {
    if (k != 0 && !periodic) continue;
    const double y = x + k * L;
    if (y >= lo && y <= hi) {
      s = k;
      return true;
    }
  }
  return false;
}
double dot3(const double *a, const double *b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// squared speed of the core's motion (x-y in 2d)
template <int DIM>
double speed2(const double *v)
{
  return DIM == 2 ? v[0] * v[0] + v[1] * v[1] : dot3(v, v);
}

// v summed over all ranks, element by element (every rank holds the same length)
template <class T>
void sum_over_ranks(std::vector<T> &v, MPI_Datatype type, MPI_Comm world)
{
  if (v.empty()) return;
  std::vector<T> sum(v.size());
  MPI_Allreduce(v.data(), sum.data(), (int) v.size(), type, MPI_SUM, world);
  v.swap(sum);
}
}    // namespace

HardsphereDomainWindow::HardsphereDomainWindow(HardsphereRunState &r, double reach_, bool check) :
    Pointers(r.instance()), state(r), ed(r.ed), reach(reach_), check_windows(check)
{
}

bool HardsphereDomainWindow::run(double t0, double dt)
{
  nlocal = atom->nlocal;
  dim = domain->dimension;
  step = dt;
  received = 0;
  base = state.core_options();
  if (!state.core_kept_by(this)) valid = false;
  state.core_used_by(this);
  epoch_now = new_epoch(t0);
  T0 = state.window_start();
  T1 = state.window_end();
  bound_reach(dt);
  factor = own_factor;
  rounds = nredone = 0;
  all_widened = false;
  kick_from = state.kick_counters();
  kplan.clear();
  if (!state.kicks.empty()) kplan = state.plan_kicks(t0, dt);
  make_regions(false);
  send_copies();
  simulate(dt);
  publish_histories();
  long global[5];
  bool ok = checked(global, false);
  double *totals = state.totals;
  totals[HardsphereRunState::STEP_CONFLICTS] = (double) (global[0] + global[1]);
  totals[HardsphereRunState::CONFLICTS] += totals[HardsphereRunState::STEP_CONFLICTS];
  // (check no keeps a conflicting window: a wrong result, to show what the check is for)
  // A rank whose core failed (global[1] counts it beside the guard's failures, global[2]) is
  // not repaired: a core fails at the event cap, whose cause (atoms far too fast, a collapse)
  // every widened shell would meet again, window after window. The gathered redo is exact and
  // reports it, or runs the window if the cap was only this rank's.
  if (!ok && check_windows && global[1] == global[2]) ok = repair(dt, global[2] > 0);
  if (!ok && check_windows) {
    state.rewind_kicks(kick_from);
    valid = false;
    widen = std::min(64.0, 2.0 * widen);
    return false;
  }
  // a rank that widened keeps its shell for the next windows and narrows it slowly while they
  // pass (in dense gases momentum runs along chains of touching grains much faster than v_max:
  // the shells near them adapt to that instead of failing window after window)
  own_factor = factor > own_factor ? std::min(64.0, factor) : std::max(1.0, 0.99 * own_factor);
  commit();
  sum_statistics();
  // the core is kept for the next window (it then starts at this window's end)
  valid = true;
  widen = all_widened ? std::min(64.0, 2.0 * widen) : std::max(1.0, widen * 0.99);
  state.keep_rows(stag, smask);    // (the collisions this rank booked)
  sowned_prev.assign(sowned.begin(), sowned.end());
  return true;
}

// this rank's window with the copies it received: the core loaded, advanced, guarded; the
// influence times of its copies
void HardsphereDomainWindow::simulate(double dt)
{
  find_copies();
  load_core();
  watch_events();
  core_failed = !advance();
  guard_failed = !core_failed && !guard(dt);
  ed.track_fast(INF);
  influence_times();
}

// did every rank pass its check? global: the conflicts, the ranks whose core or guard failed,
// those whose guard failed, over all ranks, the doubles received so far (the fix's count) and
// the ranks that redid their windows in this round (redid: this one did; counted in nredone);
// after conflicts each rank learns whether a copy of one of its atoms was among them
bool HardsphereDomainWindow::checked(long *global, bool redid)
{
  const bool fail = core_failed || guard_failed;
  conflicts_here = 0;
  blame.assign(comm->nprocs, 0);
  if (!fail) conflicts_here = compare_histories();
  long local[5] = {conflicts_here, fail ? 1 : 0, guard_failed ? 1 : 0, received, redid ? 1 : 0};
  MPI_Allreduce(local, global, 5, MPI_LONG, MPI_SUM, world);
  state.totals[HardsphereRunState::STEP_COMM] = (double) global[3];
  nredone += global[4];
  blamed_here = false;
  if (global[0] == 0) return global[1] == 0;
  blamed.resize(comm->nprocs);
  MPI_Alltoall(blame.data(), 1, MPI_INT, blamed.data(), 1, MPI_INT, world);
  blamed_here = std::find(blamed.begin(), blamed.end(), 1) != blamed.end();
  return false;
}

// ------------------------------------------------ repair a window with conflicts
// Without gathering it: each rank that found a conflict (or whose core failed), and the owner
// of each copy in conflict, widens its shell twofold and redoes its window, and so does every
// rank whose atoms it then receives as copies (only those publish the histories of the atoms
// it newly needs); all others keep theirs and only compare again, against the histories now
// published. Rounds go on until no
// rank finds a conflict. The check's argument holds for whatever mix of first and repeated
// windows the ranks then hold: the earliest wrong event anywhere would be found by the rank
// that owns it. A guard failure (an atom that went too far may have reached a rank without a
// copy of it) makes every rank widen and redo. False: not repaired in MAX_ROUNDS rounds.
bool HardsphereDomainWindow::repair(double dt, bool everyone)
{
  all_widened = everyone;
  while (rounds < MAX_ROUNDS) {
    rounds++;
    const bool widen = everyone || conflicts_here > 0 || blamed_here || core_failed || guard_failed;
    if (widen) factor *= 2.0;
    make_regions(widen);
    send_copies();
    bool redo = widen;    // (or it sends atoms to a rank that widened)
    for (size_t m = 0; m < to_dest.size(); m++)
      redo = redo || (reg[to_dest[m]].widened && to_start[m + 1] > to_start[m]);
    if (redo) {
      valid = false;    // (a core built afresh from the window's start)
      simulate(dt);
    }
    publish_histories();
    long global[5];
    if (checked(global, redo)) return true;
    everyone = global[2] > 0;
    all_widened = all_widened || everyone;
  }
  return false;
}

// ------------------------------------------------ a new epoch?
// when the fix says so, or when anything other than this fix changed atoms since the last
// window (an atom that does not hold what was written, a new atom, one fewer): all ranks alike,
// as a serial run decides. A new epoch takes every atom from LAMMPS as it is.
bool HardsphereDomainWindow::new_epoch(double t0)
{
  int due = state.epoch_starts() || atom->natoms != last_natoms ? 1 : 0;
  const double start = state.window_start();
  const hardsphere::FarWrap wrap(domain);
  if (!due) due = state.atoms.states_hold(nlocal, start, state.settings.gravity, wrap) ? 0 : 1;
  MPI_Allreduce(MPI_IN_PLACE, &due, 1, MPI_INT, MPI_MAX, world);
  last_natoms = atom->natoms;
  if (!due) return false;
  state.begin_epoch(t0);
  state.atoms.clear_periods(nlocal);
  return true;
}

// ------------------------------------------------ the reach D and the shell W
// speed bound: all of an atom's kinetic energy as translation, plus what a vibrating wall can
// add (twice its largest speed); one pass over the atoms also gives this rank's bounding box,
// for the regions
void HardsphereDomainWindow::bound_reach(double dt)
{
  const double *xa = nlocal > 0 ? atom->x[0] : nullptr, *va = nlocal > 0 ? atom->v[0] : nullptr;
  const double *wa = nlocal > 0 ? atom->omega[0] : nullptr;
  const double *radius = atom->radius;
  // (the largest shape factor of the types: every atom's spin energy bounded as its type's)
  const double q = *std::max_element(base.shape.begin() + 1, base.shape.end());
  double mx[2] = {0.0, 0.0};
  for (int d = 0; d < 3; d++) {
    mybb[d] = d < dim ? INF : 0.0;    // (nothing moves in z in 2d)
    mybb[3 + d] = d < dim ? -INF : 0.0;
  }
  // (LAMMPS keeps x, v and omega contiguous, 3 per atom: the pass indexes them directly; in 2d
  // the core moves in x-y and spins about z only: the other components play no part. The
  // running extremes live in locals, which the compiler keeps in registers)
  auto bound_pass = [&](auto dims) {
    constexpr int DIM = decltype(dims)::value;
    double e2 = 0.0, amax = 0.0, lo[3] = {INF, INF, INF}, hi[3] = {-INF, -INF, -INF};
    for (int i = 0; i < nlocal; i++) {
      const double *xi = xa + 3 * i, *vi = va + 3 * i, *wi = wa + 3 * i;
      const double w2 = DIM == 2 ? wi[2] * wi[2] : dot3(wi, wi);
      e2 = std::max(e2, speed2<DIM>(vi) + q * radius[i] * radius[i] * w2);
      amax = std::max(amax, radius[i]);
      for (int d = 0; d < DIM; d++) {
        lo[d] = std::min(lo[d], xi[d]);
        hi[d] = std::max(hi[d], xi[d]);
      }
    }
    mx[0] = e2;
    mx[1] = amax;
    for (int d = 0; d < DIM; d++) {
      mybb[d] = lo[d];
      mybb[3 + d] = hi[d];
    }
  };
  if (dim == 2)
    bound_pass(std::integral_constant<int, 2>());
  else
    bound_pass(std::integral_constant<int, 3>());
  mx[0] = std::sqrt(mx[0]);    // (the root of the largest: the largest root, exactly)
  MPI_Allreduce(mx, gmx, 2, MPI_DOUBLE, MPI_MAX, world);
  vwall = 0.0;
  for (const auto &w : base.walls)
    vwall = std::max(vwall, w.speed_bound());
  g = norm(base.gravity);
  D = reach * widen * (gmx[0] + 2.0 * vwall) * dt + 0.5 * g * dt * dt;
}

// the shell that holds every atom able to reach an owned atom when atoms travel up to D
// (f = 1), and f times that (a repair's wider shells: they grow even where nothing moves fast,
// as along a chain of touching grains)
double HardsphereDomainWindow::shell(double f) const
{
  return f * (2.0 * D + 2.0 * gmx[1] * (1.0 + 1e-12) + 1e-12 * D);
}

// ------------------------------------------------ every rank's region (owned box + its W)
// (widened: this rank's shell has just widened, in a repair)
void HardsphereDomainWindow::make_regions(bool widened)
{
  const int nprocs = comm->nprocs;
  W = shell(factor);
  double mine[8];
  std::copy_n(mybb, 6, mine);
  mine[6] = W;
  mine[7] = widened ? 1.0 : 0.0;
  std::vector<double> all(8 * nprocs);
  MPI_Allgather(mine, 8, MPI_DOUBLE, all.data(), 8, MPI_DOUBLE, world);
  bb.resize(6 * nprocs);
  reg.resize(nprocs);
  for (int r = 0; r < nprocs; r++) {
    std::copy_n(&all[8 * r], 6, &bb[6 * r]);
    reg[r].W = all[8 * r + 6];
    reg[r].widened = all[8 * r + 7] != 0.0;
  }
  for (int r = 0; r < nprocs; r++)
    for (int d = 0; d < 3; d++) {
      Region &R = reg[r];
      R.lo[d] = bb[6 * r + d] - R.W;
      R.hi[d] = bb[6 * r + 3 + d] + R.W;
      R.whole[d] = false;
      if (d >= dim) {
        R.whole[d] = true;
      } else if (domain->periodicity[d]) {
        R.whole[d] = R.hi[d] - R.lo[d] >= domain->prd[d];
      } else {
        R.lo[d] = std::max(R.lo[d], domain->boxlo[d] - R.W);
        R.hi[d] = std::min(R.hi[d], domain->boxhi[d] + R.W);
      }
    }
}

// is x inside region R (at the image shift s, in periods per dimension)?
bool HardsphereDomainWindow::inside(const Region &R, const double *x, int *s) const
{
  for (int d = 0; d < 3; d++) {
    s[d] = 0;
    if (R.whole[d]) continue;
    if (!image_in(x[d], R.lo[d], R.hi[d], domain->periodicity[d], domain->prd[d], s[d]))
      return false;
  }
  return true;
}

// ------------------------------------------------ send the atoms others need
// Each atom goes to the ranks whose regions it lies in, and to no other: a rank receives only
// its neighbours' boundary atoms, whatever the number of ranks.
// (the test of inside() without the image shift: per other rank with atoms, the dimensions its
// region does not cover whole, each with its interval and period, 0 if not periodic. A
// periodic coordinate is brought to the interval's period by one shift either way, as inside()
// tries x - L, x and x + L; the span has a margin of rounding, so that an atom the receiver's
// inside() accepts is always sent (it drops what it does not need). One test at a time over
// all atoms: straight-line code per atom)
void HardsphereDomainWindow::send_copies()
{
  struct Test {
    int rank = 0, nd = 0, dims[3];
    double lo[3], span[3], L[3];
  };
  std::vector<Test> tests;
  for (int r = 0; r < comm->nprocs; r++) {
    if (r == comm->me || bb[6 * r] > bb[6 * r + 3]) continue;
    Test T;
    T.rank = r;
    for (int d = 0; d < 3; d++) {
      if (reg[r].whole[d]) continue;
      T.dims[T.nd] = d;
      T.lo[T.nd] = reg[r].lo[d];
      T.L[T.nd] = domain->periodicity[d] ? domain->prd[d] : 0.0;
      T.span[T.nd] = reg[r].hi[d] - reg[r].lo[d] +
          1e-9 * (std::fabs(reg[r].lo[d]) + std::fabs(reg[r].hi[d]) + T.L[T.nd]);
      T.nd++;
    }
    tests.push_back(T);
  }
  // (the atoms for each other rank in a list of their own, in ascending order; sent: the union)
  const double *xa = nlocal > 0 ? atom->x[0] : nullptr;
  sent.assign(nlocal, 0);
  char *sd = sent.data();
  to_rank.clear();
  to_start.assign(1, 0);
  to_dest.clear();
  for (const Test &T : tests) {
    for (int i = 0; i < nlocal; i++) {
      bool in = true;
      for (int j = 0; j < T.nd; j++) {
        double u = xa[3 * i + T.dims[j]] - T.lo[j];
        u -= u >= T.L[j] ? T.L[j] : 0.0;    // (L = 0: no shift, and u >= 0 is required)
        u += u < 0.0 ? T.L[j] : 0.0;
        in &= u >= 0.0 && u <= T.span[j];
      }
      if (in) to_rank.push_back(i);
      sd[i] |= (char) in;
    }
    to_start.push_back((int) to_rank.size());
    to_dest.push_back(T.rank);
  }
  sendlist.clear();    // (ascending)
  for (int i = 0; i < nlocal; i++)
    if (sent[i]) sendlist.push_back(i);
  // each sent atom's record once, then copied to every rank that gets it
  std::vector<double> &rec = srec;
  rec.resize(sendlist.size() * NPACK);    // (about as many as the last window's: little to fill)
  send_index.assign(nlocal, -1);
  for (size_t k = 0; k < sendlist.size(); k++) {
    state.atom_record(sendlist[k], !epoch_now).write(&rec[k * NPACK]);
    send_index[sendlist[k]] = (int) k;
  }
  scounts.assign(comm->nprocs, 0);
  dsend.resize(to_rank.size() * NPACK);    // (every entry is set below)
  for (size_t m = 0; m < to_dest.size(); m++) {
    scounts[to_dest[m]] = (to_start[m + 1] - to_start[m]) * NPACK;
    for (int k = to_start[m]; k < to_start[m + 1]; k++)
      std::copy_n(&rec[(size_t) send_index[to_rank[k]] * NPACK], NPACK, &dsend[(size_t) k * NPACK]);
  }
  received += exchange(dsend, drecv);
}

// Each rank's buffer for every other rank (dsend-like: the parts for ranks in ascending order,
// scounts doubles each) delivered: recv holds what the others sent to this rank, in rank order,
// rcounts and rdispls say where each rank's part lies. Returns the doubles received.
long HardsphereDomainWindow::exchange(const std::vector<double> &send, std::vector<double> &recv)
{
  const int nprocs = comm->nprocs;
  rcounts.resize(nprocs);
  rdispls.resize(nprocs);
  sdispls.resize(nprocs);
  MPI_Alltoall(scounts.data(), 1, MPI_INT, rcounts.data(), 1, MPI_INT, world);
  int total = 0, stotal = 0;
  for (int p = 0; p < nprocs; p++) {
    rdispls[p] = total;
    total += rcounts[p];
    sdispls[p] = stotal;
    stotal += scounts[p];
  }
  recv.resize(total);
  MPI_Alltoallv(send.data(), scounts.data(), sdispls.data(), MPI_DOUBLE, recv.data(),
                rcounts.data(), rdispls.data(), MPI_DOUBLE, world);
  return total;
}

// ------------------------------------------------ the copies this rank needs
// each copy's record in drecv and its image shift
void HardsphereDomainWindow::find_copies()
{
  const Region &R = reg[comm->me];
  gsrc.clear();
  gshift.clear();
  int s3[3];
  if (nlocal > 0)
    for (int p = 0; p < comm->nprocs; p++) {
      if (p == comm->me) continue;
      for (int k = rdispls[p]; k < rdispls[p] + rcounts[p]; k += NPACK) {
        if (!inside(R, &drecv[k + AtomRecordAt::XL], s3)) continue;
        gsrc.push_back(k);
        gshift.insert(gshift.end(), s3, s3 + 3);
      }
    }
  nghost = (int) gsrc.size();
}

// the ID of atom a of this window: owned (a < nlocal), or a copy
long HardsphereDomainWindow::tag_of(int a) const
{
  return a < nlocal ? (long) atom->tag[a] : (long) drecv[gsrc[a - nlocal] + AtomRecordAt::TAG];
}

// and its group mask
int HardsphereDomainWindow::mask_of(int a) const
{
  return a < nlocal ? atom->mask[a] : (int) drecv[gsrc[a - nlocal] + AtomRecordAt::MASK];
}

// The atoms of this window in the order of their IDs: slots are given in that order, so that
// the window does not depend on the order in which LAMMPS stores the atoms (which differs
// between a run and its continuation from a restart file). LAMMPS reorders atoms only when it
// reneighbors: the order of the last window usually still holds.
void HardsphereDomainWindow::order_by_id()
{
  const int n = nlocal + nghost;
  // (n indices below n with increasing IDs: the sorted order, each atom once)
  bool same = (int) aorder.size() == n;
  for (int k = 0; same && k < n; k++)
    same = aorder[k] < n && (k == 0 || tag_of(aorder[k - 1]) < tag_of(aorder[k]));
  if (same) return;
  aorder.resize(n);
  for (int a = 0; a < n; a++) aorder[a] = a;
  sort_by_id(aorder);
}

void HardsphereDomainWindow::sort_by_id(std::vector<int> &atoms)
{
  // usually (IDs below 2^32) each atom's ID and index packed in one integer, sorted as numbers:
  // several times cheaper than a sort that reads the IDs through the atom arrays
  const size_t n = atoms.size();
  akeys.resize(n);
  bool packed = true;
  for (size_t k = 0; k < n; k++) {
    const long t = tag_of(atoms[k]);
    packed = packed && t >= 0 && t < (1L << 32);
    akeys[k] = (uint64_t) t << 32 | (uint32_t) atoms[k];
  }
  if (!packed) {
    std::sort(atoms.begin(), atoms.end(), [&](int a, int b) { return tag_of(a) < tag_of(b); });
    return;
  }
  std::sort(akeys.begin(), akeys.end());
  for (size_t k = 0; k < n; k++) atoms[k] = (int) (akeys[k] & 0xffffffffu);
}

// atom a of this window: an owned atom (a < nlocal), or a copy as its owner sent it
AtomRecord HardsphereDomainWindow::record_of(int a) const
{
  if (a < nlocal) return state.atom_record(a, !epoch_now);
  return AtomRecord::read(&drecv[gsrc[a - nlocal]]);
}

// the frame shift of atom a (off: its record's periods) in this rank's core: its stored
// position lies that many periods below where this rank's region sees it (the copy's image
// shift less its periods)
void HardsphereDomainWindow::frame_of(int a, const double *off, int *f) const
{
  const int *gs = a < nlocal ? nullptr : &gshift[3 * (a - nlocal)];
  for (int d = 0; d < 3; d++) f[d] = framed[d] ? (gs ? gs[d] : 0) - (int) off[d] : 0;
}

// the dimensions in which frame_of() gives shifts: periodic ones in which the cell grid does
// not span the whole length (after grid_whole is set)
void HardsphereDomainWindow::set_framed()
{
  for (int d = 0; d < 3; d++) framed[d] = d < dim && !grid_whole[d] && domain->periodicity[d];
}

// does slot sl hold atom a as its record says (state, body, frame f, which this sets, and last
// partner), bit for bit? An owned atom is read where the fix keeps it, without a record.
bool HardsphereDomainWindow::slot_holds(int a, int sl, int *f) const
{
  const auto p = std::as_const(ed).particle(sl);
  if (a >= nlocal) {
    const AtomRecord in = record_of(a);
    frame_of(a, in.off, f);
    return ed.present(sl) && in.held_by(p) && links_held(sl, f, in.partner, in.poff);
  }
  using XS = HardsphereAtomStates;
  const double *xs = state.atoms.state(a);
  frame_of(a, xs + XS::XS_OFF, f);
  return ed.present(sl) &&
      holds_atom(p, xs + XS::XS_X, xs + XS::XS_V, xs[XS::XS_T], xs[XS::XS_TLAST], atom->omega[a],
                 atom->radius[a], atom->rmass[a], (double) atom->type[a]) &&
      links_held(sl, f, xs[XS::XS_PARTNER], xs + XS::XS_POFF);
}

// does slot sl have the frame f, and the last partner of the given ID (0: none) with image
// shift poff, where that partner has a slot here (partner_slot)? (stag and slot_of_tag map
// slots and IDs both ways, so the slot's partner is the atom's when it carries that ID)
bool HardsphereDomainWindow::links_held(int sl, const int *f, double partner, const double *poff) const
{
  const int ps = ed.last_partner(sl);
  if (ps >= 0 ? stag[ps] != (long) partner : partner > 0.0 && slot_of_tag.get((long) partner) >= 0)
    return false;
  const int *fs = ed.frame(sl), *po = ed.last_offset(sl);
  for (int d = 0; d < 3; d++)
    if ((fs ? fs[d] : 0) != f[d] || (ps >= 0 && po[d] != (int) poff[d])) return false;
  return true;
}

// the slot of the last partner of atom r here (-1: none, or not here)
int HardsphereDomainWindow::partner_slot(const AtomRecord &r) const
{
  return r.partner > 0.0 ? slot_of_tag.get((long) r.partner) : -1;
}

// ------------------------------------------------ the local system: kept, or afresh
// The core of the last window is kept when its cell grid still covers this window's region and
// nothing else changed; its slots are matched to this window's atoms by ID. Each atom is taken
// as its record says (its owner's stored state, or the one this rank left for an owned atom);
// one whose state, frame or last partner differs from its slot's is predicted afresh
// (ed.changed), slots of atoms no longer here are emptied, new atoms fill empty slots. Owned
// atoms arrive as this rank left them, so mostly only the copies that lacked a partner, or
// entered the region, are predicted again. A core built afresh continues the stored states
// too (start_at), except at the start of an epoch. Either way the predictions are those the
// owners' cores hold, bit for bit.
void HardsphereDomainWindow::load_core()
{
  granfric::EDOptions o = base;
  // every rank takes the cell width of the whole system, not that of its region with its
  // empty margins (cells: neighbour lists of copies would be rebuilt every window)
  o.neighbours = granfric::EDOptions::CELLS;
  if (dim == 2 && domain->prd[0] * domain->prd[1] > 0.0)
    o.cell_width = granfric::EventDriven::auto_cell_width(
        2, 2.0 * gmx[1] * (1.0 + 1e-10), (double) atom->natoms / (domain->prd[0] * domain->prd[1]));
  repredicted = owned_changed = 0;
  keep = !epoch_now && can_keep(o);
  if (keep)
    keep_core();
  else
    fresh_core(o);
}

// whether the last window's core covers this window (its grid holds the region, its slots
// suffice); sets every atom's slot (inslot) and, with the grid kept, o's grid
bool HardsphereDomainWindow::can_keep(granfric::EDOptions &o)
{
  const Region &R = reg[comm->me];
  bool ok = valid && gmx[1] <= ed.cell_radius() && nlocal + nghost > 0;
  for (int d = 0; d < 3 && ok; d++) {
    ok = R.whole[d] == grid_whole[d];
    if (!ok || R.whole[d] || !domain->periodicity[d]) continue;
    ok = R.lo[d] >= grid_lo[d] && R.hi[d] <= grid_hi[d];
    o.lo[d] = grid_lo[d];
    o.hi[d] = grid_hi[d];
    o.periodic[d] = false;
    o.open[d] = true;
    o.period[d] = domain->prd[d];
  }
  ok = ok && ed.configured_as(o, atom->ntypes, state.law_table());
  inslot.resize(nlocal + nghost);    // (set for every atom before use)
  if (!ok) return false;
  if (++stamp == INT32_MAX) return false;
  // (locals: stores through int pointers could otherwise alias the stamp)
  const int st = stamp;
  int *seen = sseen.data(), *ins = inslot.data();
  bool twice = false;    // (an atom twice cannot happen: owned once, copied once)
  long matched = 0;      // atoms that have a slot
  const int nguess = std::min(nlocal, (int) lslot.size());
  for (int a = 0; a < nlocal + nghost; a++) {
    // (an owned atom mostly has the index, and so the slot, it had in the last window)
    const long t = tag_of(a);
    const int guess = a < nguess ? lslot[a] : -1;
    const int sl = guess >= 0 && guess < (int) stag.size() && stag[guess] == t ? guess : slot_of_tag.get(t);
    ins[a] = sl;
    if (sl < 0) continue;
    matched++;
    twice |= seen[sl] == st;
    seen[sl] = st;
  }
  // the slots of atoms no longer here are emptied first, so every atom finds one if the slots
  // outnumber the atoms
  if (twice || nlocal + nghost > ed.size()) return false;
  // The slots of atoms no longer here, in ascending order. They are nearly always the last
  // window's copies (an owned atom that leaves the rank stays near it, a copy here): those are
  // looked at first, and all slots only if that does not find as many as there are occupied
  // slots without an atom.
  const long unmatched = (long) (ed.size() - free_slots.size()) - matched;
  rm.clear();
  for (int sl : cslot)
    if (stag[sl] >= 0 && seen[sl] != st) rm.push_back(sl);
  if ((long) rm.size() == unmatched) {
    std::sort(rm.begin(), rm.end());
  } else {
    rm.clear();
    for (int sl = 0; sl < ed.size(); sl++)
      if (stag[sl] >= 0 && seen[sl] != st) rm.push_back(sl);
  }
  return true;
}

// the kept core, its slots matched to this window's atoms (can_keep)
void HardsphereDomainWindow::keep_core()
{
  set_framed();
  for (int sl : rm) {
    ed.remove(sl);    // an atom no longer in this rank's region
    slot_of_tag.erase(stag[sl]);
    stag[sl] = -1;
    smask[sl] = 0;
    free_slots.push_back(sl);
  }
  // (first every atom's slot, so that last partners can be found; new atoms take the free
  // slots in the order of their IDs, the others keep theirs: the slots do not depend on the
  // order in which LAMMPS stores the atoms)
  const int n = nlocal + nghost;
  anew.clear();
  for (int a = 0; a < n; a++)
    if (inslot[a] < 0) anew.push_back(a);
  sort_by_id(anew);
  for (int a : anew) {
    const long t = tag_of(a);
    const int sl = free_slots.back();
    free_slots.pop_back();
    slot_of_tag.set(t, sl);
    stag[sl] = t;
    inslot[a] = sl;
  }
  cslot.clear();
  sowned.assign(ed.size(), 0);
  lslot.resize(nlocal);
  for (int a = 0; a < n; a++) {
    const int sl = inslot[a];
    int f[3];
    if (!slot_holds(a, sl, f)) {
      const AtomRecord in = record_of(a);
      const int ps = partner_slot(in);
      auto p = ed.particle(sl);
      in.to_particle(p);
      p.t_last = in.tlast;
      ed.set_frame(sl, f);
      ed.changed(sl, true);
      const int poff[3] = {(int) in.poff[0], (int) in.poff[1], (int) in.poff[2]};
      ed.set_last_partner(sl, ps, poff);
      repredicted++;
      if (a < nlocal && sowned_prev[sl]) owned_changed++;
    }
    smask[sl] = mask_of(a);
    if (a < nlocal) {
      sowned[sl] = 1;
      lslot[a] = sl;
    } else {
      cslot.push_back(sl);
    }
  }
}

// afresh: the atoms in slots 0..n-1 in the order of their IDs, then empty slots for later
// windows; the cell grid covers this window's region and a margin W
void HardsphereDomainWindow::fresh_core(granfric::EDOptions &o)
{
  order_by_id();
  const Region &R = reg[comm->me];
  // (a rank that owns no atoms has no region and receives no copies: its empty core still
  // runs the window, for the kicks every rank draws, on a grid of the box)
  const bool empty = nlocal == 0;
  cslot.clear();
  for (int d = 0; d < 3; d++) {
    grid_whole[d] = R.whole[d];
    if (R.whole[d] || !domain->periodicity[d]) continue;
    grid_lo[d] = empty ? domain->boxlo[d] : R.lo[d] - W;
    grid_hi[d] = empty ? domain->boxhi[d] : R.hi[d] + W;
    o.lo[d] = grid_lo[d];
    o.hi[d] = grid_hi[d];
    o.periodic[d] = false;
    o.open[d] = true;
    o.period[d] = domain->prd[d];
  }
  set_framed();
  state.configure_core(o, false);
  const int n = nlocal + nghost, ns = n + n / 16 + 64;
  ed.resize(ns);
  stag.assign(ns, -1);
  smask.assign(ns, 0);
  sowned.assign(ns, 0);
  sseen.assign(ns, 0);
  stamp = 0;
  slot_of_tag.reset(ns);
  free_slots.clear();
  lslot.resize(nlocal);
  for (int e = 0; e < ns; e++) {
    auto p = ed.particle(e);
    if (e >= n) {
      ed.remove(e);
      free_slots.push_back(ns - 1 - (e - n));
      continue;
    }
    const int a = aorder[e];
    const AtomRecord in = record_of(a);
    in.to_particle(p);
    p.t_last = in.tlast;
    int f[3];
    frame_of(a, in.off, f);
    ed.set_frame(e, f);
    stag[e] = (long) in.tag;
    smask[e] = (int) in.mask;
    if (a < nlocal) {
      sowned[e] = 1;
      lslot[a] = e;
    } else {
      cslot.push_back(e);
    }
    slot_of_tag.set(stag[e], e);
  }
  for (int e = 0; e < n && !epoch_now; e++) {
    const AtomRecord in = record_of(aorder[e]);
    const int poff[3] = {(int) in.poff[0], (int) in.poff[1], (int) in.poff[2]};
    ed.set_last_partner(e, partner_slot(in), poff);
  }
  ed.set_clock(state.epoch_clock);
  try {
    if (epoch_now)
      ed.start();
    else
      ed.start_at(T0);
  } catch (std::exception &e) {
    state.core_failed(e, false);
  }
  repredicted = n;
  state.totals[HardsphereRunState::QUEUE_REBUILDS] += 1.0;
}

// ------------------------------------------------ the events that matter here
// those of the copies (influence times, histories compared) and of the sent atoms (histories
// published); a collision of two other owned atoms changes no influence time (owned atoms have
// t* = infinity) and is published by nobody. The watched slots in a list, the copies first,
// and each one's place in it: the influence times and event lists are kept for these only;
// widx is -1 for every other slot.
void HardsphereDomainWindow::watch_events()
{
  const int n = ed.size();
  ed.set_accounting({stag.data(), sowned.data()});    // (both unchanged until the next window)
  watch.assign(n, 0);
  for (int e : wlist)
    if (e < (int) widx.size()) widx[e] = -1;    // (the last window's entries)
  widx.resize(n, -1);
  wlist.assign(cslot.begin(), cslot.end());
  for (int i : sendlist) wlist.push_back(lslot[i]);
  nwatch = (int) wlist.size();
  ncopy = (int) cslot.size();
  for (int k = 0; k < nwatch; k++) {
    watch[wlist[k]] = 1;
    widx[wlist[k]] = k;
  }
  history.clear();
  ed.record_events(&history, watch.data());
  if (state.check_overlaps && keep) {
    // a kept core continues an exact trajectory: the once-per-run overlap check is needed
    // only if something other than this fix changed atoms a rank had written back (all
    // ranks decide alike)
    long any = 0;
    MPI_Allreduce(&owned_changed, &any, 1, MPI_LONG, MPI_SUM, world);
    if (any == 0) state.check_overlaps = false;
  }
  state.report_overlaps(true);
}

// ------------------------------------------------ the window itself
// kicks at their exact times, with the momentum shift over the whole group (planned once for
// the window); false: the core failed (e.g. the event cap: a repair or the gathered redo tells
// whether it is real)
bool HardsphereDomainWindow::advance()
{
  // (the guard: who came near the speed bound)
  const double slim = D / step - 0.5 * step * g;
  s2lim = slim > 0.0 ? 0.999 * slim * slim : 0.0;
  ed.track_fast(s2lim);
  if (!state.kicks.empty()) {
    kick_tags.assign(stag.begin(), stag.end());
    state.schedule_kicks(kplan, kick_tags, smask);
  }
  state.record_collisions();
  bool ok = true;
  try {
    state.last = ed.advance_to(T1);
  } catch (std::exception &) {
    ok = false;
  }
  ed.record_events(nullptr);
  ed.record_collisions(nullptr);
  return ok;
}

// ------------------------------------------------ guard: no owned atom went too far
// An owned atom j that went further than D (path p > D) is harmless if it stayed out of reach
// of every rank r that did not receive it: its distance to r's owned atoms is at least
// W + p - D = p + D + 2 a_max (W: the shell of f = 1, which every rank's holds), more than it
// and any atom of r (path <= D, or harmless in turn) can close. A rank that did receive it
// compares its history instead.
double HardsphereDomainWindow::gap_to(const double *xi, int r) const
{
  double s2 = 0.0;
  for (int d = 0; d < dim; d++) {
    if (reg[r].whole[d]) continue;
    const double lo = bb[6 * r + d], hi = bb[6 * r + 3 + d];
    double best = INF;
    for (int k : {0, -1, 1}) {
      if (k != 0 && !domain->periodicity[d]) continue;
      const double y = xi[d] + k * domain->prd[d];
      best = std::min(best, std::max(0.0, std::max(lo - y, y - hi)));
    }
    s2 += best * best;
  }
  return std::sqrt(s2);
}

// owned atom i with the largest squared speed s2: false if it may have reached an atom that
// was not in its window
bool HardsphereDomainWindow::guard_atom(int i, double s2, double dt)
{
  const double p = ed.path_bound(s2, dt);
  if (p <= D) return true;
  int s3[3];
  for (int r = 0; r < comm->nprocs; r++) {
    if (r == comm->me || bb[6 * r] > bb[6 * r + 3]) continue;
    if (inside(reg[r], atom->x[i], s3)) continue;    // r has it: histories are compared
    if (gap_to(atom->x[i], r) < shell(1.0) + p - D) return false;
  }
  return true;
}

// Most atoms are far below the bound: the core lists those whose speed after a velocity change
// came near it (the threshold has a margin that leaves the borderline ones to the exact bound);
// an atom never listed is bounded by its speed at window time 0 (in LAMMPS's arrays until the
// write-back) or the threshold. (No atom starts at the threshold when reach * widen exceeds 1
// by the threshold's margin: gmx[0] bounds every atom's speed.)
bool HardsphereDomainWindow::guard(double dt)
{
  const double *va = nlocal > 0 ? atom->v[0] : nullptr;
  if (s2lim <= gmx[0] * gmx[0] * (1.0 + 1e-9)) {
    for (int i = 0; i < nlocal; i++) {
      const double s2 = dim == 2 ? speed2<2>(va + 3 * i) : speed2<3>(va + 3 * i);
      if (s2 >= s2lim && !guard_atom(i, s2, dt)) return false;
    }
  }
  if (ed.fast_list().empty()) return true;
  std::vector<int> atom_of(ed.size(), -1);
  for (int i = 0; i < nlocal; i++) atom_of[lslot[i]] = i;
  for (const auto &f : ed.fast_list())
    if (atom_of[f.first] >= 0 && !guard_atom(atom_of[f.first], f.second, dt)) return false;
  return true;
}

// ------------------------------------------------ influence times t* of the copies
// (per watched slot; every other slot is an owned atom: t* = infinity)
void HardsphereDomainWindow::influence_times()
{
  tstar.resize(nwatch);
  for (int k = 0; k < nwatch; k++) tstar[k] = k < ncopy ? -INF : INF;
  const int *wi = widx.data();
  double *ts = tstar.data();
  for (auto it = history.rbegin(); it != history.rend(); ++it) {
    if (it->j < 0) continue;
    const int ki = wi[it->i], kj = wi[it->j];
    if ((ki < 0 ? INF : ts[ki]) >= it->t && kj >= 0) ts[kj] = std::max(ts[kj], it->t);
    if ((kj < 0 ? INF : ts[kj]) >= it->t && ki >= 0) ts[ki] = std::max(ts[ki], it->t);
  }
}

// one event of particle e as published: time, partner tag or -1 - wall, v and omega after
void HardsphereDomainWindow::event_of(int e, int m, double *out) const
{
  const auto &h = history[m];
  const bool first = h.i == e;
  out[0] = h.t;
  out[1] = h.j < 0 ? (double) h.j : (double) stag[first ? h.j : h.i];
  const Vec3 &vv = first ? h.vi : h.vj, &ww = first ? h.wi : h.wj;
  vv.to(out + 2);
  ww.to(out + 5);
}

// ------------------------------------------------ publish the histories of sent atoms
// events per watched slot (pair and wall collisions, in time order), then each sent atom's list
// to the ranks it was sent to
void HardsphereDomainWindow::publish_histories()
{
  start.assign(nwatch + 1, 0);
  // (a watched partner's place in the list, or -1: a wall, or an owned atom nobody watches)
  auto place_of_j = [&](const EDEvent &h) { return h.j >= 0 ? widx[h.j] : -1; };
  for (const auto &h : history) {
    const int ki = widx[h.i], kj = place_of_j(h);
    if (ki >= 0) start[ki + 1]++;
    if (kj >= 0) start[kj + 1]++;
  }
  for (int k = 0; k < nwatch; k++) start[k + 1] += start[k];
  evlist.resize(start[nwatch]);    // (every entry is set below)
  fill.assign(start.begin(), start.end() - 1);
  for (int m = 0; m < (int) history.size(); m++) {
    const auto &h = history[m];
    const int ki = widx[h.i], kj = place_of_j(h);
    if (ki >= 0) evlist[fill[ki]++] = m;
    if (kj >= 0) evlist[fill[kj]++] = m;
  }
  // each sent atom's history (its ID, its event count, its events) once, then copied to every
  // rank that got the atom
  std::vector<double> &own = dsend;    // (as scratch: the records were sent)
  std::vector<size_t> &at = hist_at;
  at.assign(sendlist.size() + 1, 0);
  for (size_t k = 0; k < sendlist.size(); k++) {
    const int w = widx[lslot[sendlist[k]]];
    at[k + 1] = at[k] + 2 + (size_t) (start[w + 1] - start[w]) * NEV;
  }
  own.resize(at.back());    // (every entry is set below)
  for (size_t k = 0; k < sendlist.size(); k++) {
    const int e = lslot[sendlist[k]], w = widx[e];
    const int cnt = start[w + 1] - start[w];
    own[at[k]] = (double) stag[e];
    own[at[k] + 1] = (double) cnt;
    for (int m = 0; m < cnt; m++) event_of(e, evlist[start[w] + m], &own[at[k] + 2 + (size_t) m * NEV]);
  }
  scounts.assign(comm->nprocs, 0);
  hsend.clear();
  for (size_t m = 0; m < to_dest.size(); m++) {
    const size_t before = hsend.size();
    for (int k = to_start[m]; k < to_start[m + 1]; k++) {
      const size_t q = send_index[to_rank[k]];
      hsend.insert(hsend.end(), own.begin() + at[q], own.begin() + at[q + 1]);
    }
    scounts[to_dest[m]] = (int) (hsend.size() - before);
  }
  received += exchange(hsend, hrecv);
}

// ------------------------------------------------ compare where it mattered
// Exactly: a copy's events up to its influence time must be its owner's, bit for bit (the
// same stored states give the same predictions and collisions on every rank). A copy that went
// wrong (a partner it lacked) differs by a whole event or more. Returns the copies in conflict;
// blame (zeroed by the caller) marks their owners (either side may be the wrong one: an owned atom can miss a
// collision with a copy that went wrong here, which no check of this rank sees).
int HardsphereDomainWindow::compare_histories()
{
  // where each copy's published history starts in hrecv (-1: none; every copy's owner sent it),
  // and who published it
  published.assign(ncopy, -1);
  owner.resize(ncopy);
  for (int p = 0; p < comm->nprocs; p++) {
    if (p == comm->me) continue;
    for (size_t k = rdispls[p]; k < (size_t) (rdispls[p] + rcounts[p]);) {
      const long t = (long) hrecv[k];
      const int sl = slot_of_tag.get(t);
      if (sl >= 0 && widx[sl] >= 0 && widx[sl] < ncopy) {    // (a copy here)
        published[widx[sl]] = (long) k;
        owner[widx[sl]] = p;
      }
      k += 2 + (size_t) hrecv[k + 1] * NEV;
    }
  }
  int conflicts = 0;
  double mine[NEV];
  for (int c = 0; c < ncopy; c++) {
    const int e = cslot[c];
    if (tstar[c] == -INF) continue;
    const long k = published[c];
    if (k < 0) {
      conflicts++;    // cannot happen: every copy was sent, so its history was published
      continue;
    }
    const double *theirs = &hrecv[k + 2];
    const int ntheirs = (int) hrecv[k + 1];
    const int nmine = start[c + 1] - start[c];
    const double limit = tstar[c];
    bool same = true;
    for (int a = 0; same; a++) {
      const bool more_a = a < nmine && history[evlist[start[c] + a]].t <= limit;
      const bool more_b = a < ntheirs && theirs[(size_t) a * NEV] <= limit;
      if (!more_a && !more_b) break;
      if (more_a != more_b) {
        same = false;
        break;
      }
      event_of(e, evlist[start[c] + a], mine);
      const double *t = &theirs[(size_t) a * NEV];
      for (int k = 0; k < NEV && same; k++) same = mine[k] == t[k];
    }
    if (!same) {
      conflicts++;
      blame[owner[c]] = 1;
    }
  }
  return conflicts;
}

// ------------------------------------------------ commit the owned atoms
// their state at the window's end in LAMMPS's frame (see FarWrap::written), and their stored
// states for the next window, wherever the atoms go
void HardsphereDomainWindow::commit()
{
  double *xa = nlocal > 0 ? atom->x[0] : nullptr, *va = nlocal > 0 ? atom->v[0] : nullptr;
  double *wa = nlocal > 0 ? atom->omega[0] : nullptr;
  imageint *image = atom->image;
  const hardsphere::FarWrap wrap(domain);
  for (int i = 0; i < nlocal; i++) {
    const int e = lslot[i];
    double xe[3], off[3];
    ed.state(e, T1, xe, va + 3 * i, wa + 3 * i);
    const double *xs = state.atoms.state(i);
    int dimg[3] = {0, 0, 0};
    for (int d = 0; d < 3; d++) {
      int o = (int) xs[HardsphereAtomStates::XS_OFF + d];
      xa[3 * i + d] = wrap.written(d, xe[d], o);
      dimg[d] = o - (int) xs[HardsphereAtomStates::XS_OFF + d];
      off[d] = o;
    }
    hardsphere::shift_image(image[i], dimg);
    const int p = ed.last_partner(e);
    state.take_back(i, e, off, p < 0 ? 0.0 : (double) stag[p], xa + 3 * i, va + 3 * i);
  }
  state.atoms.written_at = T1;
}

// ------------------------------------------------ the statistics of all ranks
// (and the atoms predicted afresh, summed with them)
void HardsphereDomainWindow::sum_statistics()
{
  granfric::EDStats &last = state.last;
  const long events = last.global_events;    // (every rank processes every kick: no sum)
  std::vector<long> counts;
  std::vector<double> sums;
  last.flatten(counts, sums);
  counts.push_back(repredicted);
  counts.push_back(nghost);
  sum_over_ranks(counts, MPI_LONG, world);
  sum_over_ranks(sums, MPI_DOUBLE, world);
  last.unflatten(counts.data(), sums.data());
  long lmax = last.max_collisions_one_particle, gmax;
  MPI_Allreduce(&lmax, &gmax, 1, MPI_LONG, MPI_MAX, world);
  last.max_collisions_one_particle = gmax;
  last.global_events = events;
  state.totals[HardsphereRunState::STEP_PREDICTED] = (double) counts[counts.size() - 2];
  state.totals[HardsphereRunState::STEP_COPIES] = (double) counts.back();
}

double HardsphereDomainWindow::memory_usage() const
{
  auto bytes = [](const auto &vec) { return (double) vec.capacity() * sizeof(vec[0]); };
  return bytes(history) + bytes(srec) + bytes(dsend) + bytes(drecv) + bytes(hsend) + bytes(hrecv) + bytes(stag) +
      bytes(smask) + bytes(kick_tags) + (double) slot_of_tag.memory_bytes() + bytes(free_slots) + bytes(lslot) +
      bytes(sowned) + bytes(sowned_prev) + bytes(sseen) + bytes(sent) + bytes(inslot) +
      bytes(evlist) + bytes(cslot) + bytes(watch) + bytes(gsrc) + bytes(start) + bytes(fill) +
      bytes(gshift) + bytes(tstar) + bytes(published) + bytes(aorder) + bytes(sendlist) +
      bytes(wlist) + bytes(widx) + bytes(rm) + bytes(bb) + bytes(reg) + bytes(to_rank) +
      bytes(to_start) + bytes(to_dest) + bytes(send_index) + bytes(scounts) + bytes(sdispls) +
      bytes(hist_at);
}
