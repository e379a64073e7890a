// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the table of collision laws (see law_table.h and doc/conventions.rst).
#include "law_table.h"

#include "viscoelastic.h"

#include <cfloat>
#include <cmath>
#include <cstring>

namespace granfric {

namespace {
  // an infinite sliding impulse is undefined: kappa_d = inf only with kappa_s = inf
  bool jz_joint(const double *c) { return !(c[3] == INF && c[2] != INF); }

  const LawSpec LAWS[NLAWS] = {
      {"rough", LawKind::ROUGH, 2,
       {{"r", 0.0, 1.0, false, "0 <= r <= 1"}, {"beta", -1.0, 1.0, false, "-1 <= beta <= 1"}},
       1.0, "r beta", nullptr, nullptr,
       [](const double *c) { return LawParams::rough(c[0], c[1]); }},
      {"walton", LawKind::WALTON, 3,
       {{"r", 0.0, 1.0, false, "0 <= r <= 1"},
        {"mu", 0.0, INF, true, "mu >= 0, or inf"},
        {"rtmax", -1.0, 1.0, false, "-1 <= rtmax <= 1"}},
       1.0, "r mu rtmax", nullptr, nullptr,
       [](const double *c) { return LawParams::walton(c[0], c[1], c[2]); }},
      {"jz", LawKind::JZ, 4,
       {{"qn", 0.0, 0.5, false, "0 <= qn <= 0.5"},
        {"qt", 0.0, 1.0, false, "0 <= qt <= 1"},
        {"kappa_s", 0.0, INF, true, "kappa_s >= 0, or inf"},
        {"kappa_d", 0.0, INF, true, "kappa_d >= 0, or inf"}},
       0.0, "qn qt kappa_s kappa_d",
       "kappa_d = inf needs kappa_s = inf (an infinite sliding impulse is undefined)", jz_joint,
       [](const double *c) { return LawParams::jz(c[0], c[1], c[2], c[3]); }},
  };

  // viscoelastic vref: the law's r is the restitution at normal speed vref
  const char *at_reference_speed(LawParams &law, const double *c)
  {
    if (!(law.r > 0.0)) return "a viscoelastic restitution is never 0: give the restitution at vref > 0";
    law.visco = viscoelastic_delta(law.r) / std::pow(c[0], 0.2);
    law.visco_material = false;
    return nullptr;
  }

  // viscoelastic/material Y nu A: A alpha^(2/5) without the pair's R_eff^(1/5) m_eff^(-2/5)
  const char *from_material(LawParams &law, const double *c)
  {
    law.r = 1.0;
    law.visco = c[2] * std::pow(std::pow(1.5, 1.5) * c[0] / (1.0 - c[1] * c[1]), 0.4);
    law.visco_material = true;
    return nullptr;
  }

  const RestitutionSpec MODELS[NRESTITUTION] = {
      {"viscoelastic", 1, {{"vref", DBL_MIN, DBL_MAX, false, "vref > 0, finite"}}, "vref", false,
       at_reference_speed},
      {"viscoelastic/material", 3,
       {{"Y", DBL_MIN, DBL_MAX, false, "Y > 0, finite"},
        {"nu", -1.0 + DBL_EPSILON, 0.5, false, "-1 < nu <= 0.5"},
        {"A", 0.0, DBL_MAX, false, "A >= 0, finite"}},
       "Y nu A", true, from_material},
  };
}    // namespace

const RestitutionSpec &restitution_spec(int index)
{
  return MODELS[index];
}

const RestitutionSpec *find_restitution(const char *name)
{
  for (const auto &s : MODELS)
    if (std::strcmp(s.name, name) == 0) return &s;
  return nullptr;
}

int first_bad_restitution_coeff(const RestitutionSpec &s, const double *c)
{
  for (int k = 0; k < s.ncoeff; k++)
    if (!(c[k] >= s.coeff[k].lo && c[k] <= s.coeff[k].hi)) return k;
  return -1;
}

const LawSpec &law_spec(int index)
{
  return LAWS[index];
}

const LawSpec *find_law(const char *name)
{
  for (const auto &s : LAWS)
    if (std::strcmp(s.name, name) == 0) return &s;
  return nullptr;
}

int first_bad_coeff(const LawSpec &s, const double *c)
{
  for (int k = 0; k < s.ncoeff; k++) {
    const LawCoeff &k_ = s.coeff[k];
    if (!(c[k] >= k_.lo && c[k] <= k_.hi)) return k;
    if (c[k] == INF && !k_.inf_ok) return k;
  }
  if (s.joint_ok && !s.joint_ok(c)) return s.ncoeff;
  return -1;
}

}    // namespace granfric
