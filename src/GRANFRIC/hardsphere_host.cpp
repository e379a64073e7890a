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

  ShearWrap::ShearWrap(const Domain *domain, double pbc_xy, double xy, double u) :
      wrap(domain), pbc_xy(pbc_xy), xy(xy), u(u), hrate(domain->h_rate[5]), Lx(domain->prd[0])
  {
    // (x goes through the fractional coordinates with the tilt's part of y)
    tolx = 64.0 * std::numeric_limits<double>::epsilon() *
        (std::fabs(domain->boxlo[0]) + std::fabs(domain->boxhi[0]) + std::fabs(pbc_xy) + std::fabs(xy));
  }

  // does b lie within the rounding of xs less n whole periods of x?
  bool ShearWrap::near(double xs, double b, double &n) const
  {
    n = std::round((xs - b) / Lx);
    return std::fabs(xs - n * Lx - b) <= tolx && std::fabs(n) <= 1e6;
  }

  bool ShearWrap::match(const double *b, double bvx, const double *w, double wvx, int *k, double *c,
                        double &cvx) const
  {
    // (as written, or rounded as a reneighboring rounds most atoms every step: no wrap, and
    // every test below would give the same)
    if (unwrapped(b, bvx, w, wvx)) {
      for (int d = 0; d < 3; d++) k[d] = 0, c[d] = w[d];
      cvx = wvx;
      return true;
    }
    if (!wrap.match(1, b[1], w[1], k[1], c[1]) || !wrap.match(2, b[2], w[2], k[2], c[2])) return false;
    // (the y wrap's x velocity: as pbc() changes it, as match() gave it before, or unchanged:
    // Domain::remap(), which wraps every atom into the box when fix deform flips it, leaves
    // the velocities as they are)
    const int ky = k[1];
    const double vx = ky ? wvx - ky * u : wvx;
    const double pbc = ky == 0 ? wvx : ky > 0 ? wvx - hrate : wvx + hrate;
    if (bvx != vx && bvx != pbc && bvx != wvx) return false;
    // (x wrapped by pbc() with the box's tilt, or as match() gave it before, with xy)
    const double xs = ky ? w[0] - ky * xy : w[0];
    double n;
    if (!near(xs, b[0], n) && !(ky && near(w[0] - ky * pbc_xy, b[0], n))) return false;
    k[0] = (int) n;
    c[0] = n != 0.0 ? xs - n * Lx : xs;
    cvx = vx;    // (last: bvx and cvx may be the same variable)
    return true;
  }

}    // namespace hardsphere
}    // namespace LAMMPS_NS
