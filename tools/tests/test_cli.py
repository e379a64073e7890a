# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""The tools' command line: --help of the tool and of every command prints to stdout and exits 0;
an unknown command or paper, or none, exits 2 with a message on stderr."""
import os
import subprocess
import sys

import pytest

TOOL = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "granfric")


def run(*args, **kw):
    return subprocess.run([sys.executable, TOOL, *args], capture_output=True, text=True, **kw)


@pytest.mark.parametrize("args", [["--help"], ["-h"], ["reproduce", "--help"],
                                  ["reproduce", "herbst2005", "--help"],
                                  ["reproduce", "luding1998", "--help"],
                                  ["reproduce", "risso2005", "--help"], ["convection", "--help"],
                                  ["collisions", "--help"]])
def test_help_exits_0_on_stdout(args):
    r = run(*args)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() and not r.stderr.strip()


@pytest.mark.parametrize("args,says", [([], "reproduce"), (["bogus"], "unknown command bogus"),
                                       (["reproduce", "nopaper"], "unknown paper nopaper"),
                                       (["reproduce"], "needs a paper")])
def test_bad_commands_exit_2_on_stderr(args, says):
    r = run(*args)
    assert r.returncode == 2
    assert says in r.stderr and not r.stdout.strip()


def test_every_convection_option_is_explained():
    out = " ".join(run("convection", "--help").stdout.split())
    for opt in ("--kappas", "--q", "--g", "--periods", "--every", "--out"):
        assert opt in out
    assert out.count("(default") == 6, out


@pytest.mark.parametrize("hidden", ["numpy", "scipy", "matplotlib"])
@pytest.mark.parametrize("args", [["reproduce", "herbst2005", "--quick"],
                                  ["convection", "--kappas", "0.03"], ["collisions"]])
def test_a_missing_python_package_gives_a_message_and_exit_2(hidden, args, tmp_path):
    # a module of that name earlier on the path that fails to import, as when it is not installed
    (tmp_path / f"{hidden}.py").write_text(f"raise ImportError('no module named {hidden}')\n")
    env = dict(os.environ, PYTHONPATH=str(tmp_path))
    r = run(*args, env=env, cwd=tmp_path)
    assert r.returncode == 2, r.stderr
    assert "Traceback" not in r.stderr and not r.stdout.strip()
    assert hidden in r.stderr.split("cannot be imported")[0]
    for word in ("python3-numpy", "python3-scipy", "python3-matplotlib",
                 "bash tools/install-deps.sh"):
        assert word in r.stderr
