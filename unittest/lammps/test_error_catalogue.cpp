// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// Every invalid input of the GRANFRIC styles ends the run with an ERROR line that names the
// offending keyword or value: one test per entry of error_catalogue.yaml. An entry gives a
// setup (a named block of commands that must run), input lines of which every one but the last
// must run too, the text the ERROR line of the last one must contain, and the word of the
// input (keyword or value) that text names.
#include "lammps_fixture.h"

#include <yaml-cpp/yaml.h>

#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace granfric_test;

namespace {

struct Entry {
  std::string name, setup, input, error, names;
};

// (for gtest's messages)
void PrintTo(const Entry &e, std::ostream *os)
{
  *os << e.name;
}

std::vector<Entry> load_catalogue()
{
  const YAML::Node doc = YAML::LoadFile(GRANFRIC_ERROR_CATALOGUE);
  std::map<std::string, std::string> setups;
  for (const auto &s : doc["setups"]) setups[s.first.as<std::string>()] = s.second.as<std::string>();
  std::vector<Entry> entries;
  for (const auto &e : doc["entries"]) {
    // (an entry for the other host only: see the catalogue's head)
    if (e["host"] && e["host"].as<std::string>() != "lammps") continue;
    const auto setup = e["setup"].as<std::string>();
    // (an unknown setup name is reported by the test of the entry)
    entries.push_back({e["name"].as<std::string>(), setups.count(setup) ? setups[setup] : "",
                       e["input"].as<std::string>(), e["error"].as<std::string>(),
                       e["names"].as<std::string>()});
  }
  return entries;
}

std::vector<std::string> lines_of(const std::string &text)
{
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line))
    if (!line.empty()) lines.push_back(line);
  return lines;
}

class ErrorCatalogue : public ::testing::TestWithParam<Entry> {};

TEST_P(ErrorCatalogue, EndsWithAnErrorNamingTheInput)
{
  const Entry &e = GetParam();
  ASSERT_FALSE(e.setup.empty()) << "no such setup in the catalogue";
  ASSERT_NE(e.error.find(e.names), std::string::npos) << "the expected text names '" << e.names << "'";
  ASSERT_NE((e.setup + e.input).find(e.names), std::string::npos)
      << "'" << e.names << "' is not a word of the input";
  auto lmp = make_lammps();
  ASSERT_EQ(error_of(lmp.get(), e.setup), "") << "the setup must run";
  const std::vector<std::string> lines = lines_of(e.input);
  ASSERT_FALSE(lines.empty());
  for (size_t k = 0; k + 1 < lines.size(); k++)
    ASSERT_EQ(error_of(lmp.get(), lines[k]), "") << "only the last line may fail: " << lines[k];
  const std::string msg = error_of(lmp.get(), lines.back());
  EXPECT_EQ(msg.rfind("ERROR", 0), 0u) << "no ERROR line for: " << lines.back() << "\n  got: " << msg;
  EXPECT_NE(msg.find(e.error), std::string::npos)
      << "the ERROR line\n  " << msg << "\ndoes not contain\n  " << e.error;
}

INSTANTIATE_TEST_SUITE_P(Inputs, ErrorCatalogue, ::testing::ValuesIn(load_catalogue()),
                         [](const ::testing::TestParamInfo<Entry> &info) { return info.param.name; });

}    // namespace
