// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: fix hardsphere/ed, the checks at the start of a run: inputs that the windows
   cannot follow exactly, or that would give a wrong result without a word, end here with an
   error that names the cause (see fix_hardsphere_ed.h)
------------------------------------------------------------------------- */

#include "fix_hardsphere_ed.h"

#include "hardsphere_host.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "input.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

using namespace LAMMPS_NS;
using namespace FixConst;

// the lowest ID of the atoms (over all ranks) for which bad(local index) holds, or NOATOM
tagint FixHardsphereED::first_atom(const std::function<bool(int)> &bad) const
{
  tagint who = NOATOM;
  for (int i = 0; i < atom->nlocal; i++)
    if (bad(i)) who = std::min(who, atom->tag[i]);
  MPI_Allreduce(MPI_IN_PLACE, &who, 1, MPI_LMP_TAGINT, MPI_MIN, world);
  return who;
}

// value(local index) of atom who, from the rank that owns it (collective)
double FixHardsphereED::atom_value(tagint who, const std::function<double(int)> &value) const
{
  double v = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->tag[i] == who) v = value(i);
  MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_SUM, world);
  return v;
}

// Absurd speeds, accelerations, steps and wall temperatures end at the start of the run, not
// after the crossing cap's maxcross x atoms cell crossings: the atoms' paths in one step (speed,
// gravity, the speed a moving or thermal wall or the kicks give) summed over the atoms, in the
// largest diameters (the narrowest cells), against that cap; lengths times speeds
// that would overflow the contact-time arithmetic; and walls that would hold grains at rest under
// gravity (check_resting_walls).
void FixHardsphereED::check_scales() const
{
  const double *gravity = run->settings.gravity;
  const long maxcross = run->settings.maxcross;
  // (over all atoms: the summed speed; the largest speed, mass, radius and inverse mass)
  double sum = 0.0, mx[4] = {0.0, 0.0, 0.0, 0.0};
  for (int i = 0; i < atom->nlocal; i++) {
    const double *v = atom->v[i], speed = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    sum += speed;
    mx[0] = std::max(mx[0], atom->rmass[i]);
    mx[1] = std::max(mx[1], atom->radius[i]);
    mx[2] = std::max(mx[2], 1.0 / atom->rmass[i]);
    mx[3] = std::max(mx[3], speed);
  }
  MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_DOUBLE, MPI_SUM, world);
  MPI_Allreduce(MPI_IN_PLACE, mx, 4, MPI_DOUBLE, MPI_MAX, world);
  const double n = (double) atom->natoms;
  if (n == 0.0) return;
  check_resting_walls(mx[0], mx[1]);
  const double dt = update->dt, g = std::hypot(gravity[0], gravity[1], gravity[2]);
  double wmax = 0.0, tmax = 0.0;    // the fastest wall's speed, the hottest wall's temperature
  for (auto *w : run->walls) {
    const granfric::EDWall e = w->geometry();
    wmax = std::max(wmax, e.speed_bound());
    tmax = std::max(tmax, e.T);
  }
  const double vwall = std::max(2.0 * wmax, tmax > 0.0 ? 5.0 * std::sqrt(tmax * mx[2]) : 0.0);
  double vkick = 0.0;
  for (auto *k : run->kicks) vkick += k->speed_scale(dt, domain->dimension);
  // (the images across a sheared box's y faces move at the tilt's rate, which drives the flow)
  const double vshear = domain->triclinic ? std::fabs(domain->h_rate[5]) : 0.0;
  const double mean = (sum / n + vwall + vkick + vshear) * dt + 0.5 * g * dt * dt;    // per atom and step
  // (the shear named only in a sheared box)
  const std::string shear = vshear > 0.0 ? host::format("{:.3g} from the shear, ", vshear) : "";
  const std::string rate = vshear > 0.0 ? "the shear rate (fix deform's erate or vel), " : "";
  if (!(mean / (2.0 * mx[1]) <= (double) maxcross))
    error->all(FLERR, "Fix hardsphere/ed: the atoms would travel {:.3g} diameters per step on "
               "average (mean speed {:.3g}, {:.3g} from moving or thermal walls, {:.3g} from kicks, "
               "{}gravity {:.3g}, timestep {:.3g}), more cells than the crossing cap maxcross = {} "
               "allows each atom in a step: lower the speeds, the walls' speed or temperature, the "
               "kicks' v_dr, {}gravity or the timestep", mean / (2.0 * mx[1]), sum / n, vwall, vkick,
               shear, g, dt, maxcross, rate);
  // (a contact time takes squares of distances and speeds, and of their products)
  const double L = std::max({domain->prd[0], domain->prd[1], domain->dimension == 3 ? domain->prd[2] : 0.0});
  const double vtop = mx[3] + vwall + vkick + vshear + g * dt;
  if (!(L * vtop < 1e150 && L < 1e150))
    error->all(FLERR, "Fix hardsphere/ed: the box length {:.3g} times the largest speed {:.3g} (of "
               "the atoms, walls, kicks and gravity in a step) is {:.3g}, beyond 1e150: the squares "
               "in the contact times would overflow and collisions be missed. Choose units in "
               "which lengths and speeds are nearer 1", L, vtop, L * vtop);
}

