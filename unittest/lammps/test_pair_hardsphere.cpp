// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// Regression tests of the hardsphere/* pair styles, in the shape of LAMMPS's
// unittest/force-styles: one YAML file per case holds the input and the reference values; the
// generic runner checks them after run 0, after write_data + read_data and after write_restart +
// read_restart. `test_pair_hardsphere -g case.yaml` regenerates the reference values.
//
// YAML keys: lammps_version, description, epsilon, input (commands building atoms),
// pair_style, pair_coeff (lines), coeffs (reference: write_coeff lines), contacts (reference: one
// row per pair within contact distance: id1 id2 p1..p8 of compute pair/local, see
// pair_hardsphere.cpp single()).
#include "lammps_fixture.h"

#include "atom.h"
#include "compute.h"
#include "modify.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>

using namespace granfric_test;

namespace {

std::string yaml_file;
bool generate = false;

struct Config {
  std::string description, input, pair_style, pair_coeff, coeffs;
  double epsilon = 1e-13;
  std::vector<std::vector<double>> contacts;
};

Config read_config(const std::string &file)
{
  YAML::Node y = YAML::LoadFile(file);
  Config c;
  c.description = y["description"].as<std::string>("");
  c.epsilon = y["epsilon"].as<double>(1e-13);
  c.input = y["input"].as<std::string>();
  c.pair_style = y["pair_style"].as<std::string>();
  c.pair_coeff = y["pair_coeff"].as<std::string>();
  c.coeffs = y["coeffs"].as<std::string>("");
  if (y["contacts"])
    for (const auto &row : y["contacts"]) c.contacts.push_back(row.as<std::vector<double>>());
  return c;
}

std::string tmpname(const std::string &what)
{
  return "granfric_test_" + std::to_string(::getpid()) + "_" + what;
}

// pair style + coefficients + the diagnostic computes, then run 0
void setup_pair(LAMMPS_NS::LAMMPS *lmp, const Config &c, bool with_coeffs)
{
  run(lmp, "pair_style " + c.pair_style);
  if (with_coeffs) {
    std::istringstream in(c.pair_coeff);
    std::string line;
    while (std::getline(in, line))
      if (!line.empty()) run(lmp, "pair_coeff " + line);
  }
}

std::vector<std::vector<double>> contacts(LAMMPS_NS::LAMMPS *lmp)
{
  run(lmp, "compute gf_pl all pair/local p1 p2 p3 p4 p5 p6 p7 p8\n"
           "compute gf_id all property/local patom1 patom2\n"
           "run 0 post no");
  auto *pl = lmp->modify->get_compute_by_id("gf_pl");
  auto *id = lmp->modify->get_compute_by_id("gf_id");
  pl->compute_local();
  id->compute_local();
  std::vector<std::vector<double>> rows;
  for (int k = 0; k < pl->size_local_rows; k++) {
    double i1 = id->array_local[k][0], i2 = id->array_local[k][1];
    std::vector<double> row = {std::min(i1, i2), std::max(i1, i2)};
    for (int m = 0; m < 8; m++) row.push_back(pl->array_local[k][m]);
    // all eight values are the same seen from either side (g.n and n flip together)
    rows.push_back(row);
  }
  std::sort(rows.begin(), rows.end());
  run(lmp, "uncompute gf_pl\nuncompute gf_id");
  return rows;
}

std::string coeff_lines(LAMMPS_NS::LAMMPS *lmp)
{
  const std::string f = tmpname("coeff");
  run(lmp, "write_coeff " + f);
  std::ifstream in(f);
  std::string line, out;
  while (std::getline(in, line))
    if (line.rfind("pair_coeff", 0) == 0) out += line + "\n";
  std::remove(f.c_str());
  return out;
}

void compare(const std::vector<std::vector<double>> &got, const Config &c, const char *stage)
{
  ASSERT_EQ(got.size(), c.contacts.size()) << stage << ": number of contacts";
  for (size_t k = 0; k < got.size(); k++) {
    ASSERT_EQ(got[k].size(), c.contacts[k].size());
    EXPECT_EQ(got[k][0], c.contacts[k][0]) << stage;
    EXPECT_EQ(got[k][1], c.contacts[k][1]) << stage;
    for (size_t m = 2; m < got[k].size(); m++) {
      const double ref = c.contacts[k][m];
      EXPECT_NEAR(got[k][m], ref, c.epsilon * std::max(1.0, std::fabs(ref)))
          << stage << ": pair " << got[k][0] << "-" << got[k][1] << " value p" << m - 1;
    }
  }
}

void write_config(const std::string &file, const Config &c,
                  const std::vector<std::vector<double>> &rows, const std::string &coeffs)
{
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "lammps_version" << YAML::Value << "4 Feb 2025";
  out << YAML::Key << "description" << YAML::Value << c.description;
  out << YAML::Key << "epsilon" << YAML::Value << c.epsilon;
  out << YAML::Key << "input" << YAML::Value << YAML::Literal << c.input;
  out << YAML::Key << "pair_style" << YAML::Value << c.pair_style;
  out << YAML::Key << "pair_coeff" << YAML::Value << YAML::Literal << c.pair_coeff;
  out << YAML::Key << "coeffs" << YAML::Value << YAML::Literal << coeffs;
  out << YAML::Key << "contacts" << YAML::Value << YAML::BeginSeq;
  out.SetDoublePrecision(17);
  for (const auto &r : rows) out << YAML::Flow << r;
  out << YAML::EndSeq << YAML::EndMap;
  std::ofstream f(file);
  f << "---\n" << out.c_str() << "\n...\n";
}

TEST(PairHardsphere, Reference)
{
  const Config c = read_config(yaml_file);
  auto lmp = make_lammps();
  run(lmp.get(), c.input);
  setup_pair(lmp.get(), c, true);
  const auto rows = contacts(lmp.get());
  const std::string coeffs = coeff_lines(lmp.get());
  if (generate) {
    write_config(yaml_file, c, rows, coeffs);
    GTEST_SKIP() << "regenerated " << yaml_file;
  }
  ASSERT_FALSE(rows.empty()) << "the case must contain contacts";
  EXPECT_EQ(coeffs, c.coeffs) << "coefficients (incl. mixed ones) differ from the reference";
  compare(rows, c, "run 0");

  // approaching and separating pairs both occur, and the law dissipates only when approaching
  int napproach = 0;
  for (const auto &r : rows) {
    if (r[2] < 0.0) ++napproach;
    else EXPECT_EQ(r[4], 0.0);
  }
  EXPECT_GT(napproach, 0);
  EXPECT_LT(napproach, (int) rows.size());
}

TEST(PairHardsphere, DataFileRoundTrip)
{
  const Config c = read_config(yaml_file);
  if (generate) GTEST_SKIP();
  const std::string data = tmpname("data");
  {
    auto lmp = make_lammps();
    run(lmp.get(), c.input);
    setup_pair(lmp.get(), c, true);
    run(lmp.get(), "run 0 post no\nwrite_data " + data + " pair ij");
  }
  auto lmp = make_lammps();
  // the geometry commands before create_box, then the data file instead of the atoms
  std::string pre;
  std::istringstream in(c.input);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("units", 0) == 0 || line.rfind("dimension", 0) == 0 ||
        line.rfind("atom_style", 0) == 0 || line.rfind("boundary", 0) == 0 ||
        line.rfind("comm_modify", 0) == 0)
      pre += line + "\n";
  }
  run(lmp.get(), pre);
  run(lmp.get(), "pair_style " + c.pair_style + "\nread_data " + data);
  std::remove(data.c_str());
  EXPECT_EQ(coeff_lines(lmp.get()), c.coeffs);
  compare(contacts(lmp.get()), c, "write_data/read_data");
}

TEST(PairHardsphere, RestartRoundTrip)
{
  const Config c = read_config(yaml_file);
  if (generate) GTEST_SKIP();
  const std::string rst = tmpname("restart");
  {
    auto lmp = make_lammps();
    run(lmp.get(), c.input);
    setup_pair(lmp.get(), c, true);
    run(lmp.get(), "run 0 post no\nwrite_restart " + rst);
  }
  auto lmp = make_lammps();
  run(lmp.get(), "read_restart " + rst + "\ncomm_modify vel yes");
  std::remove(rst.c_str());
  EXPECT_EQ(coeff_lines(lmp.get()), c.coeffs);
  compare(contacts(lmp.get()), c, "write_restart/read_restart");
}

}    // namespace

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  for (int i = 1; i < argc; i++) {
    std::string a = argv[i];
    if (a == "-g")
      generate = true;
    else
      yaml_file = a;
  }
  if (yaml_file.empty()) {
    std::fprintf(stderr, "usage: %s [-g] case.yaml\n", argv[0]);
    MPI_Finalize();
    return 2;
  }
  const int rc = RUN_ALL_TESTS();
  MPI_Finalize();
  return rc;
}
