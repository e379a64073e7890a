// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
/* ----------------------------------------------------------------------
   GRANFRIC: hard-sphere collision laws as LAMMPS pair styles (see pair_hardsphere.h)
------------------------------------------------------------------------- */

#include "pair_hardsphere.h"

#include "hardsphere_host.h"
#include "law_table.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "neigh_list.h"
#include "neighbor.h"

#include <cmath>
#include <cstdlib>
#include <cstring>

using namespace LAMMPS_NS;
using granfric::INF;
using granfric::LawKind;
using granfric::LawParams;

enum { SPHERE, DISC, NUMBER };

// raw values per type pair: [0, ncoeff) the law's coefficients, [MODEL] the normal restitution
// model's index + 1 (0: the law's constant restitution), then the model's coefficients
static constexpr int MODEL = granfric::LawSpec::MAXCOEFF;
static constexpr int MAXRAW = MODEL + 1 + granfric::RestitutionSpec::MAXCOEFF;
static_assert(MAXRAW == PairHardsphere::NVALUES, "pair_hardsphere.h: NVALUES");

static std::string law_style(LawKind k)
{
  return std::string("hardsphere/") + granfric::law_spec(k).name;
}

/* ---------------------------------------------------------------------- */

PairHardsphere::PairHardsphere(LAMMPS *lmp, LawKind k) :
    Pair(lmp), lawkind(k), qshape(0.4), inertia_style(SPHERE), raw(nullptr), params(nullptr),
    onerad(nullptr), maxrad(nullptr)
{
  nraw = granfric::law_spec(k).ncoeff;
  single_enable = 1;
  single_extra = NSINGLE;
  svector = new double[NSINGLE];
  no_virial_fdotr_compute = 1;
  GRANFRIC_PAIR_FLAGS;
  restartinfo = 1;
  writedata = 1;
}

PairHardsphere::~PairHardsphere()
{
  delete[] svector;
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
    memory->destroy(raw);
    memory->destroy(params);
    delete[] onerad;
    delete[] maxrad;
  }
}

/* ---------------------------------------------------------------------- */

void PairHardsphere::allocate()
{
  allocated = 1;
  const int n = atom->ntypes;
  memory->create(setflag, n + 1, n + 1, "pair:setflag");
  memory->create(cutsq, n + 1, n + 1, "pair:cutsq");
  memory->create(raw, n + 1, n + 1, MAXRAW, "pair:raw");
  memory->create(params, n + 1, n + 1, "pair:params");
  for (int i = 0; i <= n; i++)
    for (int j = 0; j <= n; j++) {
      setflag[i][j] = 0;
      for (int k = 0; k < MAXRAW; k++) raw[i][j][k] = 0.0;
      params[i][j] = LawParams();
    }
  onerad = new double[n + 1];
  maxrad = new double[n + 1];
}

/* ----------------------------------------------------------------------
   no forces: hard particles interact only through fix hardsphere/ed
------------------------------------------------------------------------- */

void PairHardsphere::compute(int eflag, int vflag)
{
  GRANFRIC_EV_INIT(eflag, vflag);
}

/* ----------------------------------------------------------------------
   pair_style hardsphere/<law> [inertia sphere|disc|<q>] [inertia/type I sphere|disc|<q> ...]
------------------------------------------------------------------------- */

void PairHardsphere::settings(int narg, char **arg)
{
  qshape = 0.4;
  inertia_style = SPHERE;
  type_shapes.clear();
  qtype.clear();
  const std::string who = "Pair style " + law_style(lawkind);
  int iarg = 0;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "inertia") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "pair_style inertia", error);
      bool disc;
      qshape = hardsphere::parse_inertia(lmp, who, arg[iarg + 1], disc);
      inertia_style = disc ? DISC : (strcmp(arg[iarg + 1], "sphere") == 0 ? SPHERE : NUMBER);
      iarg += 2;
    } else if (strcmp(arg[iarg], "inertia/type") == 0) {
      if (iarg + 3 > narg) utils::missing_cmd_args(FLERR, "pair_style inertia/type I q", error);
      int lo, hi;
      if (!type_range(arg[iarg + 1], 1 << 30, lo, hi))
        error->all(FLERR, "{} inertia/type {}: not a type or a range of types (I, I*J, *J, I* or *)",
                   who, arg[iarg + 1]);
      bool disc;
      const double q = hardsphere::parse_inertia(lmp, who + " inertia/type " + arg[iarg + 1], arg[iarg + 2], disc);
      type_shapes.push_back({arg[iarg + 1], q, disc});
      iarg += 3;
    } else {
      error->all(FLERR, "Unknown pair style {} keyword: {} (allowed: inertia, inertia/type)",
                 law_style(lawkind), arg[iarg]);
    }
  }
}

