#!/usr/bin/python3
"""&control units = 'si': the same problem in cm-g-us-Mbar and in SI.

Usage: check.py EXE WORKDIR [--mpiexec mpirun --np 2]

Runs decks/taylor_small.nml (Steinberg-Guinan copper from the library,
cm-g-us-Mbar) and taylor_si.nml (the same rod in m, kg, s, Pa: the code
converts the library's EOS and strength data). Criteria:
  cycles    the same dump cycles, and dump times equal after conversion
            (1 us = 1e-6 s) to 1e-12 relative: the time step is computed
            from the same numbers, scaled.
  fields    at every dump, each field of the SI run converted back
            (coordinates / 1e-2, velocity / 1e4, density / 1e3, specific
            energy / 1e8, pressure, viscosity and deviatoric stress / 1e11,
            sound speed / 1e4, plastic strain as is) equals the cgs run's
            within 100 N eps of the field's scale (N the dump's cycle, eps =
            2.2e-16): scaling every input by a non-power of 2 changes the
            rounding of each of the ~100 floating-point operations a value
            passes through per cycle, by a few eps each, and the stable
            scheme adds such errors, at most linearly in N. Scales: the rod
            length 2 cm, c0 = 0.394 cm/us, rho0 = 8.93 g/cm^3,
            rho0 c0^2 = 1.386 Mbar (pressure, q, stress; cancellation in the
            EOS makes the error relative to the bulk modulus, not to p),
            c0^2 (specific energy), 1 (plastic strain).
  units     the dumps' root units attribute names the system, and the
            fields' units attributes are cm/us and m/s (velocity), Mbar and
            Pa (pressure).
  restart   a restart of the SI run with units = 'cm-g-us-mbar' is an input
            error naming &control: units.
"""

import argparse
import glob
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
DECKS = os.path.join(HERE, "..", "..", "decks")
EPS = np.finfo(float).eps
RHO0, C0, L = 8.93, 0.394, 2.0
# dataset: (SI value per cgs value, scale of the field in cgs)
FIELDS = {
    "/mesh/coordinates": (1e-2, L),
    "/nodes/velocity": (1e4, C0),
    "/zones/density": (1e3, RHO0),
    "/zones/specific_internal_energy": (1e8, C0**2),
    "/zones/pressure": (1e11, RHO0 * C0**2),
    "/zones/viscosity": (1e11, RHO0 * C0**2),
    "/zones/sound_speed": (1e4, C0),
    "/zones/deviatoric_stress": (1e11, RHO0 * C0**2),
    "/zones/plastic_strain": (1.0, 1.0),
}
FAILED = []


def check(name, ok, detail=""):
    print(("PASS " if ok else "FAIL ") + name + (": " + detail if detail else ""))
    if not ok:
        FAILED.append(name)


def run(a, deck, wd):
    if os.path.isdir(wd):
        shutil.rmtree(wd)
    os.makedirs(wd)
    p = subprocess.run([a.mpiexec, "-np", str(a.np), os.path.abspath(a.exe), deck], cwd=wd,
                       capture_output=True, text=True)
    if p.returncode != 0:
        print(p.stdout + p.stderr)
        check("run " + os.path.basename(deck), False, "exit code %d" % p.returncode)
        sys.exit(1)
    return sorted(os.path.basename(f) for f in glob.glob(os.path.join(wd, "dump_*.h5")))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("workdir")
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--np", type=int, default=1)
    a = ap.parse_args()

    cgs_dir = os.path.join(a.workdir, "cgs")
    si_dir = os.path.join(a.workdir, "si")
    cgs = run(a, os.path.join(DECKS, "taylor_small.nml"), cgs_dir)
    si = run(a, os.path.join(HERE, "taylor_si.nml"), si_dir)
    check("same dump cycles", cgs == si and len(cgs) > 2, "%s / %s" % (cgs, si))
    worst = {k: 0.0 for k in FIELDS}
    for name in cgs:
        if name not in si:
            continue
        with h5py.File(os.path.join(cgs_dir, name), "r") as x, \
                h5py.File(os.path.join(si_dir, name), "r") as y:
            n = int(x.attrs["cycle"])
            tx, ty = float(x.attrs["time"]), float(y.attrs["time"]) / 1e-6
            check("%s: time %.6f us in both" % (name, tx), abs(tx - ty) <= 1e-12 * max(tx, 1e-30)
                  or tx == ty, "SI %.17g" % ty)
            for k, (factor, scale) in FIELDS.items():
                diff = np.abs(x[k][:] - y[k][:] / factor).max() / scale
                worst[k] = max(worst[k], diff)
                bound = 100 * max(n, 1) * EPS
                if diff > bound:
                    check("%s: %s" % (name, k), False, "%.3e > %.3e" % (diff, bound))
            if name == cgs[-1]:
                check("units attributes", x.attrs["units"] == b"cm-g-us-mbar" and
                      y.attrs["units"] == b"si" and
                      x["/nodes/velocity"].attrs["units"] == b"cm/us" and
                      y["/nodes/velocity"].attrs["units"] == b"m/s" and
                      x["/zones/pressure"].attrs["units"] == b"Mbar" and
                      y["/zones/pressure"].attrs["units"] == b"Pa")
    # A restart may change &control, but not its unit system.
    with open(os.path.join(HERE, "taylor_si.nml")) as f:
        deck = f.read().replace("units = 'si'", "units = 'cm-g-us-mbar'")
    changed = os.path.join(si_dir, "changed.nml")
    with open(changed, "w") as f:
        f.write(deck)
    p = subprocess.run([a.mpiexec, "-np", str(a.np), os.path.abspath(a.exe), "--restart",
                        "dump_000050.h5", changed], cwd=si_dir, capture_output=True, text=True)
    check("restart with changed units refused (exit 1, names &control: units)",
          p.returncode == 1 and "&control: units: changed since the restart dump" in p.stderr,
          "exit %d" % p.returncode)
    for k, w in worst.items():
        print("  %-34s largest difference / scale %.3e" % (k, w))
    check("every field equal after conversion within 100 N eps of its scale",
          not any(f for f in FAILED if f.startswith("dump_")))
    print("units_si: %s" % ("FAIL " + ", ".join(FAILED) if FAILED else "PASS"))
    sys.exit(1 if FAILED else 0)


if __name__ == "__main__":
    main()
