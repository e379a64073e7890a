/* ----------------------------------------------------------------------
   GRANFRIC plugin: registers every GRANFRIC style with LAMMPS
------------------------------------------------------------------------- */

#include "lammpsplugin.h"
#include "version.h"

#include "pair_hardsphere.h"

using namespace LAMMPS_NS;

namespace {

template <granfric::LawKind K> Pair *pair_creator(LAMMPS *lmp)
{
  return new PairHardsphere(lmp, K);
}

void register_pair(lammpsplugin_regfunc reg, void *lmp, void *handle, const char *name,
                   const char *info, lammpsplugin_factory1 *creator)
{
  lammpsplugin_t plugin;
  plugin.version = LAMMPS_VERSION;
  plugin.style = "pair";
  plugin.name = name;
  plugin.info = info;
  plugin.author = "GRANFRIC developers";
  plugin.creator.v1 = creator;
  plugin.handle = handle;
  (*reg)(&plugin, lmp);
}

}    // namespace

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto reg = (lammpsplugin_regfunc) regfunc;
  register_pair(reg, lmp, handle, "hardsphere/rough",
                "GRANFRIC rough hard spheres: constant restitution r and beta",
                (lammpsplugin_factory1 *) &pair_creator<granfric::LawKind::ROUGH>);
  register_pair(reg, lmp, handle, "hardsphere/walton",
                "GRANFRIC hard spheres with Coulomb friction (Walton: r, mu, rtmax)",
                (lammpsplugin_factory1 *) &pair_creator<granfric::LawKind::WALTON>);
  register_pair(reg, lmp, handle, "hardsphere/jz",
                "GRANFRIC hard discs/spheres, Jenkins-Zhang rule (qn, qt, kappa_s, kappa_d)",
                (lammpsplugin_factory1 *) &pair_creator<granfric::LawKind::JZ>);
}
