#!/usr/bin/python3
"""tools/plot_history.py on a short run's history.txt, its real probe file and
a probe-style CSV.

Usage: check.py EXE WORKDIR

Runs tests/regression/decks/sod_small.nml with a &probe added (history.txt
and probe_left.csv, whose columns carry units: 'time [us]',
'velocity_x [cm/us]'), writes a CSV in the probe format without units with
known values, and checks:
  * the real probe file is plotted with columns named without their units
    (-y velocity_x density, the time column found by itself), with the full
    name, with -x time and -x 'time [us]', and together with history.txt;
    an unknown column is refused with a suggestion;
  * --list prints history.txt's header columns;
  * plotting total_energy and kinetic_energy of history.txt, and
    velocity_z of the CSV, exits 0 and writes a PNG of the requested kind:
    800 x 500 pixels (8 x 5 in at 100 dpi), more than one colour;
  * an unknown column is refused: exit 2, the message names the file, the
    column, the closest valid name and the valid columns, and no PNG is
    written; a bad -x column likewise.
"""

import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", "..", "..", ".."))
PLOT = [sys.executable, os.path.join(ROOT, "tools", "plot_history.py")]
FAILED = []


def check(name, ok, detail=""):
    print(("PASS " if ok else "FAIL ") + name + (": " + detail if detail and not ok else ""))
    if not ok:
        FAILED.append(name)


def png_ok(path):
    import matplotlib.image
    import numpy as np
    if not os.path.exists(path):
        return False, "no file"
    img = matplotlib.image.imread(path)
    colours = len(np.unique((img[:, :, :3] * 255).astype(int).reshape(-1, 3), axis=0))
    return img.shape[:2] == (500, 800) and colours > 1, "shape %s, %d colours" % (img.shape,
                                                                                colours)


def main():
    exe, wd = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    if os.path.isdir(wd):
        shutil.rmtree(wd)
    os.makedirs(wd)
    # sod_small with a probe at the right end (node 1 is at x = 0): a real
    # probe file, its columns with units ('time [us]', 'velocity_x [cm/us]').
    with open(os.path.join(ROOT, "tests", "regression", "decks", "sod_small.nml")) as f:
        deck = f.read()
    with open(os.path.join(wd, "deck.nml"), "w") as f:
        f.write(deck + "&probe name = 'left', node = 1, fields = 'velocity density' /\n")
    p = subprocess.run([exe, "deck.nml"], cwd=wd, capture_output=True, text=True)
    check("run ends", p.returncode == 0, (p.stdout + p.stderr)[-400:])
    hist = os.path.join(wd, "history.txt")
    csv = os.path.join(wd, "probe_rear.csv")
    with open(csv, "w") as f:
        f.write("cycle,time,velocity_x,velocity_y,velocity_z\n")
        for k in range(21):
            f.write("%d,%.6e,0,0,%.6e\n" % (k, 0.1 * k, -0.01 * (1 if k < 10 else -1)))
    with open(hist) as f:
        header = f.readline()[1:].split()

    def run(*args):
        return subprocess.run(PLOT + list(args), cwd=wd, capture_output=True, text=True)

    p = run(hist, "--list")
    check("--list shows the header", p.returncode == 0 and " ".join(header) in p.stdout, p.stdout)
    p = run(hist, "-y", "total_energy", "kinetic_energy", "-o", "energy.png")
    ok, detail = png_ok(os.path.join(wd, "energy.png"))
    check("history columns plotted", p.returncode == 0 and ok, p.stderr + detail)
    p = run(csv, "-y", "velocity_z", "-o", "probe.png")
    ok, detail = png_ok(os.path.join(wd, "probe.png"))
    check("probe CSV column plotted", p.returncode == 0 and ok, p.stderr + detail)
    real = os.path.join(wd, "probe_left.csv")
    with open(real) as f:
        real_header = f.readline().strip()
    check("the real probe file has unit suffixes",
          real_header.startswith("cycle,time [") and "velocity_x [" in real_header, real_header)
    for args, what in (((real, "-y", "velocity_x", "density"), "names without units, time found"),
                       ((real, "-y", "velocity_x [cm/us]", "-x", "time"), "full name, -x time"),
                       ((real, "-y", "density", "-x", "time [us]"), "-x with its unit"),
                       ((real, hist, "-y", "velocity_x", "kinetic_energy"),
                        "probe and history together")):
        out = os.path.join(wd, "real.png")
        if os.path.exists(out):
            os.remove(out)
        p = run(*(args + ("-o", "real.png")))
        ok, detail = png_ok(out)
        check("real probe file plotted: " + what, p.returncode == 0 and ok, p.stderr + detail)
    p = run(real, "-y", "velocity_q", "-o", "bad.png")
    check("real probe file, unknown column: exit 2, suggestion without the unit",
          p.returncode == 2 and "no column 'velocity_q'" in p.stderr and "did you mean" in
          p.stderr, p.stderr)
    p = run(hist, "-y", "kinetic_enrgy", "-o", "bad.png")
    msg = p.stderr
    check("unknown column: exit 2", p.returncode == 2, "exit %d" % p.returncode)
    check("unknown column: message names file, column, suggestion, valid columns",
          hist in msg and "no column 'kinetic_enrgy'" in msg and
          "did you mean 'kinetic_energy'?" in msg and "columns: cycle, time, dt" in msg,
          msg)
    check("unknown column: no PNG", not os.path.exists(os.path.join(wd, "bad.png")))
    p = run(csv, "-x", "t", "-y", "velocity_z", "-o", "bad.png")
    check("unknown -x column: exit 2 and message",
          p.returncode == 2 and "no column 't'" in p.stderr and "-x" in p.stderr, p.stderr)


if __name__ == "__main__":
    main()
    print("FAILED: " + ", ".join(FAILED) if FAILED else "all checks passed")
    sys.exit(1 if FAILED else 0)
