# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
# LAMMPS CMake module of the GRANFRIC package (cmake/Modules/Packages/GRANFRIC.cmake in a LAMMPS
# tree, put there by tools/install-in-tree.sh): LAMMPS compiles the styles in src/GRANFRIC
# itself; this adds the physics core in src/GRANFRIC/core, whose headers the styles include by
# name. The plugin registration is not part of an in-tree build.
file(GLOB GRANFRIC_CORE_SOURCES CONFIGURE_DEPENDS ${LAMMPS_SOURCE_DIR}/GRANFRIC/core/[^.]*.cpp)
target_sources(lammps PRIVATE ${GRANFRIC_CORE_SOURCES})
target_include_directories(lammps PRIVATE ${LAMMPS_SOURCE_DIR}/GRANFRIC/core)
