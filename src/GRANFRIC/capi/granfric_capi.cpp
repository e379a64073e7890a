// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC core as a C ABI for the Python tools (ctypes): the same collision law the LAMMPS
// styles use. Vectors are double[3]; see core/collision.h for conventions.
#include "core/collision.h"
#include "core/energy_loss.h"
#include "core/kicks.h"
#include "core/law_table.h"
#include "core/viscoelastic.h"

#include <algorithm>
#include <cstdint>

using namespace granfric;

extern "C" {

// law: an index into the table of laws (core/law_table.h); model: an index into the table of
// normal restitution models, or -1 for the law's constant restitution, with its coefficients mc
// (a model whose law coefficient is NULL takes c[0] as given: pass the law's elastic value,
// granfric_law_elastic_normal). -1: no such law, -2: coefficients outside their ranges, -4: no
// such model, or its coefficients outside their ranges or not fitting the law's
static int make_law(int law, const double *c, LawParams &p, int model = -1, const double *mc = nullptr)
{
  if (law < 0 || law >= NLAWS) return -1;
  const LawSpec &s = law_spec(law);
  if (first_bad_coeff(s, c) >= 0) return -2;
  p = s.make(c);
  if (model < 0) return 0;
  if (model >= NRESTITUTION || !mc) return -4;
  const RestitutionSpec &r = restitution_spec(model);
  if (first_bad_restitution_coeff(r, mc) >= 0 || r.apply(p, mc)) return -4;
  return 0;
}

// the table of laws: how many, and law `law`'s name and number of coefficients (nullptr and -1
// for no such law)
int granfric_law_count()
{
  return NLAWS;
}

const char *granfric_law_name(int law)
{
  return law >= 0 && law < NLAWS ? law_spec(law).name : nullptr;
}

int granfric_law_ncoeff(int law)
{
  return law >= 0 && law < NLAWS ? law_spec(law).ncoeff : -1;
}

// coefficient k of law `law`: its name (nullptr for none) and its range in words into *range
const char *granfric_law_coeff(int law, int k, const char **range)
{
  if (law < 0 || law >= NLAWS || k < 0 || k >= law_spec(law).ncoeff) return nullptr;
  const LawCoeff &c = law_spec(law).coeff[k];
  if (range) *range = c.range;
  return c.name;
}

// whether coefficients c of law `law` are admissible: -1 if so, else as first_bad_coeff (a
// coefficient's index, or the number of coefficients for the joint condition, whose words are
// granfric_law_joint); -2: no such law
int granfric_law_check(int law, const double *c)
{
  return law >= 0 && law < NLAWS ? first_bad_coeff(law_spec(law), c) : -2;
}

const char *granfric_law_joint(int law)
{
  return law >= 0 && law < NLAWS ? law_spec(law).joint : nullptr;
}

// the value of law `law`'s first coefficient that makes the normal motion elastic (what a model
// whose law coefficient is NULL takes); NaN for no such law
double granfric_law_elastic_normal(int law)
{
  return law >= 0 && law < NLAWS ? law_spec(law).elastic_normal : 0.0 / 0.0;
}

// the table of normal restitution models: how many, model `model`'s name, number of
// coefficients, coefficient k's name and range, whether the law's normal coefficient is NULL
// with it, and whether coefficients mc are admissible (-1 if so, else the first that is not;
// -2: no such model)
int granfric_restitution_count()
{
  return NRESTITUTION;
}

const char *granfric_restitution_name(int model)
{
  return model >= 0 && model < NRESTITUTION ? restitution_spec(model).name : nullptr;
}

int granfric_restitution_ncoeff(int model)
{
  return model >= 0 && model < NRESTITUTION ? restitution_spec(model).ncoeff : -1;
}

const char *granfric_restitution_coeff(int model, int k, const char **range)
{
  if (model < 0 || model >= NRESTITUTION || k < 0 || k >= restitution_spec(model).ncoeff) return nullptr;
  const LawCoeff &c = restitution_spec(model).coeff[k];
  if (range) *range = c.range;
  return c.name;
}

int granfric_restitution_normal_null(int model)
{
  return model >= 0 && model < NRESTITUTION ? (restitution_spec(model).normal_null ? 1 : 0) : -1;
}

int granfric_restitution_check(int model, const double *mc)
{
  return model >= 0 && model < NRESTITUTION ? first_bad_restitution_coeff(restitution_spec(model), mc) : -2;
}

// E(delta), the normal restitution of viscoelastic spheres (core/viscoelastic.h)
double granfric_viscoelastic_restitution(double delta)
{
  return viscoelastic_restitution(delta);
}

// Monte Carlo mean energy changes per collision over Gaussian velocities (Ttr) and spins (Trot)
// (energy_loss.h): out = {<dE_tr>, its s.e., <dE_rot>, its s.e., <dE>, its s.e., sliding};
// model, mc: the normal restitution model (make_law)
int granfric_mean_energy_changes_model(int law, const double *c, int model, const double *mc, double q,
                                       int dim, double Ttr, double Trot, long n, unsigned long seed,
                                       double *out)
{
  LawParams p;
  const int rc = make_law(law, c, p, model, mc);
  if (rc) return rc;
  const EnergyLossResult r = mean_energy_changes(p, q, dim, Ttr, Trot, n, seed);
  const double v[7] = {r.mean_tr, r.stderr_tr, r.mean_rot, r.stderr_rot, r.mean, r.stderr_, r.sliding};
  for (int k = 0; k < 7; k++) out[k] = v[k];
  return 0;
}

// granfric_mean_energy_changes_model with the law's constant restitution
int granfric_mean_energy_changes(int law, const double *c, double q, int dim, double Ttr,
                                 double Trot, long n, unsigned long seed, double *out)
{
  return granfric_mean_energy_changes_model(law, c, -1, nullptr, q, dim, Ttr, Trot, n, seed, out);
}

// Monte Carlo <dE> per collision of equal particles over a Maxwellian at T0 (energy_loss.h):
// out = {mean, standard error, sliding fraction}
int granfric_mean_energy_loss(int law, const double *c, double q, int dim, double T0, long n,
                              unsigned long seed, double *out)
{
  LawParams p;
  const int rc = make_law(law, c, p);
  if (rc) return rc;
  const EnergyLossResult r = mean_energy_loss(p, q, dim, T0, n, seed);
  out[0] = r.mean;
  out[1] = r.stderr_;
  out[2] = r.sliding;
  return 0;
}

// law: the index of a law in the table (0 rough: c = r, beta; 1 walton: c = r, mu, rtmax; 2 jz:
// c = qn, qt, kappa_s, kappa_d).
// body = {vx,vy,vz, wx,wy,wz, m, a, q}; m2 = inf makes body 2 a wall.
// out = {v1[3], w1[3], v2[3], w2[3], dE, gn, gt, cos_gamma, rt, sliding, energy_created} (19 values)
// model, mc: the normal restitution model (make_law; -1: the law's constant restitution)
int granfric_collide_model(int law, const double *c, int model, const double *mc, const double *body1,
                           const double *body2, const double *n, double *out)
{
  LawParams p;
  const int rc = make_law(law, c, p, model, mc);
  if (rc) return rc;
  auto body = [](const double *b) {
    Body o;
    o.v = Vec3::from(b);
    o.w = Vec3::from(b + 3);
    o.m = b[6];
    o.a = b[7];
    o.q = b[8];
    return o;
  };
  Body b1 = body(body1), b2 = body(body2);
  if (b2.is_wall()) b2 = Body::wall(b2.v);
  const Collision r = collide(p, b1, b2, Vec3::from(n));
  r.v1.to(out);
  r.w1.to(out + 3);
  r.v2.to(out + 6);
  r.w2.to(out + 9);
  out[12] = r.dE;
  out[13] = r.gn;
  out[14] = r.gt;
  out[15] = r.cos_gamma;
  out[16] = r.rt;
  out[17] = r.sliding ? 1.0 : 0.0;
  out[18] = r.energy_created ? 1.0 : 0.0;
  return 0;
}

// granfric_collide_model with the law's constant restitution
int granfric_collide(int law, const double *c, const double *body1, const double *body2,
                     const double *n, double *out)
{
  return granfric_collide_model(law, c, -1, nullptr, body1, body2, n, out);
}

// Batch form of granfric_collide for n contacts of equal particles (mass m, radius a, shape
// factor q): the law is applied in place to v1, w1, v2, w2 (each n*3 doubles, pair k at 3k) with
// unit normals nrm (n*3, from 2 to 1), as given (the caller selects approaching pairs). dE
// (n doubles, may be null) receives the energy change of each collision. Used by the Monte Carlo
// solution of the Boltzmann equation (tools/granfric/dsmc.py).
int granfric_collide_batch_model(int law, const double *c, int model, const double *mc, long n, double m,
                                 double a, double q, double *v1, double *w1, double *v2, double *w2,
                                 const double *nrm, double *dE)
{
  LawParams p;
  const int rc = make_law(law, c, p, model, mc);
  if (rc) return rc;
  if (!(m > 0.0 && m < INF && a > 0.0 && q > 0.0)) return -3;
  Body b1, b2;
  b1.m = b2.m = m;
  b1.a = b2.a = a;
  b1.q = b2.q = q;
  for (long k = 0; k < n; k++) {
    const long o = 3 * k;
    b1.v = Vec3::from(v1 + o);
    b1.w = Vec3::from(w1 + o);
    b2.v = Vec3::from(v2 + o);
    b2.w = Vec3::from(w2 + o);
    const Collision r = collide(p, b1, b2, Vec3::from(nrm + o));
    r.v1.to(v1 + o);
    r.w1.to(w1 + o);
    r.v2.to(v2 + o);
    r.w2.to(w2 + o);
    if (dE) dE[k] = r.dE;
  }
  return 0;
}

// granfric_collide_batch with the law's constant restitution
int granfric_collide_batch(int law, const double *c, long n, double m, double a, double q,
                           double *v1, double *w1, double *v2, double *w2, const double *nrm,
                           double *dE)
{
  return granfric_collide_batch_model(law, c, -1, nullptr, n, m, a, q, v1, w1, v2, w2, nrm, dE);
}
// Kick k of the core's random driving (core/kicks.h, as fix hardsphere/kick applies it) to n
// particles with IDs tags, masses m, radii a and shape factor q, in place on their velocities v
// and spins w (n*3 doubles each): fdr, vdr, spin, seed and momentum (0 or 1) as the fix's
// keywords, dim 2 or 3. The momentum shift is summed over these n particles. Returns 0, or -1
// for inadmissible parameters.
int granfric_kick(double fdr, double vdr, double spin, long seed, int momentum, int dim, long k,
                  long n, const long *tags, const double *m, const double *a, double q, double *v,
                  double *w)
{
  if (!(fdr > 0.0) || !(vdr >= 0.0) || !(spin >= 0.0) || seed <= 0 || (dim != 2 && dim != 3) ||
      !(q > 0.0 && q <= 1.0) || n < 0)
    return -1;
  Kicks kicks;
  kicks.fdr = fdr;
  kicks.vdr = vdr;
  kicks.spin = spin;
  kicks.seed = seed;
  kicks.momentum = momentum != 0;
  const Vec3 dvcm = kicks.local_shift(n, tags, m, nullptr, k, dim);
  for (long i = 0; i < n; i++) {
    Vec3 x, vi(v[3 * i], v[3 * i + 1], v[3 * i + 2]), wi(w[3 * i], w[3 * i + 1], w[3 * i + 2]);
    double t = 0.0, ai = a[i], mi = m[i], tl = -INF;
    int16_t type = 1;
    kicks.apply(EDParticle(x, vi, t, ai, wi, mi, q, tl, type), tags[i], k, dim, dvcm);
    vi.to(v + 3 * i);
    wi.to(w + 3 * i);
  }
  return 0;
}
}
