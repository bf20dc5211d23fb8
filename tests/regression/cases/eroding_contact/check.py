#!/usr/bin/python3
"""Eroding contact: a steel cube into an eroding aluminium block, contact
surfaces given by blocks (docs/user-guide.md, "Failure and erosion";
docs/design.md, "Surfaces given by blocks"). Usage:

  check.py EXE WORKDIR --method dlm|dam|distortion [--mpiexec mpirun --np 1]

(emptied: pen_emptied.nml, DAM with an eroding projectile: every zone of
the cube is eroded, its side of the contact ends empty, and the run goes on
with the same checks, plus: steel_internal 0 at the end, 8 cube zones gone.
distortion: pen_distortion.nml, DLM with &erosion volume_ratio = 0.97 in
place of the failure model: one erosion event suffices, and every dump
after it has every live zone of the block at V >= 0.97 V0, V0 from the
first dump: a zone below would have been eroded at the end of that cycle.)

1. The run ends at t_end (exit 0): with on_penetration = 'stop' a node of
   either side beyond the audit's tolerance would have ended it (exit 2).
2. Zones are eroded in at least two separate cycles (the surfaces are
   rebuilt more than once), and the audit, which runs after every rebuild
   (a rebuild makes the next stage search again, and the audit follows a
   search), counts no node of either side beyond the tolerance on any row.
3. Contact goes on over the rebuilt surfaces: some row after the first
   erosion has active contact nodes.
4. The contact work stays <= 0 (within 1e-12 of the initial energy: the
   contact takes energy out, though within a contact it may give some back
   as the bodies separate) and the energy balance, with the eroded columns,
   closes to round-off: |error| <= N x 8 eps of the largest energy term (N
   about 70 cycles, so 1e-13).
"""

import argparse
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

from impact3d_tools import history

HERE = os.path.dirname(os.path.abspath(__file__))
FAILED = []


def check(name, ok, detail=""):
    print(("PASS " if ok else "FAIL ") + name + ("" if ok or not detail else ": " + detail))
    if not ok:
        FAILED.append(name)


def distortion(wd):
    dumps = sorted(f for f in os.listdir(wd) if f.startswith("dump_") and f.endswith(".h5"))
    with h5py.File(os.path.join(wd, dumps[0]), "r") as f:
        v0 = f["zones/volume"][()]
        target = f["mesh/block"][()] == 2
    worst = np.inf
    for d in dumps[1:]:
        with h5py.File(os.path.join(wd, d), "r") as f:
            live = (f["zones/alive"][()] > 0) & target
            ratio = f["zones/volume"][()][live] / v0[live]
        worst = min(worst, ratio.min())
    check("every live zone of the block at V/V0 >= 0.97 in every dump (min %.4f)" % worst,
          worst >= 0.97)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("workdir")
    ap.add_argument("--method", required=True, choices=["dlm", "dam", "distortion",
                                                        "emptied"])
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--np", type=int, default=1)
    a = ap.parse_args()
    wd = a.workdir
    if os.path.isdir(wd):
        shutil.rmtree(wd)
    os.makedirs(wd)
    p = subprocess.run([a.mpiexec, "-np", str(a.np), os.path.abspath(a.exe),
                        os.path.join(HERE, "pen_%s.nml" % a.method)], cwd=wd,
                       capture_output=True, text=True)
    check("the run ends at t_end, no node beyond the audit's tolerance (exit 0)",
          p.returncode == 0, (p.stdout + p.stderr)[-1500:])
    if p.returncode != 0:
        return 1
    h = history.read(wd)
    n = h["eroded_zones"]
    events = int(np.count_nonzero(np.diff(n) > 0))
    need = 1 if a.method == "distortion" else 2
    check("zones eroded in %d separate cycles (%d zones)" % (events, n[-1]), events >= need)
    if a.method == "distortion":
        distortion(wd)
    if a.method == "emptied":
        check("the cube is gone (steel_internal %.2e at the end)" % h["steel_internal"][-1],
              h["steel_internal"][-1] == 0.0 and n[-1] >= 8)
    for side in ("a", "b"):
        worst = h["pt_audit_count_" + side].max()
        check("side %s: no node beyond the tolerance on any row (max count %d)"
              % (side, worst), worst == 0)
    first = int(np.nonzero(n > 0)[0][0]) if n[-1] > 0 else len(n)
    after = h["pt_active"][first:]
    check("contact active on the rebuilt surfaces (max %d nodes after the first erosion)"
          % (after.max() if len(after) else 0), len(after) > 0 and after.max() > 0)
    e0 = h["total_energy"][0]
    w = h["contact_work"]
    check("contact work <= 0 on every row (max %.2e of E0)" % (w.max() / e0),
          w.max() <= 1e-12 * e0)
    scale = max(np.abs(h["internal_energy"]).max(), np.abs(h["kinetic_energy"]).max())
    worst = np.abs(h["energy_error"]).max() * e0
    check("energy balance with the eroded columns at round-off (%.2e <= %.2e)"
          % (worst, 1e-13 * scale), worst <= 1e-13 * scale)
    print("%d check(s) failed" % len(FAILED) if FAILED else "all checks passed")
    return 1 if FAILED else 0


if __name__ == "__main__":
    sys.exit(main())