// A wall under gravity toward it that holds the grains landing on it at rest: a thermal wall
// so cold that the grains it re-emits hop less than a millionth of a diameter high, or
// maxevents times and more per step (T = 0 is refused by the wall itself), or a wall whose law
// stops the normal motion (restitution 0, which the TC model cannot undo: reversing a zero
// speed leaves it zero). Refused: a grain at
// rest on a wall collides with it without end (mmax, amax: the heaviest mass, the largest radius)
void FixHardsphereED::check_resting_walls(double mmax, double amax) const
{
  const double *gravity = run->settings.gravity;
  const long maxevents = run->settings.maxevents;
  const double dt = update->dt;
  for (auto *w : run->walls) {
    const granfric::EDWall e = w->geometry();
    const double toward = e.toward(gravity);
    if (!(toward > 0.0)) continue;
    std::string why;
    if (e.T < 0.0) {
      const int type = plastic_type(w->wall());
      if (type == 0) continue;
      why = host::format("its collision law for atoms of type {} has normal restitution 0, so a "
                         "grain that lands on it stops and stays at rest on it", type);
    } else {
      // a grain re-emitted at T hops for about 2 sqrt(T/m)/g, kT/(m g) high
      const double hop = 2.0 * std::sqrt(e.T / mmax) / toward, height = e.T / (mmax * toward);
      if (hop * maxevents > dt && height > 1e-6 * 2.0 * amax) continue;
      why = host::format("(thermal at T = {}) a grain of mass {} it re-emits hops {:.3g} diameters "
                         "high, for {:.3g} (about {:.3g} times per step of {}): it stays practically "
                         "at rest on the wall", e.T * force->mvv2e / force->boltz, mmax,
                         height / (2.0 * amax), hop, dt / hop, dt);
    }
    error->all(FLERR, "Fix hardsphere/wall {} under gravity {} toward it: {}, which event-driven "
               "motion can only follow by colliding without end. For a floor on which grains "
               "settle, make it thermal at a temperature at which they hop at least a millionth "
               "of a diameter high and for longer than a step / maxevents = {:.3g} (see the fix "
               "hardsphere/wall page, 'Grains at rest on a floor')", w->wall_id(), toward, why,
               dt / maxevents);
  }
}

// The lowest atom type present whose law with the wall has normal restitution 0 (0: none)
int FixHardsphereED::plastic_type(const granfric::EDWall &w) const
{
  std::vector<int> present(atom->ntypes + 1, 0);
  for (int i = 0; i < atom->nlocal; i++) present[atom->type[i]] = 1;
  MPI_Allreduce(MPI_IN_PLACE, present.data(), atom->ntypes + 1, MPI_INT, MPI_MAX, world);
  for (int t = 1; t <= atom->ntypes; t++)
    if (present[t] && w.laws[t].r == 0.0 && w.laws[t].visco == 0.0) return t;
  return 0;
}