// a type or range of types as pair_coeff takes them (I, I*J, *J, I*, *), with ntypes types:
// false if the text is none of these or the range is empty
bool PairHardsphere::type_range(const std::string &text, int ntypes, int &lo, int &hi)
{
  const size_t star = text.find('*');
  auto number = [&](const std::string &t, int empty, int &v) {
    if (t.empty()) {
      v = empty;
      return true;
    }
    if (!utils::is_integer(t)) return false;
    const long x = std::strtol(t.c_str(), nullptr, 10);
    if (x < 1 || x > (1L << 30)) return false;
    v = (int) x;
    return true;
  };
  if (star == std::string::npos) {
    if (!number(text, 0, lo) || text.empty()) return false;
    hi = lo;
  } else if (!number(text.substr(0, star), 1, lo) || !number(text.substr(star + 1), ntypes, hi)) {
    return false;
  }
  return lo >= 1 && lo <= hi && hi <= ntypes;
}

// the shape factor of each type from inertia and inertia/type (at init_style)
void PairHardsphere::resolve_shapes()
{
  qtype.assign(atom->ntypes + 1, qshape);
  for (const auto &s : type_shapes) {
    int lo, hi;
    if (type_range(s.types, atom->ntypes, lo, hi))
      for (int t = lo; t <= hi; t++) qtype[t] = s.q;
  }
}

double PairHardsphere::shape_factor(int itype) const
{
  if (itype < (int) qtype.size()) return qtype[itype];
  double q = qshape;    // (before init_style: from the keywords)
  for (const auto &s : type_shapes) {
    int lo, hi;
    if (type_range(s.types, atom->ntypes, lo, hi) && itype >= lo && itype <= hi) q = s.q;
  }
  return q;
}

/* ---------------------------------------------------------------------- */

const char *PairHardsphere::coeff_names() const
{
  return granfric::law_spec(lawkind).coeff_names;
}

// a number, or inf (any case) where infinity is allowed
static double parse_value(const std::string &who, const char *name, const char *s, bool allow_inf,
                          LAMMPS *lmp)
{
  std::string v = utils::lowercase(s);
  if (allow_inf && (v == "inf" || v == "infinity")) return INF;
  if (!utils::is_double(v))
    host::errors(lmp)->all(FLERR, "{}: {} = {} is not a number{}", who, name, s,
                    allow_inf ? " (nor inf)" : "");
  return utils::numeric(FLERR, v, false, lmp);
}

// the law of raw values (already checked): the law's map, and the restitution model's
static LawParams law_from(LawKind kind, const double *values)
{
  LawParams p = granfric::law_spec(kind).make(values);
  if (values[MODEL] > 0.0) granfric::restitution_spec((int) values[MODEL] - 1).apply(p, values + MODEL + 1);
  return p;
}

