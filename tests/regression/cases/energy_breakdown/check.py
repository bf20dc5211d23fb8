#!/usr/bin/python3
"""Per-material energy columns of history.txt (<material>_internal,
_kinetic, _plastic_work, _hourglass).

Usage: check.py EXE WORKDIR [--mpiexec mpirun --np 2]

Runs two decks of tests/regression/decks:
  taylor_small.nml          Steinberg-Guinan copper rod on a rigid wall
                            (plastic flow, viscous hourglass control)
  bars_dissimilar_dlm.nml   elastic Al bar onto an elastic steel bar
                            (two materials, yield stress 1e3 Mbar: elastic)

Criteria (none taken from a measurement):
  sum     at every row, the sum over materials of _internal equals
          internal_energy and of _kinetic equals kinetic_energy within the
          round-off of summing n positive terms in another order,
          2 (n + 2) eps X (n = zones + nodes of the mesh, eps = 2.2e-16,
          X the column's value; the 2 for the 16 digits the history prints);
          the nodal masses are the corners' eighths of the zone masses, so
          the two sums are the same terms.
  plastic taylor: plastic work >= 0, non-decreasing row to row (each zone
          adds sbar dp V >= 0 and the sum is taken in a fixed order), > 0
          at the end (the rod deforms plastically), and at every row at most
          the increase of the internal energy since t = 0 (plastic work is
          dissipated into internal energy; the rest of that increase, the
          elastic, compression, viscous and hourglass parts, is >= 0),
          allowing 1e-12 of the initial total energy for round-off.
  elastic bars: plastic work exactly 0 for both materials at every row.
  hourglass  viscous hourglass forces only dissipate: the column is >= 0
          and non-decreasing (each increment is dt kappa/4 rho c V^2/3
          |gamma . v|^2 >= 0).
"""

import argparse
import os
import shutil
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
DECKS = os.path.join(HERE, "..", "..", "decks")
EPS = np.finfo(float).eps
FAILED = []


def check(name, ok, detail=""):
    print(("PASS " if ok else "FAIL ") + name + (": " + detail if detail else ""))
    if not ok:
        FAILED.append(name)


def history(wd):
    with open(os.path.join(wd, "history.txt")) as f:
        names = f.readline().split()[1:]
        rows = np.array([[float(v) for v in line.split()] for line in f if line.strip()])
    return {n: rows[:, i] for i, n in enumerate(names)}


def run(a, deck, wd):
    if os.path.isdir(wd):
        shutil.rmtree(wd)
    os.makedirs(wd)
    cmd = [a.mpiexec, "-np", str(a.np), os.path.abspath(a.exe), os.path.join(DECKS, deck)]
    p = subprocess.run(cmd, cwd=wd, capture_output=True, text=True)
    if p.returncode != 0:
        print(p.stdout + p.stderr)
        check(deck + " runs", False, "exit code %d" % p.returncode)
        sys.exit(1)
    return history(wd)


def mesh_size(wd):
    import h5py
    dumps = sorted(f for f in os.listdir(wd) if f.endswith(".h5"))
    with h5py.File(os.path.join(wd, dumps[0]), "r") as f:
        return f["/mesh/coordinates"].shape[0] + f["/mesh/connectivity"].shape[0]


def sums(tag, h, materials, n):
    for col, suffix in (("internal_energy", "internal"), ("kinetic_energy", "kinetic")):
        total = sum(h[m + "_" + suffix] for m in materials)
        bound = 2 * (n + 2) * EPS * np.abs(h[col])
        err = np.abs(total - h[col])
        check("%s: sum over materials of _%s = %s" % (tag, suffix, col),
              bool(np.all(err <= bound)), "largest error %.3e, bound at that row %.3e"
              % (err.max(), bound[np.argmax(err)]))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("workdir")
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--np", type=int, default=1)
    a = ap.parse_args()

    wd = os.path.join(a.workdir, "taylor")
    h = run(a, "taylor_small.nml", wd)
    sums("taylor", h, ["cu"], mesh_size(wd))
    wp = h["cu_plastic_work"]
    check("taylor: plastic work >= 0", bool(np.all(wp >= 0)))
    check("taylor: plastic work non-decreasing", bool(np.all(np.diff(wp) >= 0)))
    check("taylor: plastic work > 0 at the end", bool(wp[-1] > 0), "%.6e" % wp[-1])
    rise = h["internal_energy"] - h["internal_energy"][0]
    slack = 1e-12 * abs(h["total_energy"][0])
    check("taylor: plastic work <= internal energy increase", bool(np.all(wp <= rise + slack)),
          "final %.6e <= %.6e" % (wp[-1], rise[-1]))
    hg = h["cu_hourglass"]
    check("taylor: hourglass energy >= 0 and non-decreasing",
          bool(np.all(hg >= 0) and np.all(np.diff(hg) >= 0)), "final %.6e" % hg[-1])

    wd = os.path.join(a.workdir, "bars")
    h = run(a, "bars_dissimilar_dlm.nml", wd)
    sums("bars", h, ["al", "ss"], mesh_size(wd))
    check("bars: elastic, plastic work exactly 0",
          bool(np.all(h["al_plastic_work"] == 0) and np.all(h["ss_plastic_work"] == 0)))
    for m in ("al", "ss"):
        hg = h[m + "_hourglass"]
        check("bars: %s hourglass energy >= 0 and non-decreasing" % m,
              bool(np.all(hg >= 0) and np.all(np.diff(hg) >= 0)))

    print("energy_breakdown: %s" % ("FAIL " + ", ".join(FAILED) if FAILED else "PASS"))
    sys.exit(1 if FAILED else 0)


if __name__ == "__main__":
    main()
