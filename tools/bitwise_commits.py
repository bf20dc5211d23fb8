#!/usr/bin/python3
"""Behaviour preserved by a restructuring commit: every regression deck's
final dump bitwise identical (h5diff, /run excluded) between two builds, on
1 and 3 ranks.

Usage:
    bitwise_commits.py [--base HEAD^ | --base-exe EXE] [--head HEAD | --head-exe EXE]
        [--decks tests/regression/{decks,cases/*}/*.nml] [--ranks 1 3]
        [--max-seconds 120] [--workdir /tmp/impact3d_bitwise]

--base and --head are git revisions, each built (Release) in a temporary
worktree under --workdir; --head-exe uses an existing executable instead
(e.g. build/impact3d of the working tree), --base-exe likewise for the
base (a copy of the parent's executable kept from its own check). Decks that fail on the base
build are skipped (a failing deck is its own test's business); decks whose
base run takes longer than --max-seconds are skipped and listed. The exit
code is 1 when any dump differs.
"""

import argparse
import glob
import os
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def build(rev, workdir):
    src = os.path.join(workdir, "src-" + rev.replace("/", "_").replace("^", "p"))
    if os.path.isdir(src):
        subprocess.run(["git", "-C", ROOT, "worktree", "remove", "--force", src])
    subprocess.run(["git", "-C", ROOT, "worktree", "add", "--detach", src, rev], check=True,
                   capture_output=True)
    bdir = os.path.join(src, "build")
    subprocess.run(["cmake", "-S", src, "-B", bdir, "-DCMAKE_BUILD_TYPE=Release"], check=True,
                   capture_output=True)
    subprocess.run(["cmake", "--build", bdir, "-j2", "--target", "impact3d"], check=True,
                   capture_output=True)
    return os.path.join(bdir, "impact3d")


def run(exe, deck, np, wd):
    if os.path.isdir(wd):
        shutil.rmtree(wd)
    os.makedirs(wd)
    shutil.copy(deck, os.path.join(wd, "deck.nml"))
    t = time.time()
    p = subprocess.run(["mpirun", "--oversubscribe", "-np", str(np), exe, "deck.nml"], cwd=wd,
                       env=ENV, capture_output=True, text=True)
    dumps = sorted(glob.glob(os.path.join(wd, "*_[0-9][0-9][0-9][0-9][0-9][0-9].h5")))
    return p.returncode, (dumps[-1] if dumps else None), time.time() - t


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--base", default="HEAD^")
    ap.add_argument("--head", default="HEAD")
    ap.add_argument("--head-exe", default=None)
    ap.add_argument("--base-exe", default=None)
    regression = os.path.join(ROOT, "tests", "regression")
    ap.add_argument("--decks", nargs="*",
                    default=sorted(glob.glob(os.path.join(regression, "decks", "*.nml"))
                                   + glob.glob(os.path.join(regression, "cases", "*", "*.nml"))))
    ap.add_argument("--ranks", nargs="*", type=int, default=[1, 3])
    ap.add_argument("--max-seconds", type=float, default=120.0)
    ap.add_argument("--workdir", default="/tmp/impact3d_bitwise")
    a = ap.parse_args()
    os.makedirs(a.workdir, exist_ok=True)
    base_exe = a.base_exe or build(a.base, a.workdir)
    head_exe = a.head_exe or build(a.head, a.workdir)
    same = differ = skipped = 0
    for deck in a.decks:
        name = os.path.splitext(os.path.basename(deck))[0]
        for np in a.ranks:
            wd = os.path.join(a.workdir, "run", name, "np%d" % np)
            code, base_dump, secs = run(base_exe, deck, np, wd + "-base")
            if code not in (0, 3) or base_dump is None or secs > a.max_seconds:
                print("skip %-28s np %d (base exit %d, %.0f s)" % (name, np, code, secs))
                skipped += 1
                continue
            code2, head_dump, _ = run(head_exe, deck, np, wd + "-head")
            ok = code2 == code and head_dump is not None and \
                os.path.basename(head_dump) == os.path.basename(base_dump)
            if ok:
                p = subprocess.run(["h5diff", "--exclude-path", "/run", base_dump, head_dump],
                                   capture_output=True, text=True)
                ok = p.returncode == 0
            print("%s %-28s np %d %s" % ("same  " if ok else "DIFFER", name, np,
                                          os.path.basename(base_dump)))
            same += ok
            differ += not ok
    print("%d same, %d differ, %d skipped" % (same, differ, skipped))
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
