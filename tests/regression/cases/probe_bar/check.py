#!/usr/bin/python3
"""&probe on the elastic aluminium bar on a rigid wall (bar.nml).

Usage: check.py EXE WORKDIR [--mpiexec mpirun] [--ranks 1 2 3 4] [--restart-np 3]

Set-up: a bar of length L = 1 cm (200 zones, h = 0.005 cm) in 1D strain
(symmetry planes on its sides) moves at v0 = 1e-3 cm/us onto a rigid wall at
x = 1 at t = 0. The wave speed of 1D strain is the longitudinal one,
c = sqrt(c0^2 + 4G/(3 rho0)) = sqrt(0.524^2 + 4 0.276/(3 2.703)) = 0.640875
cm/us (al6061 library data). The compression wave reaches the free end x = 0
at L/c = 1.560365 us and reflects as a tension wave: the free end's velocity
reverses there from +v0 to -v0. The tension wave reaches the wall at
2L/c = 3.120730 us, the bar then leaves the wall and the impacted end (held
at 0 until then) reverses to -v0: the 2L/c reversal of issue 20.

Criteria:
  timing    the time at which the probe's velocity_x crosses the mid-value of
            its jump (0 at the free end, -v0/2 at the impacted end; linear
            interpolation between rows) is L/c resp. 2L/c within 2% of that
            time: the tolerance of the existing rebound test of this set-up
            (decks/bar_wall.nml, verify/bar_wall_rebound), i.e. 4 zone
            transit times h/c = 0.0078 us at the free end and 8 at the
            impacted end, whose front has run 2L and is wider: the scheme
            spreads a front over a few zones (artificial viscosity), more
            the farther it runs. (The stiffening of the Mie-Gruneisen bulk
            modulus at this strain, s1 v0 / c0 ~ 0.3% of c0, moves the times
            by < 0.005 us.)
  speed     after the reversal the end moves at -v0 (an elastic bar keeps its
            energy and leaves the wall at -v0): the mean of velocity_x from
            two tolerances after the reversal to the next event (2L/c for
            the free end, t_end for the impacted end) is -v0 within 5%; the
            end node rings about that value behind the captured front.
  dumps     at every dump, the probe rows of that cycle equal the dump's
            values of the same node / zone exactly (17 significant digits
            written, so the parsed doubles are the stored ones): velocity and
            position of node 1, velocity of the node at (1, 0, 0), and the
            zone fields (pressure, density, energy, deviatoric stress,
            plastic strain) of the zone holding the mid-bar point.
  ranks     the CSV files are byte for byte the same on every rank count.
  restart   a restart from the dump at t = 2 us, on another rank count, in
            a copy of the full run's directory (its CSV files holding rows
            past the restart) ends with CSV files byte for byte equal to the
            uninterrupted run's: rows beyond the restart dropped, none
            missing, none twice.
"""

import argparse
import filecmp
import glob
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
DECK = os.path.join(HERE, "bar.nml")
L, H, V0 = 1.0, 0.005, 1.0e-3
C = np.sqrt(0.524**2 + 4 * 0.276 / (3 * 2.703))
TOL = 0.02  # relative, see the docstring
PROBES = ("free_end", "impact_end", "mid")
MID_POINT = np.array([0.5012, 0.0025, 0.0025])
FAILED = []


def check(name, ok, detail=""):
    print(("PASS " if ok else "FAIL ") + name + (": " + detail if detail else ""))
    if not ok:
        FAILED.append(name)


def run(a, np_, wd, restart=None, fresh=True):
    if fresh:
        if os.path.isdir(wd):
            shutil.rmtree(wd)
        os.makedirs(wd)
    cmd = [a.mpiexec, "-np", str(np_), os.path.abspath(a.exe)]
    if restart:
        cmd += ["--restart", restart]
    cmd.append(DECK)
    p = subprocess.run(cmd, cwd=wd, capture_output=True, text=True)
    if p.returncode != 0:
        print(p.stdout + p.stderr)
        check("run on %d rank(s)%s" % (np_, " (restart)" if restart else ""), False,
              "exit code %d" % p.returncode)
        sys.exit(1)


def table(wd, name):
    with open(os.path.join(wd, "probe_%s.csv" % name)) as f:
        header = f.readline().strip().split(",")
        rows = np.array([[float(v) for v in line.split(",")] for line in f if line.strip()])
    return [h.split(" [")[0] for h in header], rows


