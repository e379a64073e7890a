// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the options of the event-driven core (see event_driven.h): their
// checks, the state configure() derives from them, and, from their one field list
// (EDOptions::each_field), whether two configurations are the same and a description.
#include "event_driven.h"

#include <cmath>

#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <type_traits>

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
    if (w.slide[w.dim] != 0.0 || (o.dim == 2 && w.slide.z != 0.0) || !std::isfinite(norm2(w.slide)))
      throw std::invalid_argument("a wall slides within its plane (and within the x-y plane in 2d), at a finite speed");
    if (w.shake_dim >= 0 && (w.shake_dim == w.dim || w.shake_dim >= o.dim || !(w.shake_A > 0.0) ||
                             !(w.shake_omega > 0.0) || !std::isfinite(w.shake_A * w.shake_omega)))
      throw std::invalid_argument("a wall shakes within its plane (and within the x-y plane in 2d), with a positive finite amplitude and frequency");
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
  if (o.max_crossings < 1 || o.max_crossings > 2000000000L)
    throw std::invalid_argument("the crossing cap per particle and window must be 1 to 2e9");
  if (!std::isfinite(o.shear_rate) || (o.shear_rate != 0.0 && !o.shear))
    throw std::invalid_argument("a shear rate needs shear on, and a finite value");
  if (o.shear && !(o.periodic[0] && o.periodic[1]))
    throw std::invalid_argument("shear (Lees-Edwards) needs periodic x and y");
  if (o.shear && o.neighbours == EDOptions::LISTS)
    throw std::invalid_argument("shear (Lees-Edwards) works with cells, not neighbour lists");
  if (o.shear_band < 0) throw std::invalid_argument("the rows per band of a sheared box must be >= 0 (0: automatic)");
  for (int d = 0; d < o.dim; d++)
    if (!o.periodic[d] && !walled[d] && !o.open[d])
      throw std::invalid_argument("a non-periodic dimension needs at least one wall");
}

void EventDriven::configure(const EDOptions &o, int nt, const std::vector<LawParams> &table)
{
  check_options(o, nt, table);
  opt = o;
  // (the scans that use them are 3d without gravity)
  lanes = o.simd && have_lanes();
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

// Comparisons and descriptions of values of the fields that EDOptions::each_field lists: numbers
// (compared as numbers: a NaN is never the same), the three values of an array or a Vec3, vectors
// element by element, and records with a field list of their own (walls, laws) field by field.
namespace {

template <class T>
bool same_value(const T &a, const T &b);
template <class T>
bool same_value(const T (&a)[3], const T (&b)[3]);
template <class T>
bool same_value(const std::vector<T> &a, const std::vector<T> &b);
bool same_value(const Vec3 &a, const Vec3 &b);

struct SameFields {
  bool same = true;
  template <class T>
  void operator()(const char *, const T &a, const T &b)
  {
    same = same && same_value(a, b);
  }
  template <class T>
  void operator()(const char *name, EDOptions::Role role, const T &a, const T &b)
  {
    if (role == EDOptions::DEFINING) operator()(name, a, b);
  }
};

template <class T>
bool same_value(const T &a, const T &b)
{
  if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
    return a == b;
  } else {
    SameFields s;
    T::each_field(s, a, b);
    return s.same;
  }
}
template <class T>
bool same_value(const T (&a)[3], const T (&b)[3])
{
  return same_value(a[0], b[0]) && same_value(a[1], b[1]) && same_value(a[2], b[2]);
}
bool same_value(const Vec3 &a, const Vec3 &b)
{
  return a.x == b.x && a.y == b.y && a.z == b.z;
}
template <class T>
bool same_value(const std::vector<T> &a, const std::vector<T> &b)
{
  if (a.size() != b.size()) return false;
  for (size_t k = 0; k < a.size(); k++)
    if (!same_value(a[k], b[k])) return false;
  return true;
}

// a number as it is (with the digits that tell it from its neighbours), an array or Vec3 as its
// three values in parentheses, a vector in brackets, a record as {name value, ...}
template <class T>
void put_value(std::ostream &os, const T &v);
template <class T>
void put_value(std::ostream &os, const T (&v)[3]);
template <class T>
void put_value(std::ostream &os, const std::vector<T> &v);
void put_value(std::ostream &os, const Vec3 &v);

struct PutFields {
  std::ostream &os;
  const char *sep = "";
  template <class T>
  void operator()(const char *name, const T &v)
  {
    os << sep << name << ' ';
    put_value(os, v);
    sep = ", ";
  }
  template <class T>
  void operator()(const char *name, EDOptions::Role, const T &v)
  {
    operator()(name, v);
  }
};

template <class T>
void put_value(std::ostream &os, const T &v)
{
  if constexpr (std::is_enum_v<T>) {
    os << (long) v;
  } else if constexpr (std::is_arithmetic_v<T>) {
    os << v;
  } else {
    os << '{';
    T::each_field(PutFields{os}, v);
    os << '}';
  }
}
template <class T>
void put_value(std::ostream &os, const T (&v)[3])
{
  os << '(' << v[0] << ' ' << v[1] << ' ' << v[2] << ')';
}
void put_value(std::ostream &os, const Vec3 &v)
{
  os << '(' << v.x << ' ' << v.y << ' ' << v.z << ')';
}
template <class T>
void put_value(std::ostream &os, const std::vector<T> &v)
{
  os << '[';
  for (size_t k = 0; k < v.size(); k++) {
    if (k) os << ", ";
    put_value(os, v[k]);
  }
  os << ']';
}

}    // namespace

std::string EDOptions::describe() const
{
  std::ostringstream os;
  os << std::boolalpha << std::setprecision(17);
  each_field(PutFields{os}, *this);
  return os.str();
}

bool EventDriven::same_configuration(const EDOptions &o, int nt, const std::vector<LawParams> &table,
                                     const EDOptions &opt, int ntypes, const std::vector<LawParams> &laws)
{
  if (nt != ntypes || !same_value(table, laws)) return false;
  // (no shape table means 0.4 for every type: the same as a table of 0.4s)
  EDOptions a = o, b = opt;
  a.shape = shape_table(o, nt);
  b.shape = shape_table(opt, ntypes);
  SameFields s;
  EDOptions::each_field(s, a, b);
  return s.same;
}

}    // namespace granfric