// A bed under gravity on a static floor that is not thermal, with inelastic collisions and
// nothing that feeds energy in (no kick, no thermal or moving wall, no shear): it settles and
// cools without end, colliding ever more often, which the TC model slows but does not stop.
// Warned at the start of the first run that has it (not of every run of a script that runs in
// many pieces), not refused: a settling bed may be what the run is for.
void FixHardsphereED::warn_settling_bed()
{
  const double *gravity = run->settings.gravity;
  if (warned_settling || comm->me != 0 || !run->kicks.empty() || domain->triclinic) return;
  const HardsphereWallPart *floor = nullptr;
  std::vector<granfric::LawParams> laws = run->law_table();
  for (auto *w : run->walls) {
    const granfric::EDWall e = w->wall();
    if (e.T >= 0.0 || e.moving()) return;    // (energy fed in)
    if (!floor && e.toward(gravity) > 0.0) floor = w;
    laws.insert(laws.end(), e.laws.begin() + 1, e.laws.end());
  }
  if (!floor) return;
  if (std::all_of(laws.begin(), laws.end(), [](const granfric::LawParams &l) { return l.conserves_energy(); }))
    return;
  warned_settling = true;
  error->warning(FLERR, "Fix hardsphere/ed {}: nothing feeds energy into the grains over fix "
                 "hardsphere/wall {} (static, not thermal, under gravity toward it) and the "
                 "collisions are inelastic: the bed will settle and cool without end, colliding "
                 "ever more often ({}); for a bed that comes to rest make that floor thermal at "
                 "a small temperature (see the fix hardsphere/wall page, 'Grains at rest on a floor')",
                 id, floor->wall_id(),
                 run->settings.tc > 0.0 ? "the TC model slows that but does not stop it"
                                        : "without the TC model the first grain to settle collapses against it");
}

// A step whose cell crossings reach a tenth of the crossing cap: the atoms move far faster than
// the system's scale. Energy may be running away (the cap will then stop the run), or steps are
// meant that long: warned once per run, as soon as it happens (the crossings summed over the
// ranks' windows)
void FixHardsphereED::warn_fast_atoms()
{
  if (warned_fast || atom->natoms == 0) return;
  const long maxcross = run->settings.maxcross;
  const double per_atom = (double) run->last.crossings / (double) atom->natoms;
  if (!(per_atom >= 0.1 * (double) maxcross)) return;
  warned_fast = true;
  if (comm->me == 0)
    error->warning(FLERR, "Fix hardsphere/ed {}: in step {} the atoms crossed cells {:.3g} times each, "
                   "a tenth or more of the crossing cap maxcross = {}: they move far faster than the "
                   "system's scale (is energy running away, e.g. pumped in by a fast moving wall?), "
                   "and the run stops when a step exceeds the cap", id, update->ntimestep, per_atom, maxcross);
}

// A step in which one atom collided a hundredth of the collision cap maxevents or more (and at
// least 1000 times): collisions are piling up, as in an inelastic collapse or in grains coming
// to rest, and if they go on growing the cap stops the run, possibly only after minutes; or steps
// are meant that long. Warned once per run, as soon as it happens
void FixHardsphereED::warn_piling_collisions()
{
  if (warned_piling) return;
  const long maxevents = run->settings.maxevents, most = run->last.max_collisions_one_particle;
  if (most < std::max(1000L, maxevents / 100)) return;
  warned_piling = true;
  if (comm->me == 0)
    error->warning(FLERR, "Fix hardsphere/ed {}: in step {} one atom collided {} times, a hundredth "
                   "or more of the collision cap maxevents = {}: collisions are piling up (an "
                   "inelastic collapse, or grains coming to rest on a floor or on each other: see "
                   "'Grains at rest on a floor' on the fix hardsphere/wall page), or steps are meant "
                   "that long; the run stops when an atom exceeds the cap", id, update->ntimestep,
                   most, maxevents);
}