// The law's coefficients from arg[0 .. narg-1] (as many as the law has, then optionally a
// normal restitution model and its values) into values, checked against the tables of laws and
// models; errors in the name of who
LawParams PairHardsphere::parse_law(const std::string &who, int narg, char **arg, double *values) const
{
  const granfric::LawSpec &spec = granfric::law_spec(lawkind);
  for (int k = 0; k < MAXRAW; k++) values[k] = 0.0;
  const granfric::RestitutionSpec *model = nullptr;
  if (narg > spec.ncoeff) {
    model = granfric::find_restitution(arg[spec.ncoeff]);
    if (!model && utils::is_double(arg[spec.ncoeff]))
      error->all(FLERR, "{}: {} values given, pair style {} takes {} ({}), optionally followed by "
                 "viscoelastic vref or viscoelastic/material Y nu A", who, narg, law_style(lawkind),
                 spec.ncoeff, spec.coeff_names);
    if (!model)
      error->all(FLERR, "{}: {} after the coefficients {} is not a normal restitution model (allowed: "
                 "viscoelastic vref, viscoelastic/material Y nu A)", who, arg[spec.ncoeff], spec.coeff_names);
    if (narg != spec.ncoeff + 1 + model->ncoeff)
      error->all(FLERR, "{}: {} takes {} value{} ({}), {} given", who, model->name, model->ncoeff,
                 model->ncoeff > 1 ? "s" : "", model->coeff_names, narg - spec.ncoeff - 1);
  }
  const bool null = strcmp(arg[0], "NULL") == 0, want_null = model && model->normal_null;
  if (null != want_null)
    error->all(FLERR, "{}: {} = {}: {}", who, spec.coeff[0].name, arg[0],
               want_null ? std::string("give NULL with ") + model->name + " (the model sets the normal restitution)"
                         : std::string("NULL only with viscoelastic/material"));
  for (int k = 0; k < spec.ncoeff; k++)
    values[k] = k == 0 && null ? spec.elastic_normal
                               : parse_value(who, spec.coeff[k].name, arg[k], spec.coeff[k].inf_ok, lmp);
  const int bad = granfric::first_bad_coeff(spec, values);
  if (bad >= 0 && bad < spec.ncoeff)
    error->all(FLERR, "{}: {} = {} is out of range ({})", who, spec.coeff[bad].name, values[bad],
               spec.coeff[bad].range);
  if (bad == spec.ncoeff)
    error->all(FLERR, "{}: {}; {} = {}", who, spec.joint, spec.coeff_names,
               utils::join_words(std::vector<std::string>(arg, arg + spec.ncoeff), " "));
  if (model) {
    const int index = (int) (model - &granfric::restitution_spec(0));
    values[MODEL] = index + 1;
    double *mc = values + MODEL + 1;
    for (int m = 0; m < model->ncoeff; m++)
      mc[m] = parse_value(who + " " + model->name, model->coeff[m].name, arg[spec.ncoeff + 1 + m], false, lmp);
    const int badm = granfric::first_bad_restitution_coeff(*model, mc);
    if (badm >= 0)
      error->all(FLERR, "{} {}: {} = {} is out of range ({})", who, model->name, model->coeff[badm].name,
                 mc[badm], model->coeff[badm].range);
    LawParams check = spec.make(values);
    if (const char *why = model->apply(check, mc))
      error->all(FLERR, "{}: {} = {} with {}: {}", who, spec.coeff[0].name, arg[0], model->name, why);
  }
  const LawParams p = law_from(lawkind, values);
  if (p.can_create_energy() && comm->me == 0)
    error->warning(FLERR,
                   "{}: kappa_d = {} > kappa_s = {}: the Jenkins-Zhang map is then "
                   "discontinuous and can create energy (counted by fix hardsphere/ed)",
                   who, p.mu_d, p.mu_s);
  return p;
}

// the raw values of one type pair as pair_coeff takes them (write_data)
static void print_coeffs(FILE *fp, LawKind kind, const double *values)
{
  const granfric::LawSpec &spec = granfric::law_spec(kind);
  const granfric::RestitutionSpec *model =
      values[MODEL] > 0.0 ? &granfric::restitution_spec((int) values[MODEL] - 1) : nullptr;
  for (int k = 0; k < spec.ncoeff; k++) {
    if (k == 0 && model && model->normal_null)
      fprintf(fp, " NULL");
    else
      fprintf(fp, " %.17g", values[k]);
  }
  if (!model) return;
  fprintf(fp, " %s", model->name);
  for (int m = 0; m < model->ncoeff; m++) fprintf(fp, " %.17g", values[MODEL + 1 + m]);
}

/* ----------------------------------------------------------------------
   pair_coeff I J <law coefficients>
------------------------------------------------------------------------- */

