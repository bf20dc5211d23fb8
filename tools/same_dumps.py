#!/usr/bin/python3
"""Compare two trees of impact3d dumps bitwise (h5diff, /run excluded).

Usage: same_dumps.py BEFORE_DIR AFTER_DIR [--added PATH ...]

Every *.h5 file under BEFORE_DIR is compared with the file at the same
relative path under AFTER_DIR by `h5diff --exclude-path /run` (the /run
group holds provenance and timings, which differ from run to run). Prints
one line per difference, files present on one side only, and a summary;
exit code 0 when every common dump is identical and nothing is missing.

--added PATH ... leaves datasets out of the comparison (passed to h5diff as
--exclude-path): fields a change adds, which BEFORE's dumps do not have,
e.g. --added /nodes/displacement /zones/von_mises_stress
/restart/initial_position.

Used to show that a change leaves results bitwise unchanged: keep the work
directories of the regression tests from before the change (e.g. a copy of
build/tests/regression/work), run the same tests after it, compare.
Standard library only (h5diff from hdf5-tools).
"""

import os
import subprocess
import sys


def dumps_under(root):
    found = set()
    for here, _, files in os.walk(root):
        for name in files:
            if name.endswith(".h5"):
                found.add(os.path.relpath(os.path.join(here, name), root))
    return found


def main():
    args = sys.argv[1:]
    added = []
    if "--added" in args:
        k = args.index("--added")
        added, args = args[k + 1:], args[:k]
    if len(args) != 2 or not added and "--added" in sys.argv:
        raise SystemExit(__doc__)
    before, after = args
    excluded = ["--exclude-path", "/run"]
    for path in added:
        excluded += ["--exclude-path", path]
    old = dumps_under(before)
    new = dumps_under(after)
    common = sorted(old & new)
    differ = []
    for rel in common:
        proc = subprocess.run(["h5diff"] + excluded + [os.path.join(before, rel),
                               os.path.join(after, rel)], capture_output=True, text=True)
        if proc.returncode != 0:
            differ.append(rel)
            print("DIFFERENT %s\n%s" % (rel, (proc.stdout + proc.stderr)[-500:]))
    for rel in sorted(old - new):
        print("only before: %s" % rel)
    for rel in sorted(new - old):
        print("only after: %s" % rel)
    print("same_dumps: %d dumps compared, %d identical, %d different; %d only before, "
          "%d only after" % (len(common), len(common) - len(differ), len(differ),
                             len(old - new), len(new - old)))
    sys.exit(0 if not differ and not (old - new) else 1)


if __name__ == "__main__":
    main()
