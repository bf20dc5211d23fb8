#!/usr/bin/python3
"""Make two_blocks.exo, the Exodus II test mesh of this case, with tools this
project does not write: gmsh meshes two_blocks.geo (Debian gmsh), meshio
(Debian python3-meshio) reads the Gmsh file and writes Exodus II, and
netCDF4 (Debian python3-netcdf4) adds what meshio's Exodus writer leaves
out. Run it from anywhere: ./make_mesh.py (needs gmsh only here; the test
uses the committed two_blocks.exo).

meshio 7 writes the coordinates, one element block per cell block (ids
0, 1, ... in eb_prop1), no block names and no side sets. Following the
Exodus II file format (Schoof & Yarberry, "EXODUS II: A Finite Element Data
Model", SAND92-2137, and the variable names of exodusII_int.h), this script
then, with netCDF4:
  * sets the element block ids eb_prop1 to 1, 2, ... (attribute name = "ID")
    and adds eb_status (1) and eb_names (dimension len_name = 33: at most 32
    characters), the block names being the Gmsh physical volume names;
  * adds side sets: dimension num_side_sets, ss_prop1 (ids 1, 2, ...,
    attribute name = "ID"), ss_status, ss_names, and per set k the dimension
    num_side_ssk and the variables elem_ssk (1-based element numbers in the
    file's element order, block after block) and side_ssk (the Exodus HEX8
    side: 1 = nodes 1-2-6-5, 2 = 2-3-7-6, 3 = 3-4-8-7, 4 = 1-5-8-4,
    5 = 1-4-3-2, 6 = 5-6-7-8), one per quadrilateral of a Gmsh physical
    surface, matched to the hexahedron face with the same four nodes.
"""

import os
import subprocess
import sys
import tempfile

import meshio
import netCDF4
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SIDES = [(0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (0, 4, 7, 3), (0, 3, 2, 1), (4, 5, 6, 7)]
BLOCKS = ["target", "impactor"]
SETS = ["target_bottom", "target_top", "impactor_bottom", "impactor_top", "target_side_a",
        "target_side_b", "target_side_c", "target_side_d"]


def main():
    out = os.path.join(HERE, "two_blocks.exo")
    with tempfile.TemporaryDirectory() as tmp:
        msh = os.path.join(tmp, "two_blocks.msh")
        subprocess.run(["gmsh", "-3", "-format", "msh41", os.path.join(HERE, "two_blocks.geo"),
                        "-o", msh], check=True, stdout=subprocess.DEVNULL)
        m = meshio.read(msh)
    tag_of = {name: int(v[0]) for name, v in m.field_data.items()}
    phys = m.cell_data["gmsh:physical"]
    hex_blocks = []
    for name in BLOCKS:
        cells = [c.data for c, p in zip(m.cells, phys)
                 if c.type == "hexahedron" and np.all(p == tag_of[name])]
        hex_blocks.append(np.concatenate(cells))
    quads = {}
    for name in SETS:
        quads[name] = np.concatenate([c.data for c, p in zip(m.cells, phys)
                                      if c.type == "quad" and np.all(p == tag_of[name])])
    # Only the nodes of the hexahedra, in their original order.
    used = np.unique(np.concatenate([b.ravel() for b in hex_blocks]))
    new = -np.ones(len(m.points), dtype=np.int64)
    new[used] = np.arange(len(used))
    points = m.points[used]
    hex_blocks = [new[b] for b in hex_blocks]
    quads = {k: new[q] for k, q in quads.items()}
    if os.path.exists(out):
        os.remove(out)
    meshio.write(out, meshio.Mesh(points, [("hexahedron", b) for b in hex_blocks]),
                 file_format="exodus")

    # Side sets: every quadrilateral to (element, side).
    all_hex = np.concatenate(hex_blocks)
    face_of = {}
    for e, h in enumerate(all_hex):
        for s, f in enumerate(SIDES):
            face_of[frozenset(h[list(f)])] = (e + 1, s + 1)
    with netCDF4.Dataset(out, "a") as nc:
        nc.createDimension("len_name", 33)
        ids = nc.variables["eb_prop1"]
        ids[:] = np.arange(1, len(BLOCKS) + 1)
        ids.setncattr("name", "ID")
        status = nc.createVariable("eb_status", "i4", ("num_el_blk",))
        status[:] = 1
        names = nc.createVariable("eb_names", "S1", ("num_el_blk", "len_name"))
        names[:] = netCDF4.stringtochar(np.array(BLOCKS, dtype="S33"))
        nc.createDimension("num_side_sets", len(SETS))
        ssid = nc.createVariable("ss_prop1", "i4", ("num_side_sets",))
        ssid[:] = np.arange(1, len(SETS) + 1)
        ssid.setncattr("name", "ID")
        ss_status = nc.createVariable("ss_status", "i4", ("num_side_sets",))
        ss_status[:] = 1
        ss_names = nc.createVariable("ss_names", "S1", ("num_side_sets", "len_name"))
        ss_names[:] = netCDF4.stringtochar(np.array(SETS, dtype="S33"))
        for k, name in enumerate(SETS, start=1):
            pairs = np.array([face_of[frozenset(q)] for q in quads[name]])
            nc.createDimension("num_side_ss%d" % k, len(pairs))
            elem = nc.createVariable("elem_ss%d" % k, "i4", ("num_side_ss%d" % k,))
            side = nc.createVariable("side_ss%d" % k, "i4", ("num_side_ss%d" % k,))
            elem[:] = pairs[:, 0]
            side[:] = pairs[:, 1]
    print("wrote %s: %d nodes, %d hexahedra in blocks %s, side sets %s"
          % (out, len(points), len(all_hex), BLOCKS, SETS))


if __name__ == "__main__":
    sys.exit(main())
