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

std::unique_ptr<LAMMPS_NS::LAMMPS> make_lammps()
{
  std::vector<std::string> words = {"granfric_test", "-log", "none", "-nocite"};
  if (!verbose()) {
    words.push_back("-screen");
    words.push_back("none");
  }
  std::vector<char *> argv;
  for (auto &w : words) argv.push_back(w.data());
  auto lmp = std::make_unique<LAMMPS_NS::LAMMPS>((int) argv.size(), argv.data(), MPI_COMM_WORLD);
  lmp->input->one(std::string("plugin load ") + GRANFRIC_PLUGIN);
  return lmp;
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

}    // namespace granfric_test
