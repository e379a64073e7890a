// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the table of collision laws (see law_table.h and doc/conventions.rst).
#include "law_table.h"

#include <cstring>

namespace granfric {

namespace {
  // an infinite sliding impulse is undefined: kappa_d = inf only with kappa_s = inf
  bool jz_joint(const double *c) { return !(c[3] == INF && c[2] != INF); }

  const LawSpec LAWS[NLAWS] = {
      {"rough", LawKind::ROUGH, 2,
       {{"r", 0.0, 1.0, false, "0 <= r <= 1"}, {"beta", -1.0, 1.0, false, "-1 <= beta <= 1"}},
       "r beta", nullptr, nullptr,
       [](const double *c) { return LawParams::rough(c[0], c[1]); }},
      {"walton", LawKind::WALTON, 3,
       {{"r", 0.0, 1.0, false, "0 <= r <= 1"},
        {"mu", 0.0, INF, true, "mu >= 0, or inf"},
        {"rtmax", -1.0, 1.0, false, "-1 <= rtmax <= 1"}},
       "r mu rtmax", nullptr, nullptr,
       [](const double *c) { return LawParams::walton(c[0], c[1], c[2]); }},
      {"jz", LawKind::JZ, 4,
       {{"qn", 0.0, 0.5, false, "0 <= qn <= 0.5"},
        {"qt", 0.0, 1.0, false, "0 <= qt <= 1"},
        {"kappa_s", 0.0, INF, true, "kappa_s >= 0, or inf"},
        {"kappa_d", 0.0, INF, true, "kappa_d >= 0, or inf"}},
       "qn qt kappa_s kappa_d",
       "kappa_d = inf needs kappa_s = inf (an infinite sliding impulse is undefined)", jz_joint,
       [](const double *c) { return LawParams::jz(c[0], c[1], c[2], c[3]); }},
  };
}    // namespace

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
