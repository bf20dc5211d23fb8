#!/usr/bin/python3
"""Exodus II import: two_blocks.exo (made by make_mesh.py with gmsh, meshio
and netCDF4; element blocks 'target' and 'impactor', four side sets) read by
impact3d, and its two bodies run as a contact problem (impact.nml).

Usage: check.py EXE WORKDIR --method dam|dlm [--mpiexec mpirun --np 2]

Reference values are computed here from the .exo file with netCDF4 alone
(no impact3d code): coordinates, connectivity, element volumes by 2x2x2
Gauss integration of det J (exact for the trilinear hexahedron), side areas
by 2x2 Gauss integration of |x_s x x_t| (exact for planar faces, which all of
this mesh's are: they lie in coordinate planes).

Criteria:
  import  the first dump's node coordinates equal the file's bit for bit,
          its connectivity is the file's (0-based, blocks in file order), each
          zone's block is its element block, each zone volume equals the
          file's within 1e-12 relative; the face-set
          areas and centres impact3d prints at set-up equal the file's
          side-set areas (1e-12 relative: sums of at most 36 terms of
          round-off size) and area-weighted centres (1e-12 cm; the centre
          tells the six sides of a hexahedron apart, so it checks the side
          numbering).
  contact the run ends (exit 0); the energy balance closes to 1e-12 of the
          initial energy (compatible scheme, contact work booked); the contact
          work is <= 0 (contact dissipates, it cannot add energy); the audit
          finds no node beyond its penetration tolerance at any audit (the gap
          closes without interpenetration); DLM: total z momentum constant to
          1e-12 relative (equal and opposite forces); DAM: the change of total
          z momentum equals the sum of the contact's reported momentum error
          (the impact_dmom_z column: DAM's known error on non-matching
          meshes) to 1e-12 relative; the target took momentum in (p0, 0)
          (p0 the impactor's initial momentum); the nodes of the side set
          target_side_a, a symmetry plane by &boundary, keep v_y = 0.
  errors  each an input error (exit 1) with a message naming what is wrong:
          a missing file (the full path tried), a file that is not Exodus, an
          element block that is not HEX8 (a copy of the file with its
          elem_type changed to TET8), an element block without &block, an
          unknown side set named by &contact.
"""

import argparse
import glob
import os
import re
import shutil
import subprocess
import sys