def crossing(t, v, level):
    """First time v crosses level from above (linear interpolation)."""
    i = int(np.argmax(v < level))
    if i == 0:
        return np.nan
    return t[i - 1] + (level - v[i - 1]) * (t[i] - t[i - 1]) / (v[i] - v[i - 1])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("workdir")
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2, 3, 4])
    ap.add_argument("--restart-np", type=int, default=3)
    a = ap.parse_args()

    ref = os.path.join(a.workdir, "np%d" % a.ranks[0])
    run(a, a.ranks[0], ref)

    # Timing of the reversals.
    cols, free = table(ref, "free_end")
    t, vx = free[:, 1], free[:, cols.index("velocity_x")]
    tc = crossing(t, vx, 0.0)
    t1 = L / C
    check("free end reverses at L/c = %.6f us" % t1, abs(tc - t1) <= TOL * t1,
          "crossing at %.6f us, |diff| %.2e <= %.2e" % (tc, abs(tc - t1), TOL * t1))
    late = (t > t1 * (1 + 2 * TOL)) & (t < 2 * t1)
    mean = vx[late].mean()
    check("free end then moves at -v0 (mean, 5%)", abs(mean + V0) <= 0.05 * V0,
          "mean %.5e, range %.4e .. %.4e" % (mean, vx[late].min(), vx[late].max()))
    cols, imp = table(ref, "impact_end")
    t, vx = imp[:, 1], imp[:, cols.index("velocity_x")]
    tc = crossing(t[1:], vx[1:], -0.5 * V0)
    t2 = 2 * L / C
    check("impacted end released at 2L/c = %.6f us" % t2, abs(tc - t2) <= TOL * t2,
          "crossing at %.6f us, |diff| %.2e <= %.2e" % (tc, abs(tc - t2), TOL * t2))
    late = t > t2 * (1 + 2 * TOL)
    mean = vx[late].mean() if late.any() else np.nan
    check("impacted end then moves at -v0 (mean, 5%)", abs(mean + V0) <= 0.05 * V0,
          "mean %.5e, range %.4e .. %.4e" % (mean, vx[late].min(), vx[late].max()))

    # Probe rows against the dumps.
    dumps = sorted(glob.glob(os.path.join(ref, "dump_*.h5")))
    with h5py.File(dumps[0], "r") as f:
        x0 = f["/mesh/coordinates"][:]
        conn = f["/mesh/connectivity"][:]
    impact_node = int(np.flatnonzero(np.all(x0 == [1.0, 0.0, 0.0], axis=1))[0])
    lo = x0[conn].min(axis=1)
    hi = x0[conn].max(axis=1)
    mid_zone = int(np.flatnonzero(np.all((lo <= MID_POINT) & (MID_POINT <= hi), axis=1))[0])
    d = np.sum((x0[conn[mid_zone]] - MID_POINT) ** 2, axis=1)
    corners = conn[mid_zone][d == d.min()]
    mid_node = int(corners.min())
    tables = {p: table(ref, p) for p in PROBES}
    compared = 0
    mismatch = []
    for dump in dumps:
        with h5py.File(dump, "r") as f:
            cyc = int(f.attrs["cycle"])
            vel = f["/nodes/velocity"][:]
            pos = f["/mesh/coordinates"][:]
            z = {k: f["/zones/" + k][:] for k in ("pressure", "density",
                 "specific_internal_energy", "deviatoric_stress", "plastic_strain")}
        for p in PROBES:
            cols, rows = tables[p]
            sel = rows[:, 0] == cyc
            if not sel.any():
                if p != "mid":
                    mismatch.append("%s: no row for cycle %d" % (p, cyc))
                continue
            row = dict(zip(cols, rows[sel][0]))
            want = {}
            if p == "free_end":
                want.update(zip(["velocity_x", "velocity_y", "velocity_z"], vel[0]))
                want.update(zip(["position_x", "position_y", "position_z"], pos[0]))
            elif p == "impact_end":
                want.update(zip(["velocity_x", "velocity_y", "velocity_z"], vel[impact_node]))
            else:
                want.update(zip(["velocity_x", "velocity_y", "velocity_z"], vel[mid_node]))
                want["pressure"] = z["pressure"][mid_zone]
                want["density"] = z["density"][mid_zone]
                want["specific_internal_energy"] = z["specific_internal_energy"][mid_zone]
                want["plastic_strain"] = z["plastic_strain"][mid_zone]
                want.update(zip(["deviatoric_stress_" + c for c in
                                 ("xx", "yy", "zz", "xy", "yz", "zx")],
                                z["deviatoric_stress"][mid_zone]))
            for k, v in want.items():
                compared += 1
                if row[k] != v:
                    mismatch.append("%s cycle %d %s: %r != %r" % (p, cyc, k, row[k], v))
    check("probe rows equal the dumps' values exactly (%d values, %d dumps)"
          % (compared, len(dumps)), not mismatch and compared > 0, "; ".join(mismatch[:5]))

    # Rank counts.
    for n in a.ranks[1:]:
        wd = os.path.join(a.workdir, "np%d" % n)
        run(a, n, wd)
        same = [filecmp.cmp(os.path.join(ref, "probe_%s.csv" % p),
                            os.path.join(wd, "probe_%s.csv" % p), shallow=False) for p in PROBES]
        check("CSV files on %d ranks = on %d, byte for byte" % (n, a.ranks[0]), all(same))

    # Restart in a copy of the full run (rows past the restart present).
    wd = os.path.join(a.workdir, "restart")
    if os.path.isdir(wd):
        shutil.rmtree(wd)
    shutil.copytree(ref, wd)
    with h5py.File(os.path.join(ref, "dump_000835.h5"), "r") as f:
        ok = abs(float(f.attrs["time"]) - 2.0) < 1e-12
    check("restart dump at t = 2", ok)
    run(a, a.restart_np, wd, restart="dump_000835.h5", fresh=False)
    same = [filecmp.cmp(os.path.join(ref, "probe_%s.csv" % p),
                        os.path.join(wd, "probe_%s.csv" % p), shallow=False) for p in PROBES]
    check("restart on %d ranks: CSV files byte for byte the uninterrupted run's" % a.restart_np,
          all(same))

    print("probe_bar: %s" % ("FAIL " + ", ".join(FAILED) if FAILED else "PASS"))
    sys.exit(1 if FAILED else 0)


if __name__ == "__main__":
    main()
