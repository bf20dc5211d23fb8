#!/usr/bin/python3
"""tools/plot_history.py on a short run's history.txt and on a probe-style CSV.

Usage: check.py EXE WORKDIR

Runs tests/regression/decks/sod_small.nml (history.txt), writes a CSV in the
probe format (header of comma-separated names, then rows) with known values,
and checks:
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
    p = subprocess.run([exe, os.path.join(ROOT, "tests", "regression", "decks", "sod_small.nml")],
                       cwd=wd, capture_output=True, text=True)
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