void PairHardsphere::coeff(int narg, char **arg)
{
  if (narg < 2 + nraw || (narg > 2 + nraw && utils::is_double(arg[2 + nraw])))
    error->all(FLERR, "Incorrect args for pair coefficients: pair_coeff I J {} for {} ({} given), optionally "
               "followed by viscoelastic vref or viscoelastic/material Y nu A", coeff_names(),
               law_style(lawkind), narg);
  if (!allocated) allocate();

  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);

  double values[MAXRAW];
  parse_law(std::string("Pair_coeff ") + law_style(lawkind), narg - 2, arg + 2, values);

  int count = 0;
  for (int i = ilo; i <= ihi; i++)
    for (int j = MAX(jlo, i); j <= jhi; j++) {
      for (int k = 0; k < MAXRAW; k++) raw[i][j][k] = values[k];
      set_law(i, j);
      setflag[i][j] = 1;
      count++;
    }
  if (count == 0) error->all(FLERR, "Incorrect args for pair coefficients: no type pair matched");
}

// params[i][j] from raw[i][j] (values already validated)
void PairHardsphere::set_law(int i, int j)
{
  params[i][j] = law_from(lawkind, raw[i][j]);
  params[j][i] = params[i][j];
}

// unset I,J coefficients: arithmetic mean of I,I and J,J (inf if either is inf), of the law's
// coefficients and, when both use the same normal restitution model, of its coefficients
void PairHardsphere::mix(int i, int j)
{
  if (raw[i][i][MODEL] != raw[j][j][MODEL])
    error->all(FLERR, "Pair style {}: types {} and {} have different normal restitution models; set "
               "pair_coeff {} {} explicitly", law_style(lawkind), i, j, i, j);
  for (int k = 0; k < MAXRAW; k++) {
    if (k >= nraw && k <= MODEL) {
      raw[i][j][k] = raw[i][i][k];
      continue;
    }
    const double a = raw[i][i][k], b = raw[j][j][k];
    raw[i][j][k] = (a == INF || b == INF) ? INF : 0.5 * (a + b);
  }
  set_law(i, j);
  GRANFRIC_DID_MIX;
}

/* ---------------------------------------------------------------------- */

void PairHardsphere::init_style()
{
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag)
    error->all(FLERR,
               "Pair style {} requires per-atom radius, mass and angular velocity "
               "(atom_style sphere)",
               law_style(lawkind));
  if (comm->ghost_velocity == 0)
    error->all(FLERR, "Pair style {} requires ghost atoms to store velocity: use {}",
               law_style(lawkind), host::GHOST_VELOCITY);
  if (inertia_style == DISC && domain->dimension != 2)
    error->all(FLERR, "Pair style {} inertia disc requires a 2d simulation (dimension 2)",
               law_style(lawkind));
  for (const auto &s : type_shapes) {
    int lo, hi;
    if (!type_range(s.types, atom->ntypes, lo, hi))
      error->all(FLERR, "Pair style {} inertia/type {}: no such type (types 1 to {})",
                 law_style(lawkind), s.types, atom->ntypes);
    if (s.disc && domain->dimension != 2)
      error->all(FLERR, "Pair style {} inertia/type {} disc requires a 2d simulation (dimension 2)",
                 law_style(lawkind), s.types);
  }
  resolve_shapes();

  // no neighbor list: fix hardsphere/ed finds partners with its own cell grid, and compute
  // pair/local requests an occasional list of its own

  // largest radius per type, for the cutoffs
  const int ntypes = atom->ntypes;
  for (int i = 1; i <= ntypes; i++) onerad[i] = 0.0;
  const double *radius = atom->radius;
  const int *type = atom->type;
  for (int i = 0; i < atom->nlocal; i++) onerad[type[i]] = MAX(onerad[type[i]], radius[i]);
  MPI_Allreduce(&onerad[1], &maxrad[1], ntypes, MPI_DOUBLE, MPI_MAX, world);
}

/* ----------------------------------------------------------------------
   cutoff = largest contact distance a_i + a_j of the two types; types without
   atoms get the largest contact distance of the system (so bins stay sane)
------------------------------------------------------------------------- */

double PairHardsphere::init_one(int i, int j)
{
  if (setflag[i][j] == 0) mix(i, j);
  double cut = maxrad[i] + maxrad[j];
  if (maxrad[i] <= 0.0 || maxrad[j] <= 0.0) {
    cut = 0.0;
    for (int k = 1; k <= atom->ntypes; k++) cut = MAX(cut, 2.0 * maxrad[k]);
  }
  // (no atoms left: the last cut-off with atoms. LAMMPS takes a zero cut-off, but LIGGGHTS's
  // atom sorting divides by it)
  if (cut > 0.0) last_cut = MAX(last_cut, cut);
  return cut > 0.0 ? cut : last_cut;
}

