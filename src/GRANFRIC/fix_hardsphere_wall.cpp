/* ----------------------------------------------------------------------
   GRANFRIC: fix hardsphere/wall (see the header and doc/fix_hardsphere_wall.rst)
------------------------------------------------------------------------- */

#include "fix_hardsphere_wall.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "modify.h"
#include "pair_hardsphere.h"

#include <cstring>

using namespace LAMMPS_NS;

FixHardsphereWall::FixHardsphereWall(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), dim(1), side(-1), edge(false), pos(0.0), temperature(-1.0), seed(1)
{
  if (narg < 5) utils::missing_cmd_args(FLERR, "fix hardsphere/wall face pos", error);
  const std::string face = arg[3];
  const char *faces[] = {"xlo", "xhi", "ylo", "yhi", "zlo", "zhi"};
  int f = -1;
  for (int k = 0; k < 6; k++)
    if (face == faces[k]) f = k;
  if (f < 0)
    error->all(FLERR, "Fix hardsphere/wall face {} is not one of xlo, xhi, ylo, yhi, zlo, zhi",
               face);
  dim = f / 2;
  side = (f % 2) ? +1 : -1;
  if (dim == 2 && domain->dimension == 2)
    error->all(FLERR, "Fix hardsphere/wall face {} is not allowed in a 2d simulation", face);
  if (domain->periodicity[dim])
    error->all(FLERR, "Fix hardsphere/wall face {} needs a non-periodic boundary in {} "
               "(boundary f or m)", face, "xyz"[dim]);
  if (strcmp(arg[4], "EDGE") == 0)
    edge = true;
  else
    pos = utils::numeric(FLERR, arg[4], false, lmp);
  int iarg = 5;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "coeffs") == 0) {
      iarg++;
      while (iarg < narg && (utils::is_double(arg[iarg]) || strcmp(arg[iarg], "inf") == 0))
        coeffs.emplace_back(arg[iarg++]);
      if (coeffs.empty())
        error->all(FLERR, "Fix hardsphere/wall coeffs needs the law's coefficients, as pair_coeff "
                   "takes them");
    } else if (strcmp(arg[iarg], "thermal") == 0) {
      if (iarg + 3 > narg) utils::missing_cmd_args(FLERR, "fix hardsphere/wall thermal T seed", error);
      temperature = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      seed = utils::bnumeric(FLERR, arg[iarg + 2], false, lmp);
      if (!(temperature >= 0.0))
        error->all(FLERR, "Fix hardsphere/wall thermal T = {} must be >= 0", temperature);
      if (seed <= 0) error->all(FLERR, "Fix hardsphere/wall thermal seed = {} must be > 0", seed);
      iarg += 3;
    } else {
      error->all(FLERR, "Unknown fix hardsphere/wall keyword: {} (allowed: coeffs, thermal)",
                 arg[iarg]);
    }
  }
}

int FixHardsphereWall::setmask()
{
  return 0;    // collisions are processed by fix hardsphere/ed
}

void FixHardsphereWall::init()
{
  bool ed = false;
  for (const auto &f : modify->get_fix_list())
    if (utils::strmatch(f->style, "^hardsphere/ed")) ed = true;
  if (!ed)
    error->all(FLERR, "Fix hardsphere/wall {} needs fix hardsphere/ed, which processes the "
               "collisions with it", id);
  auto *pair = dynamic_cast<PairHardsphere *>(force->pair);
  if (!pair) error->all(FLERR, "Fix hardsphere/wall {} needs a hardsphere pair style", id);
  if (!coeffs.empty() && (int) coeffs.size() != pair->ncoeff())
    error->all(FLERR, "Fix hardsphere/wall {} coeffs: {} values given, pair style {} takes {} ({})",
               id, coeffs.size(), force->pair_style, pair->ncoeff(), pair->coeff_names());
  if (!coeffs.empty()) {
    std::vector<char *> a;
    for (auto &c : coeffs) a.push_back(const_cast<char *>(c.c_str()));
    double raw[4];
    pair->parse_law(std::string("Fix hardsphere/wall ") + id + " coeffs", a.data(), raw);
  }
  const double p = edge ? (side < 0 ? domain->boxlo[dim] : domain->boxhi[dim]) : pos;
  if (p < domain->boxlo[dim] || p > domain->boxhi[dim])
    error->all(FLERR, "Fix hardsphere/wall {} position {} lies outside the box ({} to {})", id, p,
               domain->boxlo[dim], domain->boxhi[dim]);
}

granfric::EDWall FixHardsphereWall::wall() const
{
  granfric::EDWall w;
  w.dim = dim;
  w.side = side;
  w.pos = edge ? (side < 0 ? domain->boxlo[dim] : domain->boxhi[dim]) : pos;
  // a thermal wall draws velocities at T (energy units) from the Maxwellian of m v^2 / 2
  if (temperature >= 0.0) w.T = temperature * force->boltz / force->mvv2e;
  w.seed = (uint64_t) seed;
  auto *pair = dynamic_cast<PairHardsphere *>(force->pair);
  const int nt = atom->ntypes;
  w.laws.resize(nt + 1);
  if (coeffs.empty()) {
    for (int t = 1; t <= nt; t++) w.laws[t] = pair->wall_law(t);
  } else {
    std::vector<char *> a;
    for (auto &c : coeffs) a.push_back(const_cast<char *>(c.c_str()));
    double raw[4];
    const granfric::LawParams law = pair->parse_law("Fix hardsphere/wall coeffs", a.data(), raw);
    for (int t = 1; t <= nt; t++) w.laws[t] = law;
  }
  return w;
}
