# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""GRANFRIC tools command line.

    /usr/bin/python3 tools/granfric reproduce herbst2005|luding1998|risso2005 [--quick|--full] [--out DIR]
    /usr/bin/python3 tools/granfric collisions [--out DIR]
    /usr/bin/python3 tools/granfric shear [--quick|--full] [--out DIR]
    /usr/bin/python3 tools/granfric usf [--quick|--full] [--out DIR]
    /usr/bin/python3 tools/granfric usf_grad [--quick|--full] [--out DIR]
    /usr/bin/python3 tools/granfric convection --kappas K1 K2 ... [--q Q] [--g G] [--periods P]
(the same as PYTHONPATH=tools /usr/bin/python3 -m granfric ..., or tools/reproduce PAPER)

Each command takes --help for its options (reproduce PAPER --help, convection --help, ...).
"""
import os
import sys

if __name__ == "__main__" and not __package__:
    # run as `python3 tools/granfric ...`: import the package from tools/
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    from granfric.__main__ import main as _main
    sys.exit(_main())


PAPERS = ("herbst2005", "luding1998", "risso2005")
HELP = ("-h", "--help")


def main(argv=None):
    """Run a command; --help (of the tool or of a command) prints to stdout and returns 0, an
    unknown command or paper exits with a message on stderr and status 2."""
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv and argv[0] in HELP:
        print(__doc__)
        return 0
    if argv[:1] == ["reproduce"] and (len(argv) < 2 or argv[1] in HELP):
        if len(argv) < 2:
            sys.stderr.write("reproduce needs a paper: " + ", ".join(PAPERS) + "\n")
            return 2
        print("reproduce PAPER [--quick|--full] [--out DIR]: the figures and report of one paper "
              "(" + ", ".join(PAPERS) + "); PAPER --help lists its options")
        return 0
    if argv and argv[0] in ("reproduce", "convection", "collisions", "shear", "usf", "usf_grad"):
        from .cli import require_deps
        if require_deps():
            return 2
    if len(argv) >= 2 and argv[0] == "reproduce":
        paper, rest = argv[1], argv[2:]
        if paper == "herbst2005":
            from . import herbst as m
        elif paper == "luding1998":
            from . import luding as m
        elif paper == "risso2005":
            from . import risso as m
        else:
            sys.stderr.write(f"unknown paper {paper}: use herbst2005, luding1998 or risso2005\n")
            return 2
        if "--out" not in rest:
            rest += ["--out", f"out/{paper}"]
        return m.main(rest)
    if argv and argv[0] == "convection":
        from . import convection
        return convection.main(argv[1:])
    if argv and argv[0] == "collisions":
        from . import collision_demo
        return collision_demo.main(argv[1:])
    if argv and argv[0] in ("shear", "usf", "usf_grad"):
        from . import shear, usf, usf_grad
        rest = argv[1:] + ([] if "--out" in argv else ["--out", f"out/{argv[0]}"])
        return {"shear": shear, "usf": usf, "usf_grad": usf_grad}[argv[0]].main(rest)
    sys.stderr.write((f"unknown command {argv[0]}\n\n" if argv else "") + __doc__ + "\n")
    return 2


if __name__ == "__main__":
    sys.exit(main())