import h5py
import netCDF4
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
EXO = os.path.join(HERE, "two_blocks.exo")
SIDES = [(0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (0, 4, 7, 3), (0, 3, 2, 1), (4, 5, 6, 7)]
FAILED = []


def check(name, ok, detail=""):
    print(("PASS " if ok else "FAIL ") + name + (": " + detail if detail and not ok else ""))
    if not ok:
        FAILED.append(name)


def chars(var):
    return [b"".join(row).decode().strip("\x00 ") for row in var[:].filled(b"")]


def read_exo(path):
    """Coordinates, connectivity (0-based), block of each element, block
    names, side sets {name: (elements 0-based, sides 0-based)}."""
    with netCDF4.Dataset(path) as nc:
        v = nc.variables
        if "coord" in v:
            x = np.array(v["coord"][:]).T
        else:
            x = np.stack([v["coordx"][:], v["coordy"][:], v["coordz"][:]], axis=1)
        nblk = len(nc.dimensions["num_el_blk"])
        conn = [np.array(v["connect%d" % (k + 1)][:]) - 1 for k in range(nblk)]
        block = np.concatenate([np.full(len(c), k + 1) for k, c in enumerate(conn)])
        names = chars(v["eb_names"])
        sets = {}
        for k, name in enumerate(chars(v["ss_names"]), start=1):
            sets[name] = (np.array(v["elem_ss%d" % k][:]) - 1, np.array(v["side_ss%d" % k][:]) - 1)
    return x, np.concatenate(conn), block, names, sets


def hex_volumes(x, hexes):
    sign = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                     [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)
    g = 1.0 / np.sqrt(3.0)
    xe = x[hexes]
    vol = np.zeros(len(hexes))
    for a in (-g, g):
        for b in (-g, g):
            for c in (-g, g):
                p = np.array([a, b, c])
                dn = np.empty((8, 3))
                for j in range(3):
                    o = [i for i in range(3) if i != j]
                    dn[:, j] = sign[:, j] / 8.0 * np.prod(1.0 + sign[:, o] * p[o], axis=1)
                vol += np.linalg.det(np.einsum("nkd,kj->ndj", xe, dn))
    return vol


def face_area(p):
    """Area of the bilinear quadrilateral p (4, 3) by 2x2 Gauss on [0,1]^2."""
    g = [0.5 - 0.5 / np.sqrt(3.0), 0.5 + 0.5 / np.sqrt(3.0)]
    area = 0.0
    for s in g:
        for t in g:
            xs = (1 - t) * (p[1] - p[0]) + t * (p[2] - p[3])
            xt = (1 - s) * (p[3] - p[0]) + s * (p[2] - p[1])
            area += 0.25 * np.linalg.norm(np.cross(xs, xt))
    return area


def history(path):
    with open(path) as f:
        cols = f.readline().split()[1:]
        rows = np.array([[float(t) for t in line.split()] for line in f if line.strip()])
    return {c: rows[:, i] for i, c in enumerate(cols)}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("workdir")
    ap.add_argument("--method", required=True, choices=["dam", "dlm"])
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--np", type=int, default=1)
    a = ap.parse_args()
    wd = os.path.abspath(a.workdir)
    if os.path.isdir(wd):
        shutil.rmtree(wd)
    os.makedirs(wd)
    shutil.copy(EXO, wd)
    with open(os.path.join(HERE, "impact.nml")) as f:
        deck = f.read().replace("@METHOD@", a.method)

    def write(name, text):
        with open(os.path.join(wd, name), "w") as f:
            f.write(text)

    write("deck.nml", deck)
    launch = [a.mpiexec, "-np", str(a.np), os.path.abspath(a.exe)]
    p = subprocess.run(launch + ["deck.nml"], cwd=wd, capture_output=True, text=True)
    out = p.stdout + p.stderr
    check("run ends (exit 0)", p.returncode == 0, "exit %d: %s" % (p.returncode, out[-800:]))
    if p.returncode != 0:
        return

    # --- import
    x, conn, block, names, sets = read_exo(EXO)
    dumps = sorted(glob.glob(os.path.join(wd, "dump_??????.h5")))
    with h5py.File(dumps[0]) as h:
        xd = h["mesh/coordinates"][:]
        cd = h["mesh/connectivity"][:]
        bd = h["mesh/block"][:]
        bnames = h["mesh"].attrs["block_names"].decode().split(",")
        vd = h["zones/volume"][:]
    check("coordinates equal the file's (bitwise)", xd.shape == x.shape and np.array_equal(xd, x))
    check("connectivity is the file's", cd.shape == conn.shape and np.array_equal(cd, conn))
    check("zone blocks are the element blocks",
          [bnames[b - 1] for b in bd] == [names[b - 1] for b in block])
    vx = hex_volumes(x, conn)
    rel = np.abs(vd - vx).max() / vx.max()
    check("zone volumes equal the file's (1e-12)", rel <= 1e-12, "largest relative %.3e" % rel)
    pattern = r"face set '(\w+)': +\d+ faces, area +(\S+), centre +(\S+) +(\S+) +(\S+)"
    printed = dict((m.group(1), [float(t) for t in m.group(2, 3, 4, 5)])
                   for m in re.finditer(pattern, out))
    for name, (elem, side) in sets.items():
        faces = [x[conn[e][list(SIDES[s])]] for e, s in zip(elem, side)]
        areas = np.array([face_area(f) for f in faces])
        ref = areas.sum()
        centre = sum(a * f.mean(axis=0) for a, f in zip(areas, faces)) / ref
        got = printed.get(name, [np.nan] * 4)
        check("face set %s area %.6f equals the file's (1e-12)" % (name, ref),
              abs(got[0] - ref) <= 1e-12 * ref, "printed %r" % got[0])
        # The centre tells the six sides of a hexahedron apart (side numbering).
        check("face set %s centre %s equals the file's (1e-12)" % (name, np.round(centre, 6)),
              np.abs(np.array(got[1:]) - centre).max() <= 1e-12, "printed %r" % got[1:])

    # --- contact
    hist = history(os.path.join(wd, "history.txt"))
    err = np.abs(hist["energy_error"]).max()
    check("energy balance to 1e-12", err <= 1e-12, "max |energy_error| %.3e" % err)
    check("contact work <= 0", hist["contact_work"][-1] <= 0.0, "%.3e" % hist["contact_work"][-1])
    worst = max(hist["impact_audit_count_a"].max(), hist["impact_audit_count_b"].max())
    check("no node beyond the penetration tolerance", worst == 0, "%d nodes" % worst)
    # Both methods conserve momentum (DLM: equal and opposite pair forces;
    # DAM: each slave's defect returned to its group, docs/contact.md
    # section 6); the total, summed from the nodes, to round-off.
    pz = hist["momentum_z"]
    dp = np.abs(pz - pz[0]).max()
    check("z momentum conserved to 1e-12 (%s)" % a.method.upper(), dp <= 1e-12 * abs(pz[0]),
          "%.3e" % dp)
    with h5py.File(dumps[-1]) as h:
        vz = h["nodes/velocity"][:, 2]
        vy = h["nodes/velocity"][:, 1]
        m = h["nodes/mass"][:]
    elem, side = sets["target_side_a"]
    held = np.unique([conn[e][list(SIDES[s])] for e, s in zip(elem, side)])
    check("&boundary on side set target_side_a: its nodes keep v_y = 0",
          np.all(vy[held] == 0.0), "largest |v_y| %.3e" % np.abs(vy[held]).max())
    tnodes = np.unique(conn[block == names.index("target") + 1])
    pt = (m[tnodes] * vz[tnodes]).sum()
    check("target took momentum in (p0, 0)", pz[0] < pt < 0.0, "%.4e of %.4e" % (pt, pz[0]))
    print("target momentum %.3f p0, contact work %.3e, energy E0 %.4e"
          % (pt / pz[0], hist["contact_work"][-1], hist["total_energy"][0]))

    # --- errors
    tet = os.path.join(wd, "tet.exo")
    shutil.copy(EXO, tet)
    with netCDF4.Dataset(tet, "a") as nc:
        nc.variables["connect2"].setncattr("elem_type", "TET8")
    write("junk.exo", "not a netCDF file\n")
    cases = [
        ("missing file", deck.replace("two_blocks.exo", "nothere.exo"),
         "&mesh: file: '%s' does not exist" % os.path.join(wd, "nothere.exo")),
        ("not Exodus", deck.replace("two_blocks.exo", "junk.exo"),
         "mesh file '%s': cannot open it as an Exodus II file" % os.path.join(wd, "junk.exo")),
        ("not HEX8", deck.replace("two_blocks.exo", "tet.exo"),
         "element block 'impactor' (id 2) holds 100 elements of type 'TET8'"),
        ("block without &block", deck.replace("name = 'target'", "name = 'plate'")
         .replace("block = 'target'", "block = 'plate'"),
         "&mesh: file: the element block 'target' of mesh file"),
        ("unknown side set", deck.replace("'target_top'", "'target_tpo'"),
         "&contact(1): surface_b: 'target_tpo' is not a face set of the mesh"),
    ]
    for name, text, want in cases:
        write("bad.nml", text)
        p = subprocess.run(launch + ["bad.nml"], cwd=wd, capture_output=True, text=True)
        o = p.stdout + p.stderr
        check("error, %s: exit 1 and message" % name, p.returncode == 1 and want in o,
              "exit %d: %s" % (p.returncode, o[-500:]))


if __name__ == "__main__":
    main()
    print("FAILED: " + ", ".join(FAILED) if FAILED else "all checks passed")
    sys.exit(1 if FAILED else 0)
