# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""bench/peers: the side-by-side benchmark against a stand-alone event-driven code.

The peer's source is not part of GRANFRIC, so these tests check the driver with a stand-in: a
small C program with the peer's globals and output lines. They check that the globals are set
for each point (and a changed source is refused), that the outputs are read, that the guard
flags different physics, and that one whole run measures both programs and writes the table.
"""
import csv
import os
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "bench"))
import peers  # noqa: E402

STAND_IN = r"""
#include <stdio.h>
double maxtime = 100;
int initialconfig = 0;
int N = 4000;
double packfrac = 0.25;
int main(void)
{
    /* a stand-in: as many collisions as particles per time unit, the pressure of an ideal gas */
    printf("Simtime: %lf, Collisions: %u, Press: 0\n", maxtime, (unsigned) (N * maxtime));
    printf("Measured pressure     : %lf + %lf = %lf\n", 0.0, 1.0, 1.0);
    return packfrac > 0 && initialconfig == 1 ? 0 : 1;
}
"""


def stand_in(tmp_path):
    d = tmp_path / "Single"
    d.mkdir()
    (d / "mdSingle.c").write_text(STAND_IN)
    (d / "mdSingle.h").write_text("")
    (d / "mt19937ar.c").write_text("")
    return str(tmp_path)


def test_globals_are_set_once_each():
    text = peers.patch_peer_source(STAND_IN, 32000, 0.45, 4.0)
    for line in ("double maxtime = 4.0;", "int initialconfig = 1;", "int N = 32000;",
                 "double packfrac = 0.45;"):
        assert line in text
    with pytest.raises(ValueError, match="packfrac"):
        peers.patch_peer_source(STAND_IN.replace("double packfrac = 0.25;", ""), 32000, 0.45, 4.0)


def test_fcc_sizes():
    assert peers.fcc_cells(32000) == 20 and peers.fcc_cells(1000188) == 63
    with pytest.raises(ValueError, match="4 ncell"):
        peers.fcc_cells(1000)


def test_outputs_are_read():
    out = ("Simtime: 1.0, Collisions: 10, Press: 2\nSimtime: 2.0, Collisions: 25, Press: 3\n"
           "Measured pressure     : 6.391564 + 0.859437 = 7.251001\n")
    assert peers.parse_peer(out) == (25, 7.251001)
    ours = "x\nPEERS N 500 phi 0.25 time 1 steps 3 collisions 1234 pressure 1.500000\n"
    assert peers.parse_granfric(ours) == (1234, 1.5)
    with pytest.raises(ValueError):
        peers.parse_granfric("no such line")


def test_guard():
    assert peers.agree(100000, 101500) and not peers.agree(100000, 97000)
    assert not peers.agree(0, 0)


def test_missing_peer_is_a_clear_error(tmp_path):
    with pytest.raises(SystemExit, match="GRANFRIC_PEER"):
        peers.find_peer(None)
    with pytest.raises(SystemExit, match="mdSingle.c"):
        peers.find_peer(str(tmp_path))


def test_one_run_measures_both_and_flags_other_physics(tmp_path):
    src = peers.find_peer(stand_in(tmp_path))
    rows = peers.run([(500, 0.25, 1.0, 2.0)], src, 1, str(tmp_path / "out"))
    r = rows[0]
    assert r["coll_peer"] == 500 and r["coll_granfric"] > 500     # hard spheres collide more
    assert not r["same_physics"]
    assert r["cpu_peer"] > 0 and r["cpu_granfric"] > 0 and r["rss_granfric"] > 0
    with open(tmp_path / "out" / "peers.csv") as fh:
        assert len(list(csv.DictReader(fh))) == 1
