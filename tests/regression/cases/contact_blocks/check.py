#!/usr/bin/python3
"""A contact surface given by blocks (surface_a = 'block:NAME': every exterior
face of the block's zones, symmetry-plane and rigid-wall faces left out) is
the surface of the deck naming the same faces as face sets.

Usage: check.py EXE WORKDIR [--mpiexec mpirun]

Decks (each as named face sets and as blocks):
* the planar Sedov split (problems/sedov_contact, 18^3, DAM and DLM) to
  t = 0.3, with rigid walls on the outer faces ymax, zmax and right_xmax so
  that each block's only open face is the contact face: block:left is
  left_xmax, block:right is right_xmin;
* the equal bars (tests/regression/decks, DAM and DLM): each bar's open
  faces are its two ends (the sides are symmetry planes), so block:left is
  'left_xmin, left_xmax'.
Criteria, on 1 and 3 ranks: every dump of the block deck equal to the named
deck's (h5diff, /run excluded: it holds the deck text), the history files
byte-equal, the same count of contact nodes, and contact happened (some
history row has active pairs), so the comparison is not between two runs
without contact.
"""

import argparse
import glob
import os
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..", "..", "..")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
FAILED = []


def check(name, ok, detail=""):
    print(("PASS " if ok else "FAIL ") + name + ("" if ok or not detail else ": " + detail))
    if not ok:
        FAILED.append(name)


def sedov(method):
    text = open(os.path.join(ROOT, "problems", "sedov_contact",
                             "sedov_contact_%s_18.nml" % method)).read()
    text = text.replace("t_end = 1.0", "t_end = 0.3").replace("dump_interval = 0.25",
                                                              "dump_interval = 0.1")
    walls = "".join("&boundary set = '%s', type = 'wall' /\n" % s
                    for s in ("ymax", "zmax", "right_xmax"))
    text = text.replace("&contact", walls + "&contact", 1)
    named = "surface_a = 'left_xmax', surface_b = 'right_xmin'"
    return text, text.replace(named, "surface_a = 'block:left', surface_b = 'block:right'")


def bars(method):
    text = open(os.path.join(ROOT, "tests", "regression", "decks",
                             "bars_equal_%s.nml" % method)).read()
    old = "surface_a = 'left_xmax', surface_b = 'right_xmin'"
    named = text.replace(old, "surface_a = 'left_xmin, left_xmax', "
                         "surface_b = 'right_xmin, right_xmax'")
    return named, text.replace(old, "surface_a = 'block:left', surface_b = 'block:right'")


def run(a, name, text, np):
    wd = os.path.join(a.workdir, name)
    shutil.rmtree(wd, ignore_errors=True)
    os.makedirs(wd)
    with open(os.path.join(wd, "deck.nml"), "w") as f:
        f.write(text)
    p = subprocess.run([a.mpiexec, "--oversubscribe", "-np", str(np), os.path.abspath(a.exe),
                        "deck.nml"], cwd=wd, env=ENV, capture_output=True, text=True)
    nodes = re.findall(r"of (\d+) contact nodes", p.stdout)
    return wd, p.returncode, nodes


def active_rows(wd):
    lines = open(os.path.join(wd, "history.txt")).read().splitlines()
    header = lines[0].lstrip("#").split()
    col = [i for i, h in enumerate(header) if h.endswith("_active")][0]
    return sum(1 for line in lines[1:] if float(line.split()[col]) > 0)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("workdir")
    ap.add_argument("--mpiexec", default="mpirun")
    a = ap.parse_args()
    for label, make in (("sedov", sedov), ("bars", bars)):
        for method in ("dam", "dlm"):
            named, block = make(method)
            for np in (1, 3):
                tag = "%s_%s_np%d" % (label, method, np)
                wn, cn, nn = run(a, tag + "_named", named, np)
                wb, cb, nb = run(a, tag + "_block", block, np)
                check(tag + ": both runs complete", cn == 0 and cb == 0,
                      "exit %d and %d" % (cn, cb))
                if cn != 0 or cb != 0:
                    continue
                dumps = sorted(os.path.basename(p) for p in glob.glob(os.path.join(wn, "*.h5")))
                other = sorted(os.path.basename(p) for p in glob.glob(os.path.join(wb, "*.h5")))
                same = dumps == other and len(dumps) > 1
                for d in dumps if same else []:
                    p = subprocess.run(["h5diff", "--exclude-path", "/run", os.path.join(wn, d),
                                        os.path.join(wb, d)], capture_output=True)
                    same = same and p.returncode == 0
                check(tag + ": every dump bitwise equal (%d dumps)" % len(dumps), same)
                hist = open(os.path.join(wn, "history.txt"), "rb").read() == \
                    open(os.path.join(wb, "history.txt"), "rb").read()
                check(tag + ": history byte-equal", hist)
                check(tag + ": same contact nodes", nn == nb and len(nn) == 1,
                      "%s and %s" % (nn, nb))
                rows = active_rows(wb)
                check(tag + ": contact active (%d rows)" % rows, rows > 0)
    print("%d failed" % len(FAILED))
    return 1 if FAILED else 0


if __name__ == "__main__":
    sys.exit(main())
