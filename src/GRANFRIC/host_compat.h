// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: the two hosts of the styles. The styles are written against the current LAMMPS API
   (utils:: parsing, errors with {} arguments). Built for LIGGGHTS 3.8 (GRANFRIC_LIGGGHTS), whose
   API is the LAMMPS API of 2013, this header supplies the part of that API the styles use, on
   LIGGGHTS's own calls, and the few calls that differ in name are named here for both hosts.
   Included by every style after its LAMMPS headers.
------------------------------------------------------------------------- */

#ifndef GRANFRIC_HOST_COMPAT_H
#define GRANFRIC_HOST_COMPAT_H

#include "atom.h"
#include "error.h"
#include "fix.h"
#include "lammps.h"
#include "modify.h"

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#ifndef GRANFRIC_LIGGGHTS
#include "input.h"
#include "neighbor.h"
#include "utils.h"
#else
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <type_traits>
#endif

namespace LAMMPS_NS {
namespace host {

#ifndef GRANFRIC_LIGGGHTS
inline const std::vector<Fix *> &fixes(Modify *modify) { return modify->get_fix_list(); }
inline Fix *fix_by_id(Modify *modify, const std::string &id) { return modify->get_fix_by_id(id); }
constexpr int GROW = Atom::GROW, RESTART = Atom::RESTART;
// (a style class's member that stands for LAMMPS's error: none needed)
#define GRANFRIC_HOST_ERROR
// the command that makes ghost atoms carry velocities
constexpr const char *GHOST_VELOCITY = "comm_modify vel yes";
// a compute's base (LIGGGHTS's takes the index of the first argument after "ID group style")
#define GRANFRIC_COMPUTE_BASE(lmp, narg, arg) Compute(lmp, narg, arg)
// a fix that adds to the virial (global and per atom), and its per-step set-up
#define GRANFRIC_FIX_VIRIAL virial_global_flag = virial_peratom_flag = 1, thermo_virial = 1
#define GRANFRIC_V_INIT(vflag) v_init(vflag)
// a fix's largest contribution per atom to an exchange of atoms
#define GRANFRIC_MAXEXCHANGE(n) maxexchange = (n)
// a fix that is a copy of another (LAMMPS's Kokkos styles; none under LIGGGHTS)
#define GRANFRIC_COPYMODE copymode
// does fix f change the box (its size or shape)? Moving the subdomains' boundaries (fix
// balance) does not change it: the windows follow the atoms, wherever their ranks are.
inline bool changes_box(const Fix *f) { return (f->box_change & ~Fix::BOX_CHANGE_DOMAIN) != 0; }
// does fix f move the subdomains' boundaries during a run (fix balance)?
inline bool moves_subdomains(const Fix *f) { return (f->box_change & Fix::BOX_CHANGE_DOMAIN) != 0; }
// does fix f change the box's xy tilt and nothing else of it (fix deform xy: simple shear)?
inline bool shears_xy_only(const Fix *f)
{
  return (f->box_change & ~Fix::BOX_CHANGE_DOMAIN) == Fix::BOX_CHANGE_XY;
}
// the command being run, and whether neigh_modify exclude removed pairs from the neighbour
// lists
inline const char *running_command(const Input *input) { return input->command; }
inline bool pairs_excluded(const Neighbor *neighbor)
{
  return neighbor->nex_type + neighbor->nex_group + neighbor->nex_mol > 0;
}
// a pair style's per-step set-up of energy and virial tallies, its cut-off flags, its mixing
#define GRANFRIC_EV_INIT(eflag, vflag) ev_init(eflag, vflag)
#define GRANFRIC_PAIR_FLAGS finitecutflag = 1
#define GRANFRIC_DID_MIX did_mix = true
// the arguments of a restart reader (LIGGGHTS's also take the file's version)
#define GRANFRIC_RESTART_ARGS FILE *fp
#define GRANFRIC_RESTART_PASS fp
template <class... A>
std::string format(const char *f, const A &...a)
{
  return fmt::format(fmt::runtime(f), a...);
}
#else
#define GRANFRIC_COPYMODE 0
inline bool changes_box(const Fix *f)
{
  return f->box_change_size || f->box_change_shape;
}
inline bool moves_subdomains(const Fix *f) { return f->box_change_domain != 0; }
// (sheared boxes are not supported under LIGGGHTS)
inline bool shears_xy_only(const Fix *) { return false; }
// (LIGGGHTS 3.8 has no rerun command; the exclusion counts are protected: the LIGGGHTS host
// program reads them, see src/liggghts/granfric_liggghts.cpp)
inline const char *running_command(const Input *) { return nullptr; }
bool pairs_excluded(const Neighbor *neighbor);
#define GRANFRIC_EV_INIT(eflag, vflag) \
  do {                                 \
    if (eflag || vflag)                \
      ev_setup(eflag, vflag);          \
    else                               \
      evflag = vflag_fdotr = 0;        \
  } while (0)
#define GRANFRIC_PAIR_FLAGS (void) 0
#define GRANFRIC_DID_MIX (void) 0
#define GRANFRIC_RESTART_ARGS FILE *fp, const int major, const int minor
#define GRANFRIC_RESTART_PASS fp, major, minor
inline int &first_arg()
{
  static int k;
  k = 3;
  return k;
}
#define GRANFRIC_COMPUTE_BASE(lmp, narg, arg) Compute(lmp, LAMMPS_NS::host::first_arg(), narg, arg)
#define GRANFRIC_FIX_VIRIAL virial_flag = 1
#define GRANFRIC_V_INIT(vflag) \
  do {                         \
    if (vflag)                 \
      v_setup(vflag);          \
    else                       \
      evflag = 0;              \
  } while (0)
#define GRANFRIC_MAXEXCHANGE(n) \
  do {                                                                  \
    if (comm->maxexchange_fix < (n)) comm->maxexchange_fix = (n);       \
  } while (0)
inline std::vector<Fix *> fixes(Modify *modify)
{
  return std::vector<Fix *>(modify->fix, modify->fix + modify->nfix);
}
inline Fix *fix_by_id(Modify *modify, const std::string &id)
{
  const int k = modify->find_fix(id.c_str());
  return k < 0 ? nullptr : modify->fix[k];
}
constexpr int GROW = 0, RESTART = 1;    // (LIGGGHTS's callback flags)
constexpr const char *GHOST_VELOCITY = "communicate single vel yes";

// A message with {} placeholders (also {:g}, {:.Ng}, {:.Nf}) filled in order, as LAMMPS's fmt does
// for what the styles print
inline void put(std::ostringstream &o, const std::string &spec, double x)
{
  char b[64];
  if (!spec.empty()) {
    std::snprintf(b, sizeof b, ("%" + spec.substr(1)).c_str(), x);
    o << b;
    return;
  }
  if (!std::isfinite(x)) {
    o << (std::isnan(x) ? "nan" : x > 0 ? "inf" : "-inf");
    return;
  }
  // as fmt's {}: the fewest digits that read back as x, fixed notation for decimal exponents
  // -4 ... 15, else exponential
  int p = 0;
  for (; p < 17; p++) {
    std::snprintf(b, sizeof b, "%.*e", p, x);
    if (std::strtod(b, nullptr) == x) break;
  }
  const int e = x == 0.0 ? 0 : std::atoi(std::strchr(b, 'e') + 1);
  if (e >= -4 && e < 16) std::snprintf(b, sizeof b, "%.*f", p > e ? p - e : 0, x);
  o << b;
}
template <class T>
void put(std::ostringstream &o, const std::string &spec, const T &x)
{
  if constexpr (std::is_floating_point<T>::value)
    put(o, spec, (double) x);
  else
    o << x;
}
inline void fill(std::ostringstream &o, const char *f)
{
  for (; *f; f++) o << *f;
}
template <class A, class... R>
void fill(std::ostringstream &o, const char *f, const A &a, const R &...r)
{
  for (; *f; f++) {
    if (*f != '{') {
      o << *f;
      continue;
    }
    const char *e = std::strchr(f, '}');
    if (!e) break;
    put(o, std::string(f + 1, e), a);
    fill(o, e + 1, r...);
    return;
  }
}
template <class... A>
std::string format(const char *f, const A &...a)
{
  std::ostringstream o;
  fill(o, f, a...);
  return o.str();
}

// LAMMPS's error calls with arguments, on LIGGGHTS's Error: a style class holds one as `error`
// (GRANFRIC_HOST_ERROR), which hides the host's Error pointer of the same name and passes for it
class ErrorCalls {
 public:
  explicit ErrorCalls(LAMMPS *l) : lmp(l) {}
  const ErrorCalls *operator->() const { return this; }
  operator Error *() const { return lmp->error; }
  template <class... A>
  [[noreturn]] void all(const char *file, int line, const char *f, const A &...a) const
  {
    lmp->error->all(file, line, format(f, a...).c_str());
    std::abort();    // (not reached)
  }
  template <class... A>
  [[noreturn]] void one(const char *file, int line, const char *f, const A &...a) const
  {
    lmp->error->one(file, line, format(f, a...).c_str());
    std::abort();
  }
  template <class... A>
  void warning(const char *file, int line, const char *f, const A &...a) const
  {
    lmp->error->warning(file, line, format(f, a...).c_str());
  }