// rerun computes from snapshots, between which hard particles collide: the collisions (their
// counts, the energy they dissipate, the collisional part of the pressure) cannot be had from
// them, and the run would report none without a word
void FixHardsphereED::refuse_rerun() const
{
  const char *command = host::running_command(input);
  if (command && strcmp(command, "rerun") == 0)
    error->all(FLERR, "Fix hardsphere/ed {} cannot be used with rerun: hard-sphere collisions "
               "happen between the snapshots, so neither their counts nor the collisional part "
               "of the pressure can be computed from them (unfix {} to evaluate computes of "
               "single configurations, such as compute hardsphere/temp; average the pressure in "
               "the run itself)", id, id);
}

// What acts on the atoms through forces has no effect on hard particles, which move only by
// free flight, gravity, collisions, walls and kicks: a fix that adds or changes forces (fix
// viscous, langevin, addforce, spring/self, freeze, setforce, ...), or pair exclusions (every
// pair of hard particles collides). Warned, not refused: such a fix may be meant for other
// output, and it changes nothing here.
void FixHardsphereED::warn_ignored_inputs() const
{
  if (comm->me != 0) return;
  for (int k = 0; k < modify->nfix; k++) {
    const Fix *f = modify->fix[k];
    if (f == this || utils::strmatch(f->style, "^hardsphere/") || utils::strmatch(f->style, "^enforce2d")) continue;
    if (modify->fmask[k] & POST_FORCE)
      error->warning(FLERR, "Fix {} ({}) acts through forces, which the hard particles of fix "
                     "hardsphere/ed {} do not feel: it has no effect on their motion (they move "
                     "by free flight, the gravity keyword, collisions, fix hardsphere/wall and fix "
                     "hardsphere/kick)", f->id, f->style, id);
  }
  if (host::pairs_excluded(neighbor))
    error->warning(FLERR, "neigh_modify exclude has no effect on fix hardsphere/ed {}: every pair "
                   "of hard particles collides", id);
}

// In 2d the core moves discs in the plane z = 0 and spins them about z: an atom off that plane
// (set ... z, fix deposit or pour with a region of some thickness in z), moving in z or
// spinning about x or y would collide as a sphere in 3d. Checked at every run's start and when
// the number of atoms changed (atoms added during the run).
void FixHardsphereED::check_plane()
{
  plane_checked = atom->natoms;
  if (domain->dimension != 2) return;
  double **x = atom->x, **v = atom->v, **omega = atom->omega;
  // (a triclinic box takes positions through its fractional coordinates, which can leave z a
  // few units in the last place of the box's z extent off 0: put back in the plane)
  if (domain->triclinic) {
    const double tol = 16.0 * std::numeric_limits<double>::epsilon() *
        (std::fabs(domain->boxlo[2]) + std::fabs(domain->boxhi[2]));
    for (int i = 0; i < atom->nlocal; i++)
      if (std::fabs(x[i][2]) <= tol) x[i][2] = 0.0;
  }
  const tagint who = first_atom([&](int i) {
    return x[i][2] != 0.0 || v[i][2] != 0.0 || omega[i][0] != 0.0 || omega[i][1] != 0.0;
  });
  if (who == NOATOM) return;
  double at[4];    // (z, vz, omega_x, omega_y of atom who)
  for (int d = 0; d < 4; d++)
    at[d] = atom_value(who, [&](int i) { return d == 0 ? x[i][2] : d == 1 ? v[i][2] : omega[i][d - 2]; });
  error->all(FLERR, "Fix hardsphere/ed: atom {} is not a disc in the plane of the 2d simulation "
             "(z = {}, vz = {}, omega = ({}, {}, .)): every atom must lie at z = 0 with vz = 0 "
             "and spin about z only (the set and velocity commands set them; fix deposit and "
             "fix pour need a region with z from 0 to 0 in 2d)", who, at[0], at[1], at[2], at[3]);
}

