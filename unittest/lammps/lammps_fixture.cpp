// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
#include "lammps_fixture.h"

#include "input.h"

#include <cstdlib>
#include <sstream>

namespace granfric_test {

bool verbose()
{
  const char *v = std::getenv("GRANFRIC_TEST_VERBOSE");
  return v && *v && std::string(v) != "0";
}

namespace {
std::unique_ptr<LAMMPS_NS::LAMMPS> new_lammps(bool screen)
{
  std::vector<std::string> words = {"granfric_test", "-log", "none", "-nocite"};
  if (!screen) {
    words.push_back("-screen");
    words.push_back("none");
  }
  std::vector<char *> argv;
  for (auto &w : words) argv.push_back(w.data());
  auto lmp = std::make_unique<LAMMPS_NS::LAMMPS>((int) argv.size(), argv.data(), MPI_COMM_WORLD);
  lmp->input->one(std::string("plugin load ") + GRANFRIC_PLUGIN);
  return lmp;
}
}    // namespace

std::unique_ptr<LAMMPS_NS::LAMMPS> make_lammps()
{
  return new_lammps(verbose());
}

void run(LAMMPS_NS::LAMMPS *lmp, const std::string &commands)
{
  std::istringstream in(commands);
  std::string line;
  while (std::getline(in, line))
    if (!line.empty()) lmp->input->one(line);
}

std::string error_of(LAMMPS_NS::LAMMPS *lmp, const std::string &commands)
{
  try {
    run(lmp, commands);
  } catch (LAMMPS_NS::LAMMPSException &e) {
    std::string msg = e.what();
    return msg.substr(0, msg.find('\n'));
  }
  return "";
}

std::string screen_of(const std::string &commands)
{
  ::testing::internal::CaptureStdout();
  {
    auto lmp = new_lammps(true);
    error_of(lmp.get(), commands);
  }
  return ::testing::internal::GetCapturedStdout();
}

}    // namespace granfric_test
