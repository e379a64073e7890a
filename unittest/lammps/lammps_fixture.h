// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC LAMMPS-side tests: helpers to drive LAMMPS through its C++ API with the plugin loaded
// (in the style of LAMMPS's unittest/testing/core.h).
#ifndef GRANFRIC_TEST_LAMMPS_FIXTURE_H
#define GRANFRIC_TEST_LAMMPS_FIXTURE_H

#include "exceptions.h"
#include "lammps.h"

#include <gtest/gtest.h>
#include <mpi.h>

#include <memory>
#include <regex>
#include <string>
#include <vector>

namespace granfric_test {

// path of granfricplugin.so, compiled in
#ifndef GRANFRIC_PLUGIN
#error "GRANFRIC_PLUGIN must be defined"
#endif

bool verbose();

// a LAMMPS instance with the GRANFRIC plugin loaded; output goes nowhere unless verbose.
// LAMMPS registers a plugin file with the first live instance that loads it: keep one instance
// alive at a time.
std::unique_ptr<LAMMPS_NS::LAMMPS> make_lammps();

// run commands, one per line (a string may hold several lines)
void run(LAMMPS_NS::LAMMPS *lmp, const std::string &commands);

// the LAMMPS error message (first line) thrown by the commands, or "" when none is thrown
std::string error_of(LAMMPS_NS::LAMMPS *lmp, const std::string &commands);

// what a fresh LAMMPS instance with the plugin loaded prints to the screen (warnings included)
// while it runs the commands; no other instance may be alive meanwhile
std::string screen_of(const std::string &commands);

}    // namespace granfric_test

// expect that the commands fail with an error message that matches regex RE
#define EXPECT_LMP_ERROR(lmp, commands, re)                                                     \
  do {                                                                                          \
    const std::string _msg = granfric_test::error_of(lmp, commands);                            \
    EXPECT_FALSE(_msg.empty()) << "no error for: " << (commands);                               \
    EXPECT_TRUE(std::regex_search(_msg, std::regex(re)))                                        \
        << "error message\n  " << _msg << "\ndoes not match\n  " << (re);                      \
  } while (0)

#endif