// a lower wall at or above an upper wall of the same dimension (their swings included) leaves no
// room between them
// (a wall outside the box is reported by the wall itself, as that)
void FixHardsphereED::check_walls_cross() const
{
  auto inside = [&](const granfric::EDWall &w) {
    return w.pos >= domain->boxlo[w.dim] && w.pos <= domain->boxhi[w.dim];
  };
  for (auto *lo : run->walls)
    for (auto *hi : run->walls) {
      const granfric::EDWall a = lo->geometry(), b = hi->geometry();
      if (a.dim != b.dim || a.side > 0 || b.side < 0 || a.pos + a.A < b.pos - b.A) continue;
      if (!inside(a) || !inside(b)) continue;
      error->all(FLERR, "Fix hardsphere/wall {} ({} at {}{}) is not below fix hardsphere/wall {} "
                 "({} at {}{}): the lower wall must lie below the upper one", lo->wall_id(), lo->face(),
                 a.pos, a.A > 0.0 ? host::format(" + amplitude {}", a.A) : "", hi->wall_id(), hi->face(),
                 b.pos, b.A > 0.0 ? host::format(" - amplitude {}", b.A) : "");
    }
}

// The box stays as it is during a run, or is sheared: a shrink-wrapped non-periodic boundary
// may move (the fix's edge cells extend outward) and fix balance may move the subdomains
// (balancing), but no fix may change the box's size or shape (barostats, fix deform), except
// fix deform changing the xy tilt alone with remap v: simple shear through Lees-Edwards
// images. A triclinic box must then be tilted in xy only and periodic in x and y.
void FixHardsphereED::check_box_changes()
{
  balancing = false;
  const Fix *deform = nullptr;
  for (const auto &f : host::fixes(modify)) {
    balancing = balancing || host::moves_subdomains(f);
    if (!host::changes_box(f)) continue;
    if (host::shears_xy_only(f) && utils::strmatch(f->style, "^deform") && !deform) {
      deform = f;
      continue;
    }
    error->all(FLERR, "Fix hardsphere/ed does not support a box whose size or shape changes "
               "during the run (fix {} {}): the hard-sphere windows need a fixed box, or one "
               "sheared by a single fix deform that changes only the xy tilt (with remap v); fix "
               "balance, which moves only the subdomain boundaries, is supported", f->id, f->style);
  }
  if (!domain->triclinic) return;
#ifdef GRANFRIC_LIGGGHTS
  error->all(FLERR, "Fix hardsphere/ed does not support triclinic boxes under LIGGGHTS");
#endif
  if (domain->xz != 0.0 || domain->yz != 0.0)
    error->all(FLERR, "Fix hardsphere/ed supports triclinic boxes tilted in xy only (simple shear "
               "in the x-y plane): xz = {} and yz = {} must be 0", domain->xz, domain->yz);
  if (!domain->periodicity[0] || !domain->periodicity[1])
    error->all(FLERR, "Fix hardsphere/ed: a triclinic (sheared) box must be periodic in x and y "
               "(boundary p p p, or p p f with walls on the z faces): the sheared images lie "
               "across the y faces");
  if (deform && !domain->deform_vremap)
    error->all(FLERR, "Fix hardsphere/ed needs fix deform {} with remap v: an atom that crosses a "
               "y face of the sheared box takes the velocity of the image it enters (remap x "
               "would move the atoms with the box, remap none would break the flow at the "
               "faces)", deform->id);
  if (deform && domain->deform_groupbit != 1)
    error->all(FLERR, "Fix hardsphere/ed needs fix deform {} to apply to group all (remap v "
               "changes the velocity of every atom that crosses a y face)", deform->id);
}

