// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the options of the event-driven core (see event_driven.h): their
// checks, the state configure() derives from them, and whether two configurations are the same.
#include "event_driven.h"

#include <stdexcept>

namespace granfric {

// the shape factor of every type (index 0 unused): the options', or 0.4 (solid spheres)
static std::vector<double> shape_table(const EDOptions &o, int nt)
{
  return o.shape.empty() ? std::vector<double>(nt + 1, 0.4) : o.shape;
}

// every option and table checked before the core takes any of them: a refused configuration
// leaves the core as it was
static void check_options(const EDOptions &o, int nt, const std::vector<LawParams> &table)
{
  if (o.dim != 2 && o.dim != 3) throw std::invalid_argument("dimension must be 2 or 3");
  if ((int) table.size() != (nt + 1) * (nt + 1))
    throw std::invalid_argument("law table must have (ntypes+1)^2 entries");
  if (nt > 32767) throw std::invalid_argument("at most 32767 particle types");
  if (!o.shape.empty() && (int) o.shape.size() != nt + 1)
    throw std::invalid_argument("shape table must have ntypes+1 entries");
  for (int k = 1; k < (int) o.shape.size(); k++)
    if (!(o.shape[k] > 0.0 && o.shape[k] <= 1.0))
      throw std::invalid_argument("shape factor I/(m a^2) must be in (0, 1]");
  for (int d = 0; d < 3; d++) {
    if (!(o.period[d] >= 0.0)) throw std::invalid_argument("a period must be >= 0");
    if (o.period[d] > 0.0 && !o.open[d])
      throw std::invalid_argument("a period is for open dimensions only");
  }
  if (o.dim == 2 && o.gravity.z != 0.0)
    throw std::invalid_argument("gravity must lie in the x-y plane in 2d");
  bool walled[3] = {false, false, false};
  for (const auto &w : o.walls) {
    if (o.periodic[w.dim]) throw std::invalid_argument("walls must be in non-periodic dimensions");
    if ((int) w.laws.size() != nt + 1)
      throw std::invalid_argument("wall law table must have ntypes+1 entries");
    walled[w.dim] = true;
  }
  if (o.walls.size() > 100) throw std::invalid_argument("at most 100 walls");
  if (o.neighbours < EDOptions::AUTO || o.neighbours > EDOptions::LISTS)
    throw std::invalid_argument("neighbours must be AUTO, CELLS or LISTS");
  if (o.neighbours == EDOptions::LISTS && norm2(o.gravity) != 0.0)
    throw std::invalid_argument("neighbour lists do not work with gravity: use cells");
  if (!(o.list_skin >= 0.0)) throw std::invalid_argument("the list skin must be >= 0");
  if (o.max_collisions < 1 || o.max_collisions > 2000000000L)
    throw std::invalid_argument("the collision cap per particle and window must be 1 to 2e9");
  for (int d = 0; d < o.dim; d++)
    if (!o.periodic[d] && !walled[d] && !o.open[d])
      throw std::invalid_argument("a non-periodic dimension needs at least one wall");
}

void EventDriven::configure(const EDOptions &o, int nt, const std::vector<LawParams> &table)
{
  check_options(o, nt, table);
  opt = o;
  lanes = o.simd && have_lanes();    // (the scans that use them are 3d without gravity)
  // the last collision times exist only with the TC model
  if (o.tc > 0.0 && last_collision.size() != flights.size()) last_collision.assign(flights.size(), -INF);
  if (!(o.tc > 0.0)) last_collision.clear();
  has_gravity = norm2(o.gravity) != 0.0;
  ntypes = nt;
  laws = table;
  qt = shape_table(o, nt);
  L = Vec3(o.hi[0] - o.lo[0], o.hi[1] - o.lo[1], o.hi[2] - o.lo[2]);
  framed = false;
  for (int d = 0; d < 3; d++) {
    P[d] = o.periodic[d] ? L[d] : o.period[d];
    framed = framed || (o.period[d] > 0.0 && d < o.dim);
  }
  if (!framed) frames.clear();
  else if (frames.size() != flights.size()) frames.assign(flights.size(), Frame{{0, 0, 0}});
}

static bool same_law(const LawParams &a, const LawParams &b)
{
  return a.kind == b.kind && a.r == b.r && a.rt_max == b.rt_max && a.mu_s == b.mu_s && a.mu_d == b.mu_d;
}

static bool same_laws(const std::vector<LawParams> &a, const std::vector<LawParams> &b)
{
  if (a.size() != b.size()) return false;
  for (size_t k = 0; k < a.size(); k++)
    if (!same_law(a[k], b[k])) return false;
  return true;
}

bool EventDriven::same_configuration(const EDOptions &o, int nt, const std::vector<LawParams> &table,
                                     const EDOptions &opt, int ntypes, const std::vector<LawParams> &laws)
{
  if (o.dim != opt.dim || nt != ntypes || !same_laws(table, laws) ||
      o.gravity.x != opt.gravity.x || o.gravity.y != opt.gravity.y || o.gravity.z != opt.gravity.z ||
      o.tc != opt.tc || o.max_collisions != opt.max_collisions || o.gamma_bins != opt.gamma_bins ||
      o.cell_width != opt.cell_width || o.neighbours != opt.neighbours ||
      o.list_skin != opt.list_skin ||
      o.walls.size() != opt.walls.size() ||
      shape_table(o, nt) != shape_table(opt, ntypes))
    return false;
  for (int d = 0; d < 3; d++)
    if (o.lo[d] != opt.lo[d] || o.hi[d] != opt.hi[d] || o.periodic[d] != opt.periodic[d] ||
        o.open[d] != opt.open[d] || o.period[d] != opt.period[d])
      return false;
  for (size_t k = 0; k < o.walls.size(); k++) {
    const EDWall &a = o.walls[k], &b = opt.walls[k];
    if (a.dim != b.dim || a.side != b.side || a.pos != b.pos || a.T != b.T || a.seed != b.seed ||
        a.A != b.A || a.omega != b.omega || a.sine != b.sine || !same_laws(a.laws, b.laws))
      return false;
  }
  return true;
}

}    // namespace granfric