 private:
  LAMMPS *lmp;
};
#define GRANFRIC_HOST_ERROR LAMMPS_NS::host::ErrorCalls error{lmp};
#endif

// the error calls of lmp, for code outside a style class: errors(lmp)->all(FLERR, "... {}", x)
#ifndef GRANFRIC_LIGGGHTS
inline Error *errors(LAMMPS *lmp) { return lmp->error; }
#else
inline ErrorCalls errors(LAMMPS *lmp) { return ErrorCalls(lmp); }
#endif

}    // namespace host

#ifdef GRANFRIC_LIGGGHTS
// the part of LAMMPS's utils the styles use, with LAMMPS's messages
namespace utils {
inline bool is_double(const std::string &str)
{
  const char *s = str.c_str();
  if (!*s) return false;
  char *end = nullptr;
  std::strtod(s, &end);
  return *end == '\0' && std::strpbrk(s, "0123456789");
}
inline bool is_integer(const std::string &str)
{
  const char *s = str.c_str();
  if (!*s) return false;
  const char *p = s + (*s == '-' || *s == '+');
  if (!*p) return false;
  for (; *p; p++)
    if (*p < '0' || *p > '9') return false;
  return true;
}
inline double numeric(const char *file, int line, const std::string &str, bool, LAMMPS *lmp)
{
  const char *s = str.c_str();
  if (!is_double(s))
    lmp->error->all(file, line, host::format("Expected floating point parameter instead of '{}' in input script or data file", s).c_str());
  return std::strtod(s, nullptr);
}
inline int inumeric(const char *file, int line, const std::string &str, bool, LAMMPS *lmp)
{
  const char *s = str.c_str();
  if (!is_integer(s))
    lmp->error->all(file, line, host::format("Expected integer parameter instead of '{}' in input script or data file", s).c_str());
  return (int) std::strtol(s, nullptr, 10);
}
inline bigint bnumeric(const char *file, int line, const std::string &str, bool, LAMMPS *lmp)
{
  const char *s = str.c_str();
  if (!is_integer(s))
    lmp->error->all(file, line, host::format("Expected integer parameter instead of '{}' in input script or data file", s).c_str());
  return (bigint) std::strtoll(s, nullptr, 10);
}
inline int logical(const char *file, int line, const std::string &str, bool, LAMMPS *lmp)
{
  const char *s = str.c_str();
  const std::string v = s;
  if (v == "yes" || v == "on" || v == "true" || v == "1") return 1;
  if (v == "no" || v == "off" || v == "false" || v == "0") return 0;
  lmp->error->all(file, line, host::format("Expected boolean parameter instead of '{}' in input script or data file", v).c_str());
  return 0;
}
[[noreturn]] inline void missing_cmd_args(const char *file, int line, const std::string &cmd, Error *error)
{
  error->all(file, line, host::format("Illegal {} command: missing argument(s)", cmd).c_str());
  std::abort();
}
// the patterns the styles use: "^prefix" or a whole word
inline bool strmatch(const std::string &text, const std::string &pattern)
{
  if (!pattern.empty() && pattern[0] == '^') return text.compare(0, pattern.size() - 1, pattern, 1) == 0;
  return text.find(pattern) != std::string::npos;
}
inline void sfread(const char *file, int line, void *s, size_t size, size_t num, FILE *fp, const char *,
                   Error *error)
{
  if (std::fread(s, size, num, fp) != num) error->one(file, line, "Unexpected end of restart file");
}
inline std::string join_words(const std::vector<std::string> &words, const std::string &sep)
{
  std::string r;
  for (size_t k = 0; k < words.size(); k++) r += (k ? sep : "") + words[k];
  return r;
}
inline std::string lowercase(std::string s)
{
  for (auto &c : s) c = (char) std::tolower((unsigned char) c);
  return s;
}
// "n", "*", "n*", "*n", "n*m" within [nmin, nmax]
inline void bounds(const char *file, int line, const std::string &s, int nmin, int nmax, int &lo, int &hi,
                   Error *error)
{
  const size_t star = s.find('*');
  auto num = [&](const std::string &t, int dflt) { return t.empty() ? dflt : std::atoi(t.c_str()); };
  if (star == std::string::npos) {
    lo = hi = std::atoi(s.c_str());
  } else {
    lo = num(s.substr(0, star), nmin);
    hi = num(s.substr(star + 1), nmax);
  }
  if (lo < nmin || hi > nmax || lo > hi)
    error->all(file, line, host::format("Numeric index {} is out of bounds ({}-{})", s, nmin, nmax).c_str());
}
}    // namespace utils
#endif

}    // namespace LAMMPS_NS

#endif
