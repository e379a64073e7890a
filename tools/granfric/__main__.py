"""GRANFRIC tools command line.

    PYTHONPATH=tools /usr/bin/python3 -m granfric reproduce herbst2005|luding1998|risso2005 [--quick|--full] [--out DIR]
    PYTHONPATH=tools /usr/bin/python3 -m granfric collisions [--out DIR]
(or tools/reproduce PAPER [--quick|--full])
"""
import sys


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
    if argv and argv[0] == "collisions":
        from . import collision_demo
        return collision_demo.main(argv[1:])
    sys.exit(__doc__)


if __name__ == "__main__":
    main()
