#!/usr/bin/python3
"""Two mesh parts, one imported: a Gmsh-meshed projectile (projectile.msh,
physical volume 'projectile') and a generated plate (&block 'plate'), joined
by DLM contact (two_parts.nml). The deck and the mesh file are copied to
WORKDIR/case and the run is started from WORKDIR/run with the deck path
'../case/deck.nml', so the mesh file is found only if its path is taken from
the deck's directory.

Usage: check.py EXE WORKDIR [--mpiexec mpirun --np 2]

Criteria:
  * the deck runs (exit 0; before the fix it was refused with "&block: name:
    'plate' is not a physical volume of the mesh file");
  * the projectile's node coordinates in the first dump equal the mesh
    file's (read with meshio), bit for bit (nodes 1..n of the first part, in
    the file's node order), and its zone volumes sum to the file's volume,
    computed here by 2x2x2 Gauss integration of det J over each hexahedron
    (exact for trilinear hexahedra), within 1e-12 relative (round-off of a
    sum of 144 terms);
  * the energy balance closes to 1e-12 of the initial energy (compatible
    scheme, contact work booked) and, DLM forces being equal and opposite,
    the total z momentum stays at its initial value within 1e-12 relative;
  * the contact did act: the plate's z momentum at the end lies in
    (0, p0] (p0 the projectile's initial momentum; the plate cannot take
    more than all of it while the projectile moves down onto it);
  * a missing mesh file is an input error (exit 1) whose message names the
    full path tried, WORKDIR/case/missing.msh.
"""

import argparse
import glob
import os
import shutil
import subprocess
import sys

import h5py
import meshio
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
FAILED = []


def check(name, ok, detail=""):
    print(("PASS " if ok else "FAIL ") + name + (": " + detail if detail and not ok else ""))
    if not ok:
        FAILED.append(name)


def hex_volumes(points, hexes):
    """Volume of each trilinear hexahedron (VTK/Gmsh node order) by 2x2x2 Gauss."""
    sign = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                     [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)
    g = 1.0 / np.sqrt(3.0)
    x = points[hexes]                       # (n, 8, 3)
    vol = np.zeros(len(hexes))
    for a in (-g, g):
        for b in (-g, g):
            for c in (-g, g):
                p = np.array([a, b, c])
                # dN_k/dxi_j = s_kj / 8 * prod_{i != j} (1 + s_ki p_i)
                dn = np.empty((8, 3))
                for j in range(3):
                    others = [i for i in range(3) if i != j]
                    dn[:, j] = sign[:, j] / 8.0 * np.prod(1.0 + sign[:, others] * p[others], axis=1)
                jac = np.einsum("nkd,kj->ndj", x, dn)
                vol += np.linalg.det(jac)
    return vol


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("workdir")
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--np", type=int, default=1)
    a = ap.parse_args()

    wd = os.path.abspath(a.workdir)
    if os.path.isdir(wd):
        shutil.rmtree(wd)
    case, run = os.path.join(wd, "case"), os.path.join(wd, "run")
    os.makedirs(case)
    os.makedirs(run)
    shutil.copy(os.path.join(HERE, "projectile.msh"), case)
    with open(os.path.join(HERE, "two_parts.nml")) as f:
        deck = f.read().replace("@METHOD@", "dlm")
    with open(os.path.join(case, "deck.nml"), "w") as f:
        f.write(deck)
    with open(os.path.join(case, "missing.nml"), "w") as f:
        f.write(deck.replace("'projectile.msh'", "'missing.msh'"))
    launch = [a.mpiexec, "-np", str(a.np), os.path.abspath(a.exe)]

    p = subprocess.run(launch + ["../case/deck.nml"], cwd=run, capture_output=True, text=True)
    check("two-part deck runs", p.returncode == 0,
          "exit %d: %s" % (p.returncode, (p.stdout + p.stderr)[-800:]))
    if p.returncode != 0:
        return

    msh = meshio.read(os.path.join(HERE, "projectile.msh"))
    hexes = np.concatenate([c.data for c in msh.cells if c.type == "hexahedron"])
    used = np.unique(hexes)
    points = msh.points[used]
    file_volume = hex_volumes(msh.points, hexes).sum()

    dumps = sorted(glob.glob(os.path.join(run, "dump_??????.h5")))
    with h5py.File(dumps[0]) as h:
        x = h["mesh/coordinates"][:]
        block = h["mesh/block"][:]
        names = h["mesh"].attrs["block_names"].decode().split(",")
        vol = h["zones/volume"][:]
    k = names.index("projectile") + 1
    n = len(points)
    check("projectile coordinates equal the file's", np.array_equal(x[:n], points),
          "largest difference %.3e" % np.abs(x[:n] - points).max())
    v = vol[block == k].sum()
    check("projectile volume equals the file's (1e-12)",
          abs(v - file_volume) <= 1e-12 * file_volume, "%.17g vs %.17g" % (v, file_volume))
    check("projectile has the file's 144 hexahedra", (block == k).sum() == len(hexes))

    with open(os.path.join(run, "history.txt")) as f:
        cols = f.readline().split()[1:]
        h = np.array([[float(t) for t in line.split()] for line in f if line.strip()])
    col = {c: h[:, i] for i, c in enumerate(cols)}
    e0 = col["total_energy"][0]
    err = np.abs(col["energy_error"]).max()
    check("energy balance to 1e-12", err <= 1e-12, "max |energy_error| %.3e" % err)
    pz = col["momentum_z"]
    dp = np.abs(pz - pz[0]).max()
    check("z momentum conserved to 1e-12 (DLM)", dp <= 1e-12 * abs(pz[0]),
          "largest change %.3e of %.6e" % (dp, pz[0]))
    with h5py.File(dumps[-1]) as hh:
        vz = hh["nodes/velocity"][:, 2]
        m = hh["nodes/mass"][:]
    plate = (m[n:] * vz[n:]).sum()
    check("plate took momentum (0, p0]", pz[0] <= plate < 0.0,
          "plate %.6e, p0 %.6e" % (plate, pz[0]))
    print("energy E0 %.6e, plate momentum %.3f p0" % (e0, plate / pz[0]))

    p = subprocess.run(launch + ["../case/missing.nml"], cwd=run, capture_output=True, text=True)
    out = p.stdout + p.stderr
    want = os.path.join(case, "missing.msh")
    check("missing mesh file: exit 1", p.returncode == 1, "exit %d" % p.returncode)
    check("missing mesh file: message names group, key and full path",
          "&mesh(1): file: '" + want + "' does not exist" in out, out[-600:])


if __name__ == "__main__":
    main()
    print("FAILED: " + ", ".join(FAILED) if FAILED else "all checks passed")
    sys.exit(1 if FAILED else 0)
