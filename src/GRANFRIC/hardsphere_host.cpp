// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: what the styles ask of their LAMMPS host alike
------------------------------------------------------------------------- */

#include "hardsphere_host.h"

#include "domain.h"
#include "error.h"
#include "fix.h"
#include "modify.h"
#include "update.h"
#include "host_compat.h"

#include <limits>

namespace LAMMPS_NS {
namespace hardsphere {

  void wrap_image(imageint &image, const int *dimg)
  {
    imageint xb = (image & IMGMASK) - IMGMAX + dimg[0];
    imageint yb = (image >> IMGBITS & IMGMASK) - IMGMAX + dimg[1];
    imageint zb = (image >> IMG2BITS) - IMGMAX + dimg[2];
    image = ((imageint) (xb + IMGMAX) & IMGMASK) | (((imageint) (yb + IMGMAX) & IMGMASK) << IMGBITS) |
        (((imageint) (zb + IMGMAX) & IMGMASK) << IMG2BITS);
  }

  double time_at_step(const Update *update, bigint step)
  {
    return update->atime + (double) (step - update->atimestep) * update->dt;
  }

  void require_ed(LAMMPS *lmp, const char *style, const char *id, const char *what)
  {
    for (const auto &f : host::fixes(lmp->modify))
      if (utils::strmatch(f->style, "^hardsphere/ed")) return;
    host::errors(lmp)->all(FLERR, "Fix {} {} needs fix hardsphere/ed, which {}", style, id, what);
  }

  double parse_inertia(LAMMPS *lmp, const std::string &who, const std::string &value, bool &disc)
  {
    disc = value == "disc";
    if (value == "sphere") return 0.4;
    if (disc) return 0.5;
    if (!utils::is_double(value))
      host::errors(lmp)->all(FLERR, "{} inertia must be sphere, disc or a number 0 < q <= 1, not {}", who,
                      value);
    const double q = utils::numeric(FLERR, value, false, lmp);
    if (!(q > 0.0 && q <= 1.0))
      host::errors(lmp)->all(FLERR, "{} inertia q = I/(m a^2) = {} is out of range (0 < q <= 1)", who, value);
    return q;
  }

  FarWrap::FarWrap(const Domain *domain)
  {
    const double inf = std::numeric_limits<double>::infinity();
    for (int d = 0; d < 3; d++) {
      const bool p = domain->periodicity[d];
      lo[d] = p ? domain->boxlo[d] - 0.5 * domain->prd[d] : -inf;
      hi[d] = p ? domain->boxhi[d] + 0.5 * domain->prd[d] : inf;
      boxlo[d] = domain->boxlo[d];
      L[d] = domain->prd[d];
      periodic[d] = p;
      tol[d] = 16.0 * std::numeric_limits<double>::epsilon() *
          (std::fabs(domain->boxlo[d]) + std::fabs(domain->boxhi[d]));
    }
  }

}    // namespace hardsphere
}    // namespace LAMMPS_NS
