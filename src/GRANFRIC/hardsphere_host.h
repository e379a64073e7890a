/* -*- c++ -*- ----------------------------------------------------------
   SPDX-License-Identifier: GPL-2.0-or-later
   Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
   GRANFRIC: what the styles ask of their LAMMPS host alike.
------------------------------------------------------------------------- */

#ifndef LMP_GRANFRIC_HARDSPHERE_HOST_H
#define LMP_GRANFRIC_HARDSPHERE_HOST_H

#include "lmptype.h"

namespace LAMMPS_NS {
class LAMMPS;
class Update;

namespace hardsphere {

  // the simulated time at step `step`: elapsed time of the last anchor of LAMMPS's clock plus
  // the steps since (one arithmetic for every style, so that equal steps give equal bits)
  double time_at_step(const Update *update, bigint step);

  // an error unless a fix hardsphere/ed is defined: fix `style` `id` needs it, because it `what`
  void require_ed(LAMMPS *lmp, const char *style, const char *id, const char *what);

}    // namespace hardsphere
}    // namespace LAMMPS_NS

#endif
