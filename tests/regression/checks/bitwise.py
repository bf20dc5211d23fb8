"""Bitwise identity of dumps (h5diff, no tolerance, /run excluded: it holds
run metadata - deck text, version, command line, rank count, timings).

  bitwise --deck D --ranks 1 2 3 4 [--replace OLD NEW ...]
      the dumps of every rank count are the same files and bitwise identical
  same --deck D --reference R --np N
      D and R write the same dumps, every one bitwise identical: e.g. a
      material given by deck keys against its library set
"""
import os

from checks.common import (add_reference, add_replace, check, dump_names, h5same, run,
                           run_pair, variant_deck)


def cmd_bitwise(args):
    ref = None
    deck = variant_deck(args) if args.replace else args.deck
    for np in args.ranks:
        wd = os.path.join(args.workdir, "np%d" % np)
        code, out, err = run(args, np, wd, deck)
        check("run on %d rank(s) exits 0" % np, code == 0, err[-2000:])
        if code != 0:
            return
        dumps = dump_names(wd)
        if ref is None:
            ref = (wd, dumps)
            check("dumps written", len(dumps) >= 2, " ".join(dumps))
            continue
        check("%d ranks wrote the same dumps as %d" % (np, args.ranks[0]), dumps == ref[1])
        for name in ref[1]:
            same, diff = h5same(os.path.join(ref[0], name), os.path.join(wd, name))
            check("%s bitwise identical on %d and %d ranks" % (name, args.ranks[0], np), same,
                  diff)


def cmd_same(args):
    """--deck and --reference, run on --np ranks, write the same dumps and every one
    is bitwise identical (h5diff, /run excluded)."""
    wd_ref = os.path.join(args.workdir, "reference")
    wd = os.path.join(args.workdir, "run")
    ok, out = run_pair(args, wd_ref, wd)
    if not ok:
        return
    ref = dump_names(wd_ref)
    mine = dump_names(wd)
    check("same dumps written (%d)" % len(ref), mine == ref and len(ref) >= 2, " ".join(mine))
    for name in ref:
        if name in mine:
            same, diff = h5same(os.path.join(wd_ref, name), os.path.join(wd, name))
            check("%s bitwise identical to the reference's" % name, same, diff)


def register(sub, common):
    p = sub.add_parser("bitwise", parents=[common], help="dumps identical on every rank count")
    p.add_argument("--ranks", type=int, nargs="+", default=[1, 2, 3, 4])
    add_replace(p)
    p.set_defaults(func=cmd_bitwise)
    p = sub.add_parser("same", parents=[common], help="two decks write identical dumps")
    add_reference(p)
    p.set_defaults(func=cmd_same)
