#!/usr/bin/python3
"""ParaView reads impact3d's dumps (issue 20 item 6): a run of viz.nml (an
imported Exodus mesh, contact, strength; five dumps) is opened in ParaView's
pvbatch, offscreen under xvfb-run, through its dump.xmf (pv_script.py), and
what ParaView sees is compared with the HDF5 dumps read here with h5py.

Usage: check.py EXE WORKDIR [--mpiexec mpirun --np 2]
Exit 77 (ctest SKIP_RETURN_CODE) when pvbatch or xvfb-run is not installed
(`./setup.sh --viz` installs them).

Criteria:
  * the time steps are the dumps' /time attributes, exactly (the XDMF files
    write them with 17 significant digits, which round-trip a double);
  * at the last time, the point and cell counts are the dump's nnode and
    nzone; the cell arrays are block plus every /zones dataset and the point
    arrays every /nodes dataset but mass (the node mass is a restart
    quantity, not in the XDMF), with the dumps' component counts (vectors 3,
    deviatoric_stress 6);
  * the ranges ParaView reports for pressure, plastic_strain and
    contact_gap equal the dataset's minimum and maximum exactly (the same
    doubles, read from the same file);
  * the PNG of the pressure field has the requested size, is not one colour
    (at least 16 distinct colours) and the body covers at least 5% of it
    (pixels differing from the corner, background, colour).
"""

import argparse
import glob
import json
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SKIP = 77
FAILED = []
# pvbatch's messages when the X display is unusable (not a result of the dump).
DISPLAY_FAILURES = ("CreateAWindow", "bad X server connection", "cannot open display",
                    "Could not open display", "unable to open display")


def check(name, ok, detail=""):
    print(("PASS " if ok else "FAIL ") + name + (": " + detail if detail and not ok else ""))
    if not ok:
        FAILED.append(name)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("workdir")
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--np", type=int, default=1)
    a = ap.parse_args()
    missing = [p for p in ("pvbatch", "xvfb-run") if shutil.which(p) is None]
    if missing:
        print("SKIP: %s not installed (./setup.sh --viz installs ParaView and xvfb)"
              % " and ".join(missing))
        return SKIP
    wd = os.path.abspath(a.workdir)
    if os.path.isdir(wd):
        shutil.rmtree(wd)
    os.makedirs(wd)
    p = subprocess.run([a.mpiexec, "-np", str(a.np), os.path.abspath(a.exe),
                        os.path.join(HERE, "viz.nml")], cwd=wd, capture_output=True, text=True)
    check("run ends (exit 0)", p.returncode == 0, (p.stdout + p.stderr)[-600:])
    if p.returncode != 0:
        return 1

    png, js = os.path.join(wd, "pressure.png"), os.path.join(wd, "paraview.json")
    # xvfb-run -a can hand pvbatch a display that is not ready yet, or one
    # another X server has just taken (a known race of xvfb-run on a loaded
    # machine): pvbatch then aborts while creating its window, before it reads
    # anything. Only that failure is retried (at most 3 attempts); any other
    # failure, and every check on the result, counts at once.
    for attempt in range(3):
        p = subprocess.run(["xvfb-run", "-a", "pvbatch", os.path.join(HERE, "pv_script.py"),
                            os.path.join(wd, "dump.xmf"), png, js],
                           cwd=wd, capture_output=True, text=True, timeout=300)
        if p.returncode == 0 or not any(m in p.stdout + p.stderr for m in DISPLAY_FAILURES):
            break
        print("note: pvbatch could not open its window (attempt %d), retrying" % (attempt + 1))
    check("pvbatch ends (exit 0)", p.returncode == 0 and os.path.exists(js),
          (p.stdout + p.stderr)[-1500:])
    if FAILED:
        return 1
    with open(js) as f:
        pv = json.load(f)
    print("ParaView reader: %s" % pv["reader"])

    dumps = sorted(glob.glob(os.path.join(wd, "dump_??????.h5")))
    times = [float(h5py.File(d).attrs["time"]) for d in dumps]
    check("time steps are the dumps' times (%d)" % len(times), pv["times"] == times,
          "%s vs %s" % (pv["times"], times))
    with h5py.File(dumps[-1]) as h:
        nnode, nzone = len(h["mesh/coordinates"]), len(h["mesh/connectivity"])
        zones = {k: h["zones/" + k][()] for k in h["zones"]}
        nodes = {k: h["nodes/" + k][()] for k in h["nodes"] if k != "mass"}
    check("point and cell counts", (pv["points"], pv["cells"]) == (nnode, nzone),
          "%s vs %s" % ((pv["points"], pv["cells"]), (nnode, nzone)))
    want_cells = {k: (1 if v.ndim == 1 else v.shape[1]) for k, v in zones.items()}
    want_cells["block"] = 1
    want_points = {k: (1 if v.ndim == 1 else v.shape[1]) for k, v in nodes.items()}
    got_cells = {k: v["components"] for k, v in pv["cell_arrays"].items()}
    got_points = {k: v["components"] for k, v in pv["point_arrays"].items()}
    check("cell arrays and components", got_cells == want_cells,
          "%s vs %s" % (got_cells, want_cells))
    check("point arrays and components", got_points == want_points,
          "%s vs %s" % (got_points, want_points))
    for kind, name, data in (("cell_arrays", "pressure", zones.get("pressure")),
                             ("cell_arrays", "plastic_strain", zones.get("plastic_strain")),
                             ("point_arrays", "contact_gap", nodes.get("contact_gap"))):
        got = pv[kind].get(name, {}).get("range")
        want = None if data is None else [float(data.min()), float(data.max())]
        check("%s range equals the dump's" % name, got is not None and got == want,
              "%s vs %s" % (got, want))

    import matplotlib.image
    img = matplotlib.image.imread(png)
    check("PNG is 480 x 360", img.shape[:2] == (360, 480), str(img.shape))
    rgb = (img[:, :, :3] * 255).round().astype(int).reshape(-1, 3)
    colours = len(np.unique(rgb, axis=0))
    body = np.any(rgb != rgb[0], axis=1).mean()
    check("PNG is not one colour (>= 16 colours)", colours >= 16, "%d colours" % colours)
    check("the body covers >= 5% of the PNG", body >= 0.05, "%.3f" % body)
    print("PNG: %d colours, body %.1f%% of the pixels" % (colours, 100 * body))
    return 1 if FAILED else 0


if __name__ == "__main__":
    code = main()
    if code != SKIP:
        print("FAILED: " + ", ".join(FAILED) if FAILED else "all checks passed")
    sys.exit(code)
