#!/usr/bin/python3
"""tools/section.py on real dumps, and the dumps' derived fields (issue 33).

Usage: check.py EXE WORKDIR

Runs plates.nml (two aluminium blocks of one 8 x 6 x 4 box mesh, the left
one striking the right one; both yield) and checks:
  * derived fields of every dump: /zones/von_mises_stress equals
    sqrt(3/2 s:s) of /zones/deviatoric_stress (to 4 ulp: the compiler may
    fuse the multiply-adds), is positive somewhere at the end and never above
    the yield stress 1e-3 by more than that round-off (the return to the
    yield surface); /nodes/displacement equals /mesh/coordinates minus
    /restart/initial_position exactly; /restart/initial_position equals
    the t = 0 dump's coordinates exactly; the t = 0 displacement is 0;
  * section counts on the t = 0 dump, exact for this structured mesh: the
    plane z = 0.15 (between node layers) and z = 0.2 (through a node layer)
    cut 8 x 6 = 48 zones, y = 0.25 cuts 8 x 4 = 32; the block outlines are
    the section's boundary plus the interface between the blocks,
    2 (8 + 6) + 6 = 34 and 2 (8 + 4) + 4 = 28 segments;
  * pictures of the last dump coloured by zone fields (plastic_strain,
    von_mises_stress, deviatoric_stress:xy), node fields (velocity,
    displacement:x) and on an oblique plane: exit 0, a PNG of exactly the
    requested 900 x 600 pixels, not blank: in its left three quarters (the
    axes) at least 15% of the pixels are coloured (not grey, black or
    white) in at least 8 colours;
  * an unknown field and a plane outside the mesh exit 2 with a message
    naming the field and the valid ones, or the mesh's extent.
"""

import os
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", "..", "..", ".."))
SECTION = [sys.executable, os.path.join(ROOT, "tools", "section.py")]
FAILED = []


def check(name, ok, detail=""):
    print(("PASS " if ok else "FAIL ") + name + (": " + detail if detail and not ok else ""))
    sys.stdout.flush()
    if not ok:
        FAILED.append(name)


