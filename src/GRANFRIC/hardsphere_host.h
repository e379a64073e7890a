/* -*- c++ -*- ----------------------------------------------------------
   SPDX-License-Identifier: GPL-2.0-or-later
   Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
   GRANFRIC: what the styles ask of their LAMMPS host alike.
------------------------------------------------------------------------- */

#ifndef LMP_GRANFRIC_HARDSPHERE_HOST_H
#define LMP_GRANFRIC_HARDSPHERE_HOST_H

#include "lmptype.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace LAMMPS_NS {
class Domain;
class LAMMPS;
class Update;

namespace hardsphere {

  // the simulated time at step `step`: elapsed time of the last anchor of LAMMPS's clock plus
  // the steps since (one arithmetic for every style, so that equal steps give equal bits)
  double time_at_step(const Update *update, bigint step);

  // an error unless a fix hardsphere/ed is defined: fix `style` `id` needs it, because it `what`
  void require_ed(LAMMPS *lmp, const char *style, const char *id, const char *what);

  // The inertia keyword of the pair styles and compute hardsphere/temp: sphere (q = I/(m a^2)
  // = 2/5), disc (1/2; the caller checks that the simulation is 2d) or a number 0 < q <= 1.
  // Returns q and sets disc; errors in the name of who (a style).
  double parse_inertia(LAMMPS *lmp, const std::string &who, const std::string &value, bool &disc);

  // Far-out coordinates at the end of a step. LAMMPS wraps an atom back into a periodic box
  // when it reneighbors; an atom more than half a period outside the box (a step longer than a
  // box crossing) is wrapped by the window itself, by whole periods, and its image flags follow.
  class FarWrap {
   public:
    explicit FarWrap(const Domain *domain);
    // the periods by which coordinate y of dimension d lies outside the box: 0 unless it lies
    // more than half a period outside (always 0 in a dimension that is not periodic)
    int periods(int d, double y) const
    {
      if (!(y < lo[d] || y >= hi[d])) return 0;
      return (int) std::floor((y - boxlo[d]) / L[d]);
    }
    // y wrapped into the box if it lies that far out; k: the periods taken off
    void apply(int d, double &y, int &k) const
    {
      k = periods(d, y);
      if (k) y -= k * L[d];
    }
    // The core keeps positions unwrapped (its frame); LAMMPS's lie off periods lower. What a
    // window writes for core coordinate xc of dimension d: xc - off L, and a far one wrapped
    // further (off follows: the periods taken off are off after the call less off before)
    // (shift: in a sheared box, the tilt's part of x at the atom's height, (y - ylo) xy / L_y,
    // which the box's x extent has there)
    double written(int d, double xc, int &off, double shift = 0.0) const
    {
      if (!periodic[d]) return xc;
      double y = off ? xc - off * L[d] : xc;
      const int k = periods(d, y - shift);
      if (k) {
        off += k;
        y = off ? xc - off * L[d] : xc;
      }
      return y;
    }
    // does LAMMPS's coordinate b hold what a window wrote (w), or that wrapped by one period
    // as LAMMPS wraps atoms into the box (off follows)? Up to rounding: see match().
    bool holds(int d, double b, double w, int &off) const
    {
      if (b == w) return true;
      int k;
      double c;
      if (!match(d, b, w, k, c)) return false;
      off += k;
      return true;
    }
    // the coordinate c that LAMMPS's b stands for: w, or w wrapped by one period as
    // Domain::pbc() wraps it (k = -1: w + L; k = 1: w - L, at least the box's lower edge), the
    // same bits or up to rounding. LAMMPS's balance and fix balance (shift) take every position
    // to the box's fractional coordinates and back, which may move it by a few units in the
    // last place of the box's extent (tol). False if b is none of them.
    bool match(int d, double b, double w, int &k, double &c) const
    {
      const int ks[3] = {0, -1, 1};
      const double cs[3] = {w, w + L[d], std::max(w - L[d], boxlo[d])};
      const int n = periodic[d] ? 3 : 1;
      for (int pass = 0; pass < 2; pass++)
        for (int m = 0; m < n; m++)
          if (pass == 0 ? b == cs[m] : std::fabs(b - cs[m]) <= tol[d]) {
            k = ks[m];
            c = cs[m];
            return true;
          }
      return false;
    }
    // would match() find b to be w itself (k = 0, c = w)? The test of the usual case, which
    // skips the wrapped candidates: b within the rounding of w, and not the box's lower edge
    // (which match() takes for w wrapped down to it)
    bool unwrapped(int d, double b, double w) const
    {
      return b == w || (std::fabs(b - w) <= tol[d] && b != boxlo[d]);
    }

   private:
    double lo[3], hi[3], boxlo[3], L[3];
    double tol[3];    // rounding of a coordinate through the box's fractional coordinates
    bool periodic[3];
  };

  // An atom of a sheared box (Lees-Edwards: triclinic, tilted in xy, periodic in x and y) as
  // LAMMPS holds it against what a window wrote (w: x, y, z; wvx: the x velocity), written
  // with the tilt xy and its rate u. LAMMPS takes every position of a triclinic box through
  // its fractional coordinates when it reneighbors, which rounds it by a few units in the last
  // place; Domain::pbc() wraps an atom that left through a y face by the lattice vector
  // (pbc_xy, L_y), with the box's tilt pbc_xy of that step, and changes its x velocity by fix
  // deform's rate hrate (remap v); a box flip moves it by whole periods of x, and wraps it
  // through a y face without changing its velocity (Domain::remap()). match() finds
  // the periods k (k[1] through the y faces, k[0] of x, k[2] of z, as FarWrap::match counts
  // them) and the exact values the atom stands for: c (3) and cvx, w wrapped so with xy and u
  // (the same whether LAMMPS's values came from pbc() or were already these). False if the
  // atom is none of them.
  class ShearWrap {
   public:
    ShearWrap(const Domain *domain, double pbc_xy, double xy, double u);
    bool match(const double *b, double bvx, const double *w, double wvx, int *k, double *c,
               double &cvx) const;    // (c and cvx set only if true)
    // would match() find the atom to be w itself (k = 0, c = w, cvx = wvx)? The usual case
    // (no wrap, rounded as a reneighboring rounds most atoms every step), tested inline
    bool unwrapped(const double *b, double bvx, const double *w, double wvx) const
    {
      return bvx == wvx && std::fabs(b[0] - w[0]) <= tolx && wrap.unwrapped(1, b[1], w[1]) &&
          wrap.unwrapped(2, b[2], w[2]);
    }

   private:
    FarWrap wrap;
    double pbc_xy, xy, u, hrate, Lx, tolx;
    bool near(double xs, double b, double &n) const;
  };

  // the image flags of an atom that a window wrapped by dimg periods (most are not: inline
  // test)
  void wrap_image(imageint &image, const int *dimg);
  inline void shift_image(imageint &image, const int *dimg)
  {
    if (dimg[0] | dimg[1] | dimg[2]) wrap_image(image, dimg);
  }

}    // namespace hardsphere
}    // namespace LAMMPS_NS

#endif