// every box length at least the largest diameter (the cells of the core are that wide); the
// error names an atom of that diameter
void FixHardsphereED::check_box_fits_atoms() const
{
  double amax = 0.0;
  for (int i = 0; i < atom->nlocal; i++) amax = std::max(amax, atom->radius[i]);
  MPI_Allreduce(MPI_IN_PLACE, &amax, 1, MPI_DOUBLE, MPI_MAX, world);
  for (int d = 0; d < domain->dimension; d++) {
    if (domain->prd[d] >= 2.0 * amax * (1.0 + 1e-10)) continue;
    const tagint who = first_atom([&](int i) { return atom->radius[i] == amax; });
    error->all(FLERR, "Fix hardsphere/ed: atom {} has diameter {}, longer than the box in {} ({} "
               "from {} to {}): every box length must be at least the largest diameter", who,
               2.0 * amax, "xyz"[d], domain->prd[d], domain->boxlo[d], domain->boxhi[d]);
  }
}

// An atom that starts at rest on a static wall that is not thermal, under gravity toward it,
// or so nearly at rest that its hop off the wall, even an elastic one, would last less than a
// step / maxevents: it would collide with the wall without end from the first instant (the TC
// model makes such collisions elastic, not rarer; a thermal or moving wall throws it off). Hops
// of a settled bed, however low, are not refused: with the TC model they last about t_c.
void FixHardsphereED::check_atoms_at_rest_on_walls() const
{
  const double *gravity = run->settings.gravity;
  const double dt = update->dt, maxevents = (double) run->settings.maxevents;
  for (auto *w : run->walls) {
    const granfric::EDWall e = w->geometry();
    const double g = e.toward(gravity);
    if (e.T >= 0.0 || e.moving() || !(g > 0.0)) continue;
    // (its speed when it reaches the wall, from its gap and its speed away from the wall)
    auto hit_speed = [&](int i) {
      const double gap = std::max(0.0, -e.side * (atom->x[i][e.dim] - e.pos) - atom->radius[i]);
      const double away = -e.side * atom->v[i][e.dim];
      return std::sqrt(away * away + 2.0 * g * gap);
    };
    const tagint who = first_atom([&](int i) { return 2.0 * hit_speed(i) / g * maxevents <= dt; });
    if (who == NOATOM) continue;
    const double v = atom_value(who, hit_speed), diameter = atom_value(who, [&](int i) { return 2.0 * atom->radius[i]; });
    error->all(FLERR, "Fix hardsphere/ed: atom {} starts at rest on fix hardsphere/wall {} (or "
               "nearly: it reaches the wall at speed {:.3g}) under gravity {} toward it: it would "
               "hop off the wall {:.3g} diameters high, for {:.3g}, and collide with it without end "
               "(the TC model makes such collisions elastic, not rarer). Lift it off the wall, "
               "give it a speed away from it, or make the wall thermal (see the fix "
               "hardsphere/wall page, 'Grains at rest on a floor')", who, w->wall_id(), v, g,
               v * v / (2.0 * g) / diameter, 2.0 * v / g);
  }
}

// no atom reaches behind a wall at the start of the run (its center at least its radius from
// the plane, on the inner side, up to rounding); the error names the atom with the lowest ID
void FixHardsphereED::check_atoms_between_walls() const
{
  const double t = window_start_time() + update->dt;    // (the time the next window starts)
  for (auto *w : run->walls) {
    const granfric::EDWall g = w->geometry();
    double p, vw, aw;
    g.motion(t, p, vw, aw);
    // (a margin for rounding: 1e-9 of the diameter, 1e-12 of the wall's coordinate)
    const tagint who = first_atom([&](int i) {
      const double a = atom->radius[i], gap = g.side * (p - atom->x[i][g.dim]);
      return gap < a - 2e-9 * a - 1e-12 * std::fabs(p);
    });
    if (who == NOATOM) continue;
    double at[4];    // (position and radius of atom who)
    for (int d = 0; d < 4; d++)
      at[d] = atom_value(who, [&](int i) { return d < 3 ? atom->x[i][d] : atom->radius[i]; });
    error->all(FLERR, "Fix hardsphere/ed: atom {} at ({}, {}, {}) with radius {} reaches behind "
               "fix hardsphere/wall {} ({} at {}): every atom must start between the walls, "
               "at least its radius away from each", who, at[0], at[1], at[2], at[3], w->wall_id(),
               w->face(), p);
  }
}
