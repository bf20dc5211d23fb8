#!/usr/bin/python3
"""A cube driven edge-first or vertex-first into a finer plate (issue 16,
item 3): the contact must hold a convex edge or corner that meets the other
surface with a sliver of its area.

Usage: check.py EXE WORKDIR --deck DECK [--mpiexec mpirun --np N]

Criteria (each can fail; none is taken from a measurement):
  * the run exits 0 and the energy balance, with the contact work booked,
    closes to 1e-12 of the initial energy at every row (round-off of the
    compatible scheme);
  * at every audit, no node of either surface is deeper than its tolerance
    (audit_count_a/_b = 0) and no penetrating node is unheld;
  * the deepest cube node (side a) stays within 5% of the plate's segment,
    0.05 x 0.0625 cm: the default tolerance of a cube node is 5% of the
    smaller of its own and the opposite segment (the plate's), the flat
    plate has no faceting sagitta;
  * the contact work never becomes positive beyond round-off (1e-10 of the
    initial energy): a contact that only pushes and stops approaches
    dissipates; energy it gives the bodies is injected.
"""

import argparse
import os
import shutil
import subprocess
import sys

import numpy as np

from impact3d_tools import history as impact3d_history

PLATE_SEGMENT = 0.0625  # cm, from the decks
FAILED = []


def check(name, ok, detail=""):
    print(("PASS " if ok else "FAIL ") + name + ("" if ok or not detail else ": " + detail))
    if not ok:
        FAILED.append(name)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("workdir")
    ap.add_argument("--deck", required=True)
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--np", type=int, default=1)
    a = ap.parse_args()

    if os.path.isdir(a.workdir):
        shutil.rmtree(a.workdir)
    os.makedirs(a.workdir)
    shutil.copy(a.deck, os.path.join(a.workdir, "deck.nml"))
    cmd = [a.mpiexec, "-np", str(a.np), os.path.abspath(a.exe), "deck.nml"]
    p = subprocess.run(cmd, cwd=a.workdir, capture_output=True, text=True)
    check("run exits 0", p.returncode == 0, (p.stdout + p.stderr)[-2000:])
    if p.returncode != 0:
        return finish()

    h = impact3d_history.columns(a.workdir)
    e0 = h["total_energy"][0]
    err = np.max(np.abs(h["energy_error"]))
    check("energy balance with the contact work <= 1e-12 (%.1e)" % err, err <= 1e-12)
    for col in ("hit_audit_count_a", "hit_audit_count_b", "hit_unheld"):
        check("%s = 0 at every audit (max %g)" % (col, np.max(h[col])), np.all(h[col] == 0))
    tol = 0.05 * PLATE_SEGMENT
    deepest = np.max(h["hit_audit_pen_max_a"])
    check("deepest cube node %.2e <= %.3e" % (deepest, tol), deepest <= tol)
    work = np.max(h["hit_work"]) / e0
    check("contact work <= 1e-10 E0 at every row (max %.2e E0)" % work, work <= 1e-10)
    return finish()


def finish():
    print("%d failed" % len(FAILED))
    return 1 if FAILED else 0


if __name__ == "__main__":
    sys.exit(main())
