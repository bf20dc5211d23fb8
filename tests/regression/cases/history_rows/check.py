#!/usr/bin/python3
"""Restarts of long and wide histories (issue 33, item 1).

Usage: check.py long  EXE WORKDIR MPIEXEC
       check.py wide  EXE WORKDIR MPIEXEC

long: long_history.nml (6000 cycles, a history row and a probe row each,
      restart dump at cycle 3000) run on 1 rank, then restarted from its
      cycle-3000 dump on 1 rank (a second rank polling in MPI on an
      oversubscribed machine would take the first one's processor and be
      measured too), the files of the first run in place:
  * the first run stops at max_cycles (exit 3) and prints the timing report
    (its `set-up` line is the fresh start's set-up time);
  * the restart's `set-up` line is below max(10 x the fresh start's, 0.5 s):
    keeping 3001 rows of each file must cost time linear in their length (a
    few microseconds a row); the earlier code rebuilt an array row by row
    on 4096- and 8192-character records, 50 s for 1580 rows;
  * history.txt (>= 5000 rows) and probe_corner.csv after the restart are
    byte for byte those of the uninterrupted run (the rows kept and the rows
    written after the restart).
wide: a deck of 48 materials (one zone each; 4 history columns each), so
      that a history row is wider than 4096 characters, run 40 cycles with a
      dump at cycle 20 on 1 rank, restarted from it on 2 ranks:
  * the rows are wider than 4096 characters (the old restart buffer);
  * every row kept by the restart (cycles 0 to 20) is byte for byte the
    uninterrupted run's row, and so is the whole file.
"""

import os
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
FAILED = []
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")


def check(name, ok, detail=""):
    print(("PASS " if ok else "FAIL ") + name + (": " + detail if detail else ""))
    sys.stdout.flush()
    if not ok:
        FAILED.append(name)


def fresh(wd):
    if os.path.isdir(wd):
        shutil.rmtree(wd)
    os.makedirs(wd)


