"""Bitwise identity of dumps (h5diff, no tolerance, /run excluded: it holds
run metadata - deck text, version, command line, rank count, timings).

  bitwise --deck D --ranks 1 2 3 4 [--replace OLD NEW ...] [--history]
          [--history-except SUFFIX ...]
      the dumps of every rank count are the same files and bitwise identical;
      with --history also history.txt and every probe_*.csv, byte for byte
      (with --history-except, the columns whose names end in one of the
      suffixes are left out, every other column compared as text)
  same --deck D --reference R --np N
      D and R write the same dumps, every one bitwise identical: e.g. a
      material given by deck keys against its library set
"""
import glob
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
        if args.history:
            same_text_files(ref[0], wd, "%d and %d ranks" % (args.ranks[0], np),
                            args.history_except or [])
        for name in ref[1]:
            same, diff = h5same(os.path.join(ref[0], name), os.path.join(wd, name))
            check("%s bitwise identical on %d and %d ranks" % (name, args.ranks[0], np), same,
                  diff)


def same_text_files(a, b, what, except_suffixes):
    """history.txt and the probe CSVs of run directories a and b: the same
    bytes; with except_suffixes, history.txt's columns whose names end in
    one of them are left out and every other column's text compared."""
    names = ["history.txt"] + sorted(os.path.basename(p)
                                     for p in glob.glob(os.path.join(a, "probe_*.csv")))
    for name in names:
        pa, pb = os.path.join(a, name), os.path.join(b, name)
        if not os.path.exists(pb):
            check("%s written on %s" % (name, what), False, pb)
            continue
        ta, tb = open(pa, "rb").read(), open(pb, "rb").read()
        if name != "history.txt" or not except_suffixes:
            where = ""
            if ta != tb:
                la, lb = ta.split(b"\n"), tb.split(b"\n")
                first = next((i for i in range(min(len(la), len(lb))) if la[i] != lb[i]),
                             min(len(la), len(lb)))
                where = "first different line %d" % (first + 1)
            check("%s byte for byte identical on %s (%d bytes)" % (name, what, len(ta)),
                  ta == tb and len(ta) > 0, where)
            continue
        la, lb = ta.decode().splitlines(), tb.decode().splitlines()
        header = la[0].split()[1:]
        keep = [i for i, n in enumerate(header) if not n.endswith(tuple(except_suffixes))]
        left = [n for n in header if n.endswith(tuple(except_suffixes))]
        bad = []
        if la[0] != lb[0] or len(la) != len(lb):
            bad.append("header or row count")
        else:
            for i in range(1, len(la)):
                wa, wb = la[i].split(), lb[i].split()
                for j in keep:
                    if wa[j] != wb[j]:
                        bad.append("row %d column %s" % (i, header[j]))
        check("history.txt identical on %s, %d rows, every column but %s (%d compared)"
              % (what, len(la) - 1, ", ".join(left), len(keep)),
              not bad and len(la) > 1, "; ".join(bad[:5]))


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
    p.add_argument("--history", action="store_true",
                   help="history.txt and the probe CSVs byte for byte too")
    p.add_argument("--history-except", nargs="+", metavar="SUFFIX",
                   help="history columns (name suffixes) left out of --history")
    add_replace(p)
    p.set_defaults(func=cmd_bitwise)
    p = sub.add_parser("same", parents=[common], help="two decks write identical dumps")
    add_reference(p)
    p.set_defaults(func=cmd_same)
