// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: fix hardsphere/ed's per-atom state (see hardsphere_atom_states.h)
------------------------------------------------------------------------- */

#include "hardsphere_atom_states.h"

#include "hardsphere_host.h"

#include "atom.h"
#include "domain.h"
#include "force.h"
#include "memory.h"

#include <algorithm>
#include <cstring>
#include <utility>

using namespace LAMMPS_NS;
using granfric::INF;

HardsphereAtomStates::HardsphereAtomStates(LAMMPS *lmp, bool stored, bool tc) : Pointers(lmp)
{
  if (stored) memory->create(xstate, 1, XS_SIZE, "hardsphere/ed:xstate");
  if (tc) memory->create(tlast, 1, "hardsphere/ed:tlast");
}

HardsphereAtomStates::~HardsphereAtomStates()
{
  memory->destroy(tlast);
  memory->destroy(atally);
  memory->destroy(xstate);
  memory->destroy(wrote);
}

void HardsphereAtomStates::keep_written()
{
  if (wrote) return;
  memory->create(wrote, 1, WR_SIZE, "hardsphere/ed:wrote");
  grow(atom->nmax);
}

void HardsphereAtomStates::request_tallies()
{
  if (atally) return;
  memory->create(atally, atom->nmax, NTALLY, "hardsphere/ed:atally");
  atally_n = 0;
  grow(atom->nmax);
}

// (new rows: no stored state, no collision yet, empty tallies)
void HardsphereAtomStates::grow(int nmax)
{
  if (tlast) {
    memory->grow(tlast, nmax, "hardsphere/ed:tlast");
    for (int i = tlast_n; i < nmax; i++) tlast[i] = -INF;
    tlast_n = std::max(tlast_n, nmax);
  }
  if (xstate) {
    memory->grow(xstate, nmax, XS_SIZE, "hardsphere/ed:xstate");
    for (int i = xstate_n; i < nmax; i++) xstate[i][XS_T] = xstate[i][XS_WX] = xstate[i][XS_WW] = NAN;
    xstate_n = std::max(xstate_n, nmax);
  }
  if (wrote) {
    memory->grow(wrote, nmax, WR_SIZE, "hardsphere/ed:wrote");
    for (int i = wrote_n; i < nmax; i++) wrote[i][WR_X] = NAN;
    wrote_n = std::max(wrote_n, nmax);
  }
  if (atally) {
    memory->grow(atally, nmax, NTALLY, "hardsphere/ed:atally");
    for (int i = atally_n; i < nmax; i++)
      for (int k = 0; k < NTALLY; k++) atally[i][k] = k == T_LAST ? -1.0 : 0.0;
    atally_n = std::max(atally_n, nmax);
  }
}

void HardsphereAtomStates::copy(int i, int j)
{
  if (tlast) tlast[j] = tlast[i];
  if (xstate) memcpy(xstate[j], xstate[i], XS_SIZE * sizeof(double));
  if (wrote) memcpy(wrote[j], wrote[i], WR_SIZE * sizeof(double));
  if (atally) memcpy(atally[j], atally[i], NTALLY * sizeof(double));
}

int HardsphereAtomStates::per_atom() const
{
  return (tlast ? 1 : 0) + (xstate ? XS_SIZE : 0) + (atally ? NTALLY : 0);
}

int HardsphereAtomStates::pack(int i, double *buf) const
{
  int m = 0;
  if (tlast) buf[m++] = tlast[i];
  if (xstate)
    for (int k = 0; k < XS_SIZE; k++) buf[m++] = xstate[i][k];
  if (atally)
    for (int k = 0; k < NTALLY; k++) buf[m++] = atally[i][k];
  return m;
}

int HardsphereAtomStates::unpack(int i, const double *buf)
{
  int m = 0;
  if (tlast) tlast[i] = buf[m++];
  if (xstate)
    for (int k = 0; k < XS_SIZE; k++) xstate[i][k] = buf[m++];
  if (wrote) wrote[i][WR_X] = NAN;
  if (atally)
    for (int k = 0; k < NTALLY; k++) atally[i][k] = buf[m++];
  return m;
}

double HardsphereAtomStates::memory_usage() const
{
  return (double) atom->nmax * sizeof(double) * (per_atom() + (wrote ? WR_SIZE : 0));
}

AtomRecord HardsphereAtomStates::record(int i, bool exact, double clock) const
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
  // (the last collision relative to the epoch's start)
  r.tlast = xs ? xs[XS_TLAST] : !tlast || tlast[i] == -INF ? -INF : tlast[i] - clock;
  r.mask = (double) atom->mask[i];
  r.partner = xs ? xs[XS_PARTNER] : 0.0;
  return r;
}

void HardsphereAtomStates::store_state(const granfric::EventDriven &ed, int i, int e,
                                       const double *off, double partner, const double *wx,
                                       const double *wv)
{
  const auto p = ed.particle(e);
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
    const double *w = atom->omega[i];
    for (int d = 0; d < 3; d++) {    // (element by element: copy_n of three called memcpy)
      xs[XS_WX + d] = wx[d];
      xs[XS_WV + d] = wv[d];
      xs[XS_WW + d] = w[d];
    }
    xs[XS_BODY] = atom->radius[i];
    xs[XS_BODY + 1] = atom->rmass[i];
    xs[XS_BODY + 2] = (double) atom->type[i];
  } else {
    xs[XS_WX] = NAN;    // (states_hold compares this first)
  }
}

