# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""GRANFRIC Python tools: theory, analysis and plots for the GRANFRIC LAMMPS package.

Put <repo>/tools on sys.path (PYTHONPATH=tools) and import granfric.<module>.
Uses Debian's python3-numpy / scipy / matplotlib (run with /usr/bin/python3).
"""