def png_ok(path, size):
    """The PNG has exactly size (w, h) pixels and a drawn body: in its left
    three quarters (the axes; the colour bar is on the right), at least 15%
    of the pixels are coloured (not grey: the mesh edges, outlines, labels
    and background are grey or black or white) in at least 8 colours."""
    import matplotlib.image
    if not os.path.exists(path):
        return False, "no file"
    img = matplotlib.image.imread(path)[:, :, :3]
    rgb = (img * 255).astype(int)
    axes = rgb[:, : rgb.shape[1] * 3 // 4].reshape(-1, 3)
    coloured = axes[axes.max(axis=1) - axes.min(axis=1) > 30]
    share = len(coloured) / float(len(axes))
    colours = len(np.unique(coloured, axis=0)) if len(coloured) else 0
    ok = img.shape[:2] == (size[1], size[0]) and share >= 0.15 and colours >= 8
    return ok, "shape %s, %.0f%% of the axes' side coloured, %d colours" % (
        img.shape, 100 * share, colours)


def derived_fields(wd, dumps):
    with h5py.File(os.path.join(wd, dumps[0]), "r") as h:
        x0 = h["mesh/coordinates"][()]
    for name in dumps:
        with h5py.File(os.path.join(wd, name), "r") as h:
            s = h["zones/deviatoric_stress"][()]
            vm = h["zones/von_mises_stress"][()]
            x = h["mesh/coordinates"][()]
            u = h["nodes/displacement"][()]
            xi = h["restart/initial_position"][()]
        ref = np.sqrt(1.5 * (s[:, 0] ** 2 + s[:, 1] ** 2 + s[:, 2] ** 2
                             + 2.0 * (s[:, 3] ** 2 + s[:, 4] ** 2 + s[:, 5] ** 2)))
        eps = np.finfo(float).eps
        err = float(np.max(np.abs(vm - ref) / np.maximum(ref, 1e-300)))
        check("%s: von_mises_stress = sqrt(3/2 s:s) (largest relative difference %.1e <= "
              "4 eps)" % (name, err), err <= 4 * eps)
        check("%s: von_mises_stress <= yield stress 1e-3 (largest %.17g)" % (name, vm.max()),
              vm.max() <= 1e-3 * (1 + 4 * eps))
        check("%s: displacement = coordinates - initial_position exactly" % name,
              np.array_equal(u, x - xi))
        check("%s: initial_position = the t = 0 coordinates exactly" % name,
              np.array_equal(xi, x0))
        if name == dumps[0]:
            check("%s: displacement 0 at t = 0" % name, not np.any(u))
        if name == dumps[-1]:
            check("%s: von_mises_stress > 0 somewhere (largest %.3g)" % (name, vm.max()),
                  vm.max() > 0)
            check("%s: displacement > 0 somewhere (largest %.3g)" % (name, np.abs(u).max()),
                  np.abs(u).max() > 0)


def main():
    exe, wd = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    if os.path.isdir(wd):
        shutil.rmtree(wd)
    os.makedirs(wd)
    shutil.copy(os.path.join(HERE, "plates.nml"), os.path.join(wd, "deck.nml"))
    p = subprocess.run([exe, "deck.nml"], cwd=wd, capture_output=True, text=True)
    check("run ends", p.returncode == 0, (p.stdout + p.stderr)[-400:])
    dumps = sorted(f for f in os.listdir(wd) if re.match(r"dump_\d{6}\.h5$", f))
    check("dumps written (%d)" % len(dumps), len(dumps) >= 2)
    if p.returncode != 0 or len(dumps) < 2:
        return
    derived_fields(wd, dumps)

    def run(*args):
        return subprocess.run(SECTION + list(args), cwd=wd, capture_output=True, text=True)

    for plane, zones, outline in (("z=0.15", 48, 34), ("z=0.2", 48, 34), ("y=0.25", 32, 28)):
        p = run(dumps[0], "-f", "block", "--plane", plane, "-o", "count.png")
        m = re.search(r"(\d+) zones, (\d+) outline segments", p.stdout)
        got = (int(m.group(1)), int(m.group(2))) if m else None
        check("t = 0, plane %s: %d zones cut, %d block outline segments (got %s)"
              % (plane, zones, outline, got), p.returncode == 0 and got == (zones, outline),
              p.stderr)
    last = dumps[-1]
    for field, extra in (("plastic_strain", ["--plane", "z=0.15"]),
                         ("von_mises_stress", ["--plane", "y=0.3"]),
                         ("deviatoric_stress:xy", ["--plane", "z=0.2"]),
                         ("velocity", ["--plane", "z=0.15"]),
                         ("displacement:x", ["--plane", "z=0.15"]),
                         ("pressure", ["--point", "0.4", "0.3", "0.2", "--normal", "1", "1",
                                       "0.5"])):
        out = "section_%s.png" % re.sub(r"\W", "_", field)
        p = run(last, "-f", field, "-o", out, "--size", "900", "600", *extra)
        ok, detail = png_ok(os.path.join(wd, out), (900, 600))
        check("%s of %s %s: 900 x 600 PNG, not blank" % (field, last, " ".join(extra)),
              p.returncode == 0 and ok, p.stderr[-300:] + detail)
        print("  " + p.stdout.strip() + "  [" + detail + "]")
    p = run(last, "-f", "von_mises", "-o", "bad.png")
    check("unknown field: exit 2, names it and the valid fields, no PNG",
          p.returncode == 2 and "no field 'von_mises'" in p.stderr and "von_mises_stress" in
          p.stderr and "velocity[:x|y|z]" in p.stderr and
          not os.path.exists(os.path.join(wd, "bad.png")), p.stderr)
    p = run(last, "-f", "density", "--plane", "z=5", "-o", "bad.png")
    check("plane outside the mesh: exit 2, gives the mesh's extent",
          p.returncode == 2 and "cuts no zone" in p.stderr and "z 0 to 0.4" in p.stderr,
          p.stderr)


if __name__ == "__main__":
    main()
    print("FAILED: " + ", ".join(FAILED) if FAILED else "all checks passed")
    sys.exit(1 if FAILED else 0)