void HardsphereAtomStates::store_tlast(const granfric::EventDriven &ed, int i, int e, double clock)
{
  const double t = ed.particle(e).t_last;
  tlast[i] = t == -INF ? -INF : t + clock;
}

void HardsphereAtomStates::store_tally(const granfric::EventDriven &ed, int i, int e, double clock)
{
  const auto &p = ed.particle_tally(e);
  double *a = atally[i];
  for (int k = 0; k < 6; k++) a[T_VIRIAL + k] = p.virial[k];
  a[T_COLL] = p.collisions;
  a[T_WALL] = p.wall_collisions;
  a[T_DETR] = p.dE_tr * force->mvv2e;
  a[T_DEROT] = p.dE_rot * force->mvv2e;
  a[T_DEWALL] = p.dE_wall * force->mvv2e;
  if (p.t_last > -INF) a[T_LAST] = clock + p.t_last;
}

bool HardsphereAtomStates::states_hold(int n, double T0, const double *g,
                                       const hardsphere::FarWrap &wrap)
{
  // (an atom that holds the x and v written at T0 passes at once: the full test would compute
  // them again from its stored state, with its periods as they are. The rows lie one after
  // another, as LAMMPS allocates per-atom arrays)
  // An atom whose spin or body (radius, mass, type) differs from what the window left (set,
  // fix adapt) does not hold: a serial run starts a new epoch for it too
  const bool written = T0 == written_at;
  const granfric::Vec3 gv(g[0], g[1], g[2]);
  const double *xa = n > 0 ? atom->x[0] : nullptr, *va = n > 0 ? atom->v[0] : nullptr;
  const double *wa = n > 0 ? atom->omega[0] : nullptr;
  const double *xs = n > 0 ? xstate[0] : nullptr;
  const double *radius = atom->radius, *rmass = atom->rmass;
  const int *type = atom->type;
  for (int i = 0; i < n; i++, xa += 3, va += 3, wa += 3, xs += XS_SIZE) {
    if (wa[0] != xs[XS_WW] || wa[1] != xs[XS_WW + 1] || wa[2] != xs[XS_WW + 2] ||
        radius[i] != xs[XS_BODY] || rmass[i] != xs[XS_BODY + 1] || type[i] != xs[XS_BODY + 2])
      return false;
    if (written && xa[0] == xs[XS_WX] && xa[1] == xs[XS_WX + 1] && xa[2] == xs[XS_WX + 2] &&
        va[0] == xs[XS_WV] && va[1] == xs[XS_WV + 1] && va[2] == xs[XS_WV + 2])
      continue;
    if (!state_holds(i, T0, gv, wrap)) return false;
  }
  return true;
}

bool HardsphereAtomStates::state_holds(int i, double T0, const granfric::Vec3 &g,
                                       const hardsphere::FarWrap &wrap)
{
  double *xs = xstate[i];
  if (std::isnan(xs[XS_T])) return false;
  const double *xa = atom->x[i], *va = atom->v[i];
  const granfric::Vec3 x(xs[XS_X], xs[XS_X + 1], xs[XS_X + 2]), v(xs[XS_V], xs[XS_V + 1], xs[XS_V + 2]);
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

void HardsphereAtomStates::clear_periods(int n)
{
  for (int i = 0; i < n; i++)
    for (int d = 0; d < 3; d++) xstate[i][XS_OFF + d] = 0.0;
}

void HardsphereAtomStates::note_positions(double now)
{
  if (!xstate || written_at == now) return;
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

void HardsphereAtomStates::undo_rounding(bool sheared, double pbc_xy, double xy, double u)
{
  if (!xstate && !(sheared && wrote)) return;
  const int n = atom->nlocal;
  if (n == 0) return;
  // (the rows lie one after another, as LAMMPS allocates per-atom arrays: what was written, in
  // the stored states or kept by a serial run, every stride doubles)
  const double *w = xstate ? xstate[0] + XS_WX : wrote[0] + WR_X;
  const int stride = xstate ? (int) XS_SIZE : (int) WR_SIZE;
  const int wv = xstate ? (int) XS_WV - XS_WX : (int) WR_VX - WR_X;
  double *x = atom->x[0], *v = atom->v[0];
  if (sheared) {
    const hardsphere::ShearWrap shear(domain, pbc_xy, xy, u);
    for (int i = 0; i < n; i++, w += stride, x += 3, v += 3) {
      const double wvx = w[wv];
      if (std::isnan(w[0]) || std::isnan(wvx)) continue;
      int k[3];
      double c[3];
      if (shear.unwrapped(x, v[0], w, wvx))
        x[0] = w[0], x[1] = w[1], x[2] = w[2];
      else if (shear.match(x, v[0], w, wvx, k, c, v[0]))
        x[0] = c[0], x[1] = c[1], x[2] = c[2];
    }
    return;
  }
  const hardsphere::FarWrap wrap(domain);
  for (int i = 0; i < n; i++, w += stride, x += 3) {
    if (std::isnan(w[0])) continue;
    for (int d = 0; d < 3; d++) {
      int k;
      double c;
      if (x[d] != w[d] && wrap.match(d, x[d], w[d], k, c)) x[d] = c;
    }
  }
}