/* ---------------------------------------------------------------------- */

// Restart files: the settings begin with the law's kind plus RESTART_FORMAT times 1000. Files of
// format 0 (written before inertia/type and the restitution models) hold no inertia/type list
// and four values per type pair; they are still read.
static constexpr int RESTART_FORMAT = 1;
static constexpr int RAW_FORMAT0 = 4;

void PairHardsphere::write_restart(FILE *fp)
{
  write_restart_settings(fp);
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      fwrite(&setflag[i][j], sizeof(int), 1, fp);
      if (setflag[i][j]) fwrite(raw[i][j], sizeof(double), MAXRAW, fp);
    }
}

void PairHardsphere::read_restart(GRANFRIC_RESTART_ARGS)
{
  read_restart_settings(GRANFRIC_RESTART_PASS);
  allocate();
  const int me = comm->me;
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      if (me == 0) utils::sfread(FLERR, &setflag[i][j], sizeof(int), 1, fp, nullptr, error);
      MPI_Bcast(&setflag[i][j], 1, MPI_INT, 0, world);
      if (setflag[i][j]) {
        const int nread = restart_format == 0 ? RAW_FORMAT0 : MAXRAW;
        for (int k = 0; k < MAXRAW; k++) raw[i][j][k] = 0.0;
        if (me == 0) utils::sfread(FLERR, raw[i][j], sizeof(double), nread, fp, nullptr, error);
        MPI_Bcast(raw[i][j], MAXRAW, MPI_DOUBLE, 0, world);
        set_law(i, j);
      }
    }
}

void PairHardsphere::write_restart_settings(FILE *fp)
{
  int kind = static_cast<int>(lawkind) + 1000 * RESTART_FORMAT;
  fwrite(&kind, sizeof(int), 1, fp);
  fwrite(&inertia_style, sizeof(int), 1, fp);
  fwrite(&qshape, sizeof(double), 1, fp);
  // inertia/type: how many, then each one's type text (length and characters), q and disc flag
  const int n = (int) type_shapes.size();
  fwrite(&n, sizeof(int), 1, fp);
  for (const auto &t : type_shapes) {
    const int len = (int) t.types.size(), disc = t.disc ? 1 : 0;
    fwrite(&len, sizeof(int), 1, fp);
    fwrite(t.types.data(), sizeof(char), len, fp);
    fwrite(&t.q, sizeof(double), 1, fp);
    fwrite(&disc, sizeof(int), 1, fp);
  }
}

void PairHardsphere::read_restart_settings(GRANFRIC_RESTART_ARGS)
{
  int kind = 0;
  if (comm->me == 0) {
    utils::sfread(FLERR, &kind, sizeof(int), 1, fp, nullptr, error);
    utils::sfread(FLERR, &inertia_style, sizeof(int), 1, fp, nullptr, error);
    utils::sfread(FLERR, &qshape, sizeof(double), 1, fp, nullptr, error);
  }
  MPI_Bcast(&kind, 1, MPI_INT, 0, world);
  MPI_Bcast(&inertia_style, 1, MPI_INT, 0, world);
  MPI_Bcast(&qshape, 1, MPI_DOUBLE, 0, world);
  restart_format = kind / 1000;
  kind %= 1000;
  if (restart_format > RESTART_FORMAT)
    error->all(FLERR, "Restart file of pair style {} has format {}, newer than this build reads ({})",
               law_style(lawkind), restart_format, RESTART_FORMAT);
  int n = 0;
  if (comm->me == 0 && restart_format > 0) utils::sfread(FLERR, &n, sizeof(int), 1, fp, nullptr, error);
  MPI_Bcast(&n, 1, MPI_INT, 0, world);
  type_shapes.assign(n, TypeShape());
  qtype.clear();
  for (auto &t : type_shapes) {
    int len = 0, disc = 0;
    if (comm->me == 0) utils::sfread(FLERR, &len, sizeof(int), 1, fp, nullptr, error);
    MPI_Bcast(&len, 1, MPI_INT, 0, world);
    std::vector<char> text(len + 1, 0);
    if (comm->me == 0) {
      utils::sfread(FLERR, text.data(), sizeof(char), len, fp, nullptr, error);
      utils::sfread(FLERR, &t.q, sizeof(double), 1, fp, nullptr, error);
      utils::sfread(FLERR, &disc, sizeof(int), 1, fp, nullptr, error);
    }
    MPI_Bcast(text.data(), len, MPI_CHAR, 0, world);
    MPI_Bcast(&t.q, 1, MPI_DOUBLE, 0, world);
    MPI_Bcast(&disc, 1, MPI_INT, 0, world);
    t.types = text.data();
    t.disc = disc != 0;
  }
  if (kind != static_cast<int>(lawkind))
    error->all(FLERR, "Restart file holds a different hardsphere collision law than {}",
               law_style(lawkind));
}

