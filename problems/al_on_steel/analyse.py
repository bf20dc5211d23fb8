#!/usr/bin/python3
"""Axial stress on the axis near the Al / steel interface (docs/problems.md, D3).

Usage: PYTHONPATH=tools problems/al_on_steel/analyse.py RUN_DIRECTORY [--window 0.3 1.2] [--tol 0.03]
(from the repository root: the impact3d_tools package is in tools/)

Averages sigma_zz = p - s_zz (compression positive) of the zones on the axis
(centroid within 0.12 cm of x = y = 0) next to the interface (|z| < 0.12 cm at
t = 0, both sides) over the dumps in the window (us after impact; impact at
t = 0), and compares it with the 1D elastic-plastic impedance match built from
the same data and models (impedance_match.py: two-wave Rankine-Hugoniot match
with the Mie-Grueneisen EOS and the Steinberg-Guinan yield of the shocked state,
0.11995 Mbar; a 1D uniaxial-strain column of impact3d on one conforming mesh
gives the same to 1e-5 Mbar, see README.md). Also reports the mean of each
side, the largest penetration, the contact momentum balance and the energy
error from history.txt. With --tol, exits 1 if |error| > tol."""
import argparse
import glob
import os
import sys

import numpy as np

import impedance_match as im
from impact3d_tools import dump
from impact3d_tools import history


def impedance_match(v=0.1):
    """(axial stress, interface velocity) of the two-wave match (impedance_match.py)."""
    u, sigma = im.match(lambda m, up: im.state_at_velocity(m, up)[0]["sigma"], v)
    return sigma, u


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("run")
    p.add_argument("--window", type=float, nargs=2, default=[0.3, 1.2])
    p.add_argument("--tol", type=float, default=None,
                   help="exit 1 if |mean / reference - 1| exceeds this")
    a = p.parse_args()
    target, u = impedance_match()
    values, sides = [], []
    selected = None
    for path in sorted(glob.glob(os.path.join(a.run, "*_[0-9][0-9][0-9][0-9][0-9][0-9].h5"))):
        d = dump.load(path)
        t = float(d["attrs"]["time"])
        if not a.window[0] <= t <= a.window[1]:
            continue
        if selected is None:
            # Zones are Lagrangian: select them once, by their first centroids in the window
            # (at impact the interface is z = 0; by 1.2 us it has moved 0.036 cm).
            c = dump.zone_centroids(d)
            selected = (np.hypot(c[:, 0], c[:, 1]) < 0.12) & (np.abs(c[:, 2] + u * t) < 0.12)
            al_side = c[:, 2] + u * t > 0.0
        szz = d["pressure"] - d["deviatoric_stress"][:, 2]
        values.append(szz[selected].mean())
        sides.append([szz[selected & al_side].mean(), szz[selected & ~al_side].mean()])
    values, sides = np.array(values), np.array(sides)
    print("impedance match: interface velocity %.5f cm/us, axial stress %.5f Mbar" % (u, target))
    print("axis, next to the interface, %d dumps in [%.2f, %.2f] us: mean %.5f Mbar "
          "(min %.5f, max %.5f), error %+.2f%%" % (values.size, a.window[0], a.window[1],
                                                  values.mean(), values.min(), values.max(),
                                                  100 * (values.mean() / target - 1)))
    print("  Al side %.5f Mbar (%+.2f%%), steel side %.5f Mbar (%+.2f%%)"
          % (sides[:, 0].mean(), 100 * (sides[:, 0].mean() / target - 1),
             sides[:, 1].mean(), 100 * (sides[:, 1].mean() / target - 1)))
    h = history.read(a.run)
    header, rows = h.names, h.rows
    pen = [k for k in header if k.endswith("_pen_max")]
    dmom = [k for k in header if k.endswith("_dmom_z")]
    print("energy error at the end %.2e" % rows[-1, header.index("energy_error")])
    if pen:
        print("largest penetration %.3e cm; contact work %.4e"
              % (rows[:, header.index(pen[0])].max(), rows[-1, header.index("contact_work")]))
        print("momentum added by contact, summed over the run: %.3e (initial |p_z| %.4e)"
              % (rows[:, header.index(dmom[0])].sum(), abs(rows[0, header.index("momentum_z")])))
    if a.tol is not None and abs(values.mean() / target - 1) > a.tol:
        print("FAIL: |error| above %.1f%%" % (100 * a.tol))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
