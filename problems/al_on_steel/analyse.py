#!/usr/bin/python3
"""Axial stress on the axis near the Al / steel interface (PROBLEMS.md D3).

Usage: analyse.py RUN_DIRECTORY [--window 0.3 1.2]

Averages sigma_zz = -p + s_zz of the zones on the axis (centroid within 0.12 cm
of x = y = 0) next to the interface (|z| < 0.12 cm, both sides) over the dumps
in the window (us after impact; impact at t = 0), and compares it with the 1D
elastic-plastic impedance match built from the same data: Hugoniot stress
rho0 (c0 + s1 up) up plus 2 Y0/3 on each side, solved for the interface
velocity (0.1201 Mbar). Also reports the largest penetration, the contact
momentum balance and the energy error from history.txt."""
import argparse
import glob
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
import dump  # noqa: E402


def impedance_match(v=0.1):
    al = (2.703, 0.524, 1.40, 0.0029)
    ss = (7.90, 0.457, 1.49, 0.0034)

    def stress(m, up):
        return m[0] * (m[1] + m[2] * up) * up + 2.0 * m[3] / 3.0
    lo, hi = 0.0, v
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if stress(al, v - mid) > stress(ss, mid):
            lo = mid
        else:
            hi = mid
    return stress(ss, lo), lo


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("run")
    p.add_argument("--window", type=float, nargs=2, default=[0.3, 1.2])
    a = p.parse_args()
    target, u = impedance_match()
    values = []
    for path in sorted(glob.glob(os.path.join(a.run, "*_[0-9][0-9][0-9][0-9][0-9][0-9].h5"))):
        d = dump.load(path)
        t = float(d["attrs"]["time"])
        if not a.window[0] <= t <= a.window[1]:
            continue
        c = dump.zone_centroids(d)
        sel = (np.hypot(c[:, 0], c[:, 1]) < 0.12) & (np.abs(c[:, 2]) < 0.12)
        szz = -(-d["pressure"][sel] + d["deviatoric_stress"][sel, 2])
        values.append(szz.mean())
    values = np.array(values)
    print("impedance match: interface velocity %.5f cm/us, axial stress %.5f Mbar" % (u, target))
    print("axis, next to the interface, %d dumps in [%.2f, %.2f] us: mean %.5f Mbar "
          "(min %.5f, max %.5f), error %+.2f%%" % (values.size, a.window[0], a.window[1],
                                                  values.mean(), values.min(), values.max(),
                                                  100 * (values.mean() / target - 1)))
    hist = os.path.join(a.run, "history.txt")
    with open(hist) as f:
        header = f.readline().split()[1:]
        rows = np.array([[float(x) for x in line.split()] for line in f if line.strip()])
    pen = [k for k in header if k.endswith("_pen_max")]
    dmom = [k for k in header if k.endswith("_dmom_z")]
    print("largest penetration %.3e cm; energy error at the end %.2e; contact work %.4e"
          % (rows[:, header.index(pen[0])].max(), rows[-1, header.index("energy_error")],
             rows[-1, header.index("contact_work")]))
    print("momentum added by contact, summed over the run: %.3e (initial |p_z| %.4e)"
          % (rows[:, header.index(dmom[0])].sum(), abs(rows[0, header.index("momentum_z")])))


if __name__ == "__main__":
    main()
