"""Regression checks of impact3d runs, each on an exact or physical criterion:
one module per kind of check, each registering its subcommands and their
options (`register(subparsers, common)`). Run them through
tests/regression/check.py SUBCOMMAND ... (CTest does, from the case folders'
case.cmake); `check.py SUBCOMMAND --help` lists a subcommand's options.

Every subcommand takes --exe PATH, --mpiexec PATH, --workdir DIR (its runs'
directories, made afresh), --deck DECK and --np N (default 1); prints a
PASS/FAIL line per criterion, then 'N passed, M failed', and exits 1 on
failure. Needs tools/ on PYTHONPATH (the impact3d_tools package; CTest sets it).
"""
import argparse
import os
import sys

from checks import bitwise, common, contact, exact, health, reference, restart, solids

MODULES = (bitwise, restart, health, exact, solids, contact, reference)


def parser():
    shared = argparse.ArgumentParser(add_help=False)
    shared.add_argument("--exe", required=True, help="the impact3d executable")
    shared.add_argument("--mpiexec", default="mpirun")
    shared.add_argument("--workdir", required=True)
    shared.add_argument("--deck", required=True)
    shared.add_argument("--np", type=int, default=1, help="ranks")
    top = argparse.ArgumentParser(prog="check.py", description=__doc__,
                                  formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = top.add_subparsers(dest="command", required=True, metavar="SUBCOMMAND")
    for module in MODULES:
        module.register(sub, shared)
    return top


def main(argv=None):
    args = parser().parse_args(argv)
    for name in ("deck", "reference", "workdir", "exe"):
        if getattr(args, name, None):
            setattr(args, name, os.path.abspath(getattr(args, name)))
    if hasattr(args, "compare_args"):
        args.compare_args = args.compare_args.split()
    args.func(args)
    npass = sum(common.results)
    print("%d passed, %d failed" % (npass, len(common.results) - npass))
    return 0 if common.results and all(common.results) else 1


if __name__ == "__main__":
    sys.exit(main())