def run(mpiexec, np, exe, wd, deck, extra=()):
    p = subprocess.run([mpiexec, "-np", str(np), exe] + list(extra) + [deck], cwd=wd,
                       env=ENV, capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


def setup_seconds(out):
    m = re.search(r"^ +set-up +([0-9.]+)$", out, re.M)
    return float(m.group(1)) if m else None


def restarted_copy(full, wr, names):
    """wr: a new directory with the first run's deck and text files (the
    restart reads and rewrites them)."""
    fresh(wr)
    for n in names:
        shutil.copy(os.path.join(full, n), os.path.join(wr, n))


def cmd_long(exe, wd, mpiexec):
    full = os.path.join(wd, "full")
    fresh(full)
    shutil.copy(os.path.join(HERE, "long_history.nml"), os.path.join(full, "deck.nml"))
    code, out, err = run(mpiexec, 1, exe, full, "deck.nml")
    check("uninterrupted run stops at max_cycles (exit 3)", code == 3, err[-1000:])
    fresh_setup = setup_seconds(out)
    check("it prints the timing report with its set-up line", fresh_setup is not None,
          out[-1000:])
    start = os.path.join(full, "dump_003000.h5")
    if code != 3 or fresh_setup is None or not os.path.exists(start):
        check("mid-run dump exists", os.path.exists(start))
        return
    names = ["deck.nml", "history.txt", "probe_corner.csv"]
    rows = sum(1 for _ in open(os.path.join(full, "history.txt"))) - 1
    check("history has at least 5000 rows (%d)" % rows, rows >= 5000)
    wr = os.path.join(wd, "restarted")
    restarted_copy(full, wr, names)
    # One rank, like the fresh run: on an oversubscribed machine a second
    # rank polling in MPI takes the first one's processor and its set-up
    # time would measure that.
    code, out, err = run(mpiexec, 1, exe, wr, "deck.nml", ["--restart", start])
    check("restart on 1 rank stops at max_cycles (exit 3)", code == 3, err[-1000:])
    t = setup_seconds(out)
    bound = max(10.0 * fresh_setup, 0.5)
    check("restart set-up %s s below max(10 x fresh %.3f s, 0.5 s) = %.3f s"
          % (t, fresh_setup, bound), t is not None and t < bound, out[-600:])
    for n in names[1:]:
        a = open(os.path.join(full, n), "rb").read()
        b = open(os.path.join(wr, n), "rb").read()
        check("%s after the restart byte for byte the uninterrupted run's (%d bytes)"
              % (n, len(a)), a == b)


def wide_deck(path):
    n = 48
    lines = ["! 48 materials, one zone each: history rows of 12 + 48 x 4 columns (4900",
             "! characters). Sod-like: dense left half.",
             "&control title = 'wide history', t_end = 100.0, max_cycles = 40 /",
             "&mesh x = 0.0, 4.8, nx = %d, y = 0.0, 0.1, ny = 1, z = 0.0, 0.1, nz = 1 /" % n]
    for k in range(n):
        lines.append("&material name = 'gas%02d', eos = 'ideal_gas', gamma = 1.4 /" % (k + 1))
        lines.append("&block name = 'b%02d', material = 'gas%02d', box = %.2f, %.2f, -1, 1, "
                     "-1, 1 /" % (k + 1, k + 1, 0.1 * k, 0.1 * (k + 1)))
    lines.append("&region density = 0.125, energy = 2.0 /")
    lines.append("&region box = 0, 2.4, -1, 1, -1, 1, density = 1.0, energy = 2.5 /")
    for s in ("xmin", "xmax", "ymin", "ymax", "zmin", "zmax"):
        lines.append("&boundary set = '%s', type = 'symmetry' /" % s)
    lines.append("&output status_every = 100000, dump_cycles = 20 /")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def cmd_wide(exe, wd, mpiexec):
    full = os.path.join(wd, "full")
    fresh(full)
    wide_deck(os.path.join(full, "deck.nml"))
    code, out, err = run(mpiexec, 1, exe, full, "deck.nml")
    check("uninterrupted run stops at max_cycles (exit 3)", code == 3, err[-1000:])
    start = os.path.join(full, "dump_000020.h5")
    if code != 3 or not os.path.exists(start):
        check("mid-run dump exists", os.path.exists(start))
        return
    a = open(os.path.join(full, "history.txt"), "rb").read()
    width = min(len(r) for r in a.split(b"\n")[1:] if r)
    check("every history row wider than 4096 characters (narrowest %d)" % width, width > 4096)
    wr = os.path.join(wd, "restarted")
    restarted_copy(full, wr, ["deck.nml", "history.txt"])
    code, out, err = run(mpiexec, 2, exe, wr, "deck.nml", ["--restart", start])
    check("restart on 2 ranks stops at max_cycles (exit 3)", code == 3, err[-1000:])
    b = open(os.path.join(wr, "history.txt"), "rb").read()
    ra, rb = a.split(b"\n"), b.split(b"\n")
    kept = [r for r in ra[1:] if r and int(r.split()[0]) <= 20]
    same = [i for i, r in enumerate(kept) if i + 1 < len(rb) and rb[i + 1] == r]
    check("the %d rows kept (cycles 0 to 20) byte for byte the uninterrupted run's"
          % len(kept), len(kept) == 21 and len(same) == len(kept))
    check("the whole history after the restart byte for byte the uninterrupted run's "
          "(%d bytes)" % len(a), a == b)


def main():
    what, exe, wd, mpiexec = sys.argv[1], os.path.abspath(sys.argv[2]), \
        os.path.abspath(sys.argv[3]), sys.argv[4]
    {"long": cmd_long, "wide": cmd_wide}[what](exe, wd, mpiexec)


if __name__ == "__main__":
    main()
    print("FAILED: " + ", ".join(FAILED) if FAILED else "all checks passed")
    sys.exit(1 if FAILED else 0)
