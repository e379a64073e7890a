# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""GRANFRIC tools command line.

    /usr/bin/python3 tools/granfric reproduce herbst2005|luding1998|risso2005 [--quick|--full] [--out DIR]
    /usr/bin/python3 tools/granfric collisions [--out DIR]
    /usr/bin/python3 tools/granfric convection --kappas K1 K2 ... [--q Q] [--g G] [--periods P]
(the same as PYTHONPATH=tools /usr/bin/python3 -m granfric ..., or tools/reproduce PAPER)
"""
import os
import sys

if __name__ == "__main__" and not __package__:
    # run as `python3 tools/granfric ...`: import the package from tools/
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    from granfric.__main__ import main as _main
    _main()
    sys.exit(0)


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    if len(argv) >= 2 and argv[0] == "reproduce":
        paper, rest = argv[1], argv[2:]
        if paper == "herbst2005":
            from . import herbst as m
        elif paper == "luding1998":
            from . import luding as m
        elif paper == "risso2005":
            from . import risso as m
        else:
            sys.exit(f"unknown paper {paper}: use herbst2005, luding1998 or risso2005")
        if "--out" not in rest:
            rest += ["--out", f"out/{paper}"]
        return m.main(rest)
    if argv and argv[0] == "convection":
        from . import convection
        return convection.main(argv[1:])
    if argv and argv[0] == "collisions":
        from . import collision_demo
        return collision_demo.main(argv[1:])
    sys.exit(__doc__)


if __name__ == "__main__":
    main()