/* ----------------------------------------------------------------------
   data file: full precision, so write_data + read_data reproduce the law exactly
------------------------------------------------------------------------- */

void PairHardsphere::write_data(FILE *fp)
{
  for (int i = 1; i <= atom->ntypes; i++) {
    fprintf(fp, "%d", i);
    print_coeffs(fp, lawkind, raw[i][i]);
    fprintf(fp, "\n");
  }
}

void PairHardsphere::write_data_all(FILE *fp)
{
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      fprintf(fp, "%d %d", i, j);
      print_coeffs(fp, lawkind, raw[i][j]);
      fprintf(fp, "\n");
    }
}

/* ----------------------------------------------------------------------
   what a collision of i and j would do if it happened now (compute pair/local p1..p8):
   p1 = g.n (normal contact velocity, < 0 approaching), p2 = |g_t|, p3 = energy change of the
   collision in energy units (0 when separating), p4 = tangential restitution applied, p5 = 1 if sliding,
   p6 = impact angle gamma (rad), p7 = |normal impulse|, p8 = |tangential impulse|.
   No force: fforce = 0, energy 0.
------------------------------------------------------------------------- */

double PairHardsphere::single(int i, int j, int itype, int jtype, double rsq, double, double,
                              double &fforce)
{
  using granfric::Vec3;
  fforce = 0.0;
  const double r = sqrt(rsq);
  for (int k = 0; k < NSINGLE; k++) svector[k] = 0.0;
  if (r == 0.0) return 0.0;

  double **x = atom->x, **v = atom->v, **omega = atom->omega;
  const Vec3 n = (1.0 / r) * (Vec3::from(x[i]) - Vec3::from(x[j]));
  granfric::Body b1, b2;
  b1.v = Vec3::from(v[i]);
  b1.w = Vec3::from(omega[i]);
  b1.m = atom->rmass[i];
  b1.a = atom->radius[i];
  b1.q = shape_factor(itype);
  b2.v = Vec3::from(v[j]);
  b2.w = Vec3::from(omega[j]);
  b2.m = atom->rmass[j];
  b2.a = atom->radius[j];
  b2.q = shape_factor(jtype);

  const granfric::Collision c = granfric::collide(params[itype][jtype], b1, b2, n);
  svector[0] = c.gn;
  svector[1] = c.gt;
  if (c.gn < 0.0) {
    const double dPn = fabs(granfric::dot(c.dP, n));
    svector[2] = c.dE * force->mvv2e;
    svector[3] = c.rt;
    svector[4] = c.sliding ? 1.0 : 0.0;
    svector[5] = c.gamma();
    svector[6] = dPn;
    svector[7] = granfric::norm(c.dP - granfric::dot(c.dP, n) * n);
  }
  return 0.0;
}

/* ---------------------------------------------------------------------- */

void *PairHardsphere::extract(const char *str, int &dim)
{
  dim = 0;
  if (strcmp(str, "inertia") == 0) return (void *) &qshape;
  // granfric::LawParams[ntypes+1][ntypes+1], for code that cannot see this class
  dim = 2;
  if (strcmp(str, "hardsphere_laws") == 0) return (void *) params;
  dim = 0;
  return nullptr;
}

double PairHardsphere::memory_usage()
{
  const double n = atom->ntypes + 1;
  return n * n * (sizeof(int) + sizeof(double) + MAXRAW * sizeof(double) + sizeof(LawParams)) +
      2.0 * n * sizeof(double);
}
