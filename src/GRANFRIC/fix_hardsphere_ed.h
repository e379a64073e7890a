/* -*- c++ -*- ----------------------------------------------------------
   SPDX-License-Identifier: GPL-2.0-or-later
   Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
   GRANFRIC: fix hardsphere/ed, the exact event-driven integrator for hard spheres and discs.

   fix ID group hardsphere/ed [gravity gx gy gz] [tc t_c] [maxevents N] [maxcross N]
                              [parallel domain|gather]
                              [reach f] [check yes|no] [overlap error|allow]

   Each time step is a window in which every collision is processed in exact time order with the
   collision law of the hardsphere pair style (core/event_driven.h); positions, velocities and
   spins are advanced exactly to the end of the step.

   This class is the LAMMPS glue: keywords, the checks at the start of a run
   (fix_hardsphere_ed_checks.cpp), output, restart files and the per-atom callbacks. The
   windows (hardsphere_gather_window.h, hardsphere_domain_window.h) run the steps; what they
   share from one step to the next is the run's state (hardsphere_run_state.h), which the fix
   owns and hands to them.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(hardsphere/ed,FixHardsphereED);
// clang-format on
#else

#ifndef LMP_GRANFRIC_FIX_HARDSPHERE_ED_H
#define LMP_GRANFRIC_FIX_HARDSPHERE_ED_H

#include "domain.h"
#include "fix.h"

#include "hardsphere_run_state.h"
#include "host_compat.h"

#include <functional>
#include <string>
#include <vector>

namespace LAMMPS_NS {

class FixHardsphereED : public Fix {
 protected:
  GRANFRIC_HOST_ERROR    // (under LIGGGHTS: LAMMPS's error calls)

 public:
  // the output vector (HardsphereRunState lists its entries)
  static constexpr int NVECTOR = HardsphereRunState::NVECTOR;
  enum { GATHER, DOMAIN };
  static constexpr double RESTART_FORMAT = 4.0;    // (see write_restart)

  FixHardsphereED(class LAMMPS *, int, char **);
  // the fix hardsphere/ed with ID id, or an error in the name of who (a command and its style)
  static FixHardsphereED *lookup(class LAMMPS *lmp, const std::string &id, const char *who);
  ~FixHardsphereED() override;
  int setmask() override;
  void init() override;
  void post_force(int) override;
  void post_force_respa(int, int, int) override;
  void setup(int) override;
  void setup_pre_neighbor() override { undo_rounding(); }
  // (a triclinic box rounds every position when LAMMPS reneighbors: see undo_rounding)
  void pre_neighbor() override
  {
    if (balancing || domain->triclinic) undo_rounding();
  }
  void initial_integrate(int) override;
  void initial_integrate_respa(int, int, int) override;
  double compute_vector(int) override;

  double memory_usage() override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;

  // for computes and tests
  // everything since the fix was created (not kept in restart files; the output totals are)
  const granfric::EDStats &cumulative() const { return run->cum; }
  // elapsed simulated time covered by cumulative()
  double cumulative_time() const { return run->cum_time; }
  // the gravity keyword's vector (3 values)
  const double *gravity() const { return run->settings.gravity; }
  // a compute asks for impact-angle histograms with this many bins (one size per fix)
  void request_gamma_bins(int nbins);
  // one collision of the last step, for per-collision output: absolute time, the atoms' IDs and
  // group masks (id[1] = 0 and mask[1] = 0 for a wall), the wall (0: a pair; k: the k-th wall
  // fix), what the core reports. Each collision is kept by one rank only.
  using CollisionRow = HardsphereRunState::CollisionRow;
  // a compute asks for the rows of every step from now on
  void request_collision_rows() { run->want_rows = true; }
  const std::vector<CollisionRow> &collision_rows() const { return run->rows; }
  // Per-atom tallies of the last step, kept with the atoms (they migrate with them), from the
  // first step after they were asked for (a compute, or LAMMPS asking for per-atom virials);
  // HardsphereAtomStates lists their fields
  using Tally = HardsphereAtomStates;
  void request_atom_tallies();
  const double *atom_tally(int i) const { return run->atoms.tally(i); }

 protected:
  // the run's state, which the windows share: the core, epochs, per-atom states, counters
  HardsphereRunState *run = nullptr;
  // the windows: gathered (serial, parallel gather, and the redo of a domain window that had a
  // conflict) and domain-decomposed
  class HardsphereGatherWindow *gwin = nullptr;
  class HardsphereDomainWindow *dwin = nullptr;
  int parallel = DOMAIN;                 // GATHER or DOMAIN
  int nlevels_respa = 0;
  bool balancing = false;    // a fix moves the subdomains during the run (fix balance)
  void find_window_parts();
  // LAMMPS's balance, and its reneighboring of a triclinic box, may round positions: every atom
  // moved only so is put back where the last window wrote it (from the stored states on several
  // ranks, from what a serial run kept in a sheared box, else from the core serially)
  void undo_rounding();
  // a restart file was written: the next window starts afresh from the atoms as the file holds
  // them, as a run continued from that file does (see resync_for_restart)
  bool resync = false;
  void resync_for_restart();
  double window_start_time() const;
  void finish_window(double dt);

  int choice(const char *keyword, const std::string &value,
             const std::vector<std::string> &allowed) const;
  // errors in the setup of a run: walls that cross, a diameter longer than the box, atoms
  // behind a wall, absurd scales
  void check_walls_cross() const;
  void check_box_fits_atoms() const;
  void check_box_changes();                // (sets balancing)
  void check_atoms_between_walls() const;
  void check_plane();                      // (2d: every atom at z = 0, vz = 0, spin about z)
  void refuse_rerun() const;
  void check_scales() const;
  void check_resting_walls(double mmax, double amax) const;
  int plastic_type(const granfric::EDWall &w) const;
  void warn_settling_bed();
  bool warned_settling = false;            // (once per fix)
  void check_atoms_at_rest_on_walls() const;
  void warn_ignored_inputs() const;
  void warn_fast_atoms();                  // (after each window)
  bool warned_fast = false;                // (once per run)
  void warn_piling_collisions();           // (after each window)
  bool warned_piling = false;              // (once per run)
  bigint plane_checked = -1;               // the number of atoms the last check_plane saw
  static constexpr tagint NOATOM = MAXTAGINT;
  tagint first_atom(const std::function<bool(int)> &bad) const;
  double atom_value(tagint who, const std::function<double(int)> &value) const;
};

}    // namespace LAMMPS_NS

#endif
#endif
