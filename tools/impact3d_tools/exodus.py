"""Convert a Gmsh mesh of 8-node hexahedra to Exodus II, with meshio (Debian
python3-meshio) and netCDF4 (Debian python3-netcdf4).

Usage: tools/msh_to_exodus.py MESH.msh OUT.exo, or convert(msh_path, exo_path).

Every named 3D physical group becomes an element block of that name (ids
1, 2, ... in the order of the physical tags), every named 2D physical group
of quadrilaterals a side set of that name. Nodes not used by a hexahedron
are dropped (the others keep their order).

meshio 7 writes the coordinates and one element block per cell block (ids
0, 1, ... in eb_prop1), no block names and no side sets. Following the
Exodus II file format (Schoof & Yarberry, "EXODUS II: A Finite Element Data
Model", SAND92-2137; the variable names of exodusII_int.h), the blocks are
written one per physical volume, then with netCDF4:
  * the block ids eb_prop1 are set to 1, 2, ... (attribute name = "ID"),
    eb_status (1) and eb_names (dimension len_name = 33: names of at most
    32 characters) added;
  * side sets added: dimension num_side_sets, ss_prop1 (ids 1, 2, ...,
    attribute name = "ID"), ss_status, ss_names, and per set k the dimension
    num_side_ssk and the variables elem_ssk (1-based element numbers in the
    file's element order, block after block) and side_ssk (the Exodus HEX8
    side: 1 = nodes 1-2-6-5, 2 = 2-3-7-6, 3 = 3-4-8-7, 4 = 1-5-8-4,
    5 = 1-4-3-2, 6 = 5-6-7-8), one per quadrilateral of the physical surface,
    matched to the hexahedron face with the same four nodes.
"""

import os

import meshio
import netCDF4
import numpy as np

SIDES = [(0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (0, 4, 7, 3), (0, 3, 2, 1), (4, 5, 6, 7)]


def convert(msh_path, exo_path):
    """Write exo_path from msh_path; returns (block names, side set names)."""
    m = meshio.read(msh_path)
    groups = sorted(((int(v[1]), int(v[0]), name) for name, v in m.field_data.items()),
                    key=lambda t: (t[0], t[1]))
    volumes = [(tag, name) for dim, tag, name in groups if dim == 3]
    surfaces = [(tag, name) for dim, tag, name in groups if dim == 2]
    phys = m.cell_data["gmsh:physical"]
    blocks, block_names = [], []
    for tag, name in volumes:
        cells = [c.data[p == tag] for c, p in zip(m.cells, phys) if c.type == "hexahedron"]
        cells = [c for c in cells if len(c)]
        if cells:
            blocks.append(np.concatenate(cells))
            block_names.append(name)
    if not blocks:
        raise SystemExit("%s: no hexahedra in a named physical volume" % msh_path)
    used = np.unique(np.concatenate([b.ravel() for b in blocks]))
    new = -np.ones(len(m.points), dtype=np.int64)
    new[used] = np.arange(len(used))
    points = m.points[used]
    blocks = [new[b] for b in blocks]
    all_hex = np.concatenate(blocks)
    face_of = {}
    for e, h in enumerate(all_hex):
        for s, f in enumerate(SIDES):
            face_of.setdefault(frozenset(h[list(f)]), (e + 1, s + 1))
    sets, set_names = [], []
    for tag, name in surfaces:
        quads = [c.data[p == tag] for c, p in zip(m.cells, phys) if c.type == "quad"]
        quads = [q for q in quads if len(q)]
        if not quads:
            continue
        pairs = []
        for q in new[np.concatenate(quads)]:
            key = frozenset(q)
            if key not in face_of:
                raise SystemExit("%s: a quadrilateral of '%s' is no hexahedron face"
                                 % (msh_path, name))
            pairs.append(face_of[key])
        sets.append(np.array(pairs))
        set_names.append(name)
    for n in block_names + set_names:
        if len(n) > 32:
            raise SystemExit("%s: the name '%s' is longer than 32 characters" % (msh_path, n))

    if os.path.exists(exo_path):
        os.remove(exo_path)
    meshio.write(exo_path, meshio.Mesh(points, [("hexahedron", b) for b in blocks]),
                 file_format="exodus")
    with netCDF4.Dataset(exo_path, "a") as nc:
        nc.createDimension("len_name", 33)
        ids = nc.variables["eb_prop1"]
        ids[:] = np.arange(1, len(blocks) + 1)
        ids.setncattr("name", "ID")
        nc.createVariable("eb_status", "i4", ("num_el_blk",))[:] = 1
        names = nc.createVariable("eb_names", "S1", ("num_el_blk", "len_name"))
        names[:] = netCDF4.stringtochar(np.array(block_names, dtype="S33"))
        if sets:
            nc.createDimension("num_side_sets", len(sets))
            ssid = nc.createVariable("ss_prop1", "i4", ("num_side_sets",))
            ssid[:] = np.arange(1, len(sets) + 1)
            ssid.setncattr("name", "ID")
            nc.createVariable("ss_status", "i4", ("num_side_sets",))[:] = 1
            ssn = nc.createVariable("ss_names", "S1", ("num_side_sets", "len_name"))
            ssn[:] = netCDF4.stringtochar(np.array(set_names, dtype="S33"))
            for k, pairs in enumerate(sets, start=1):
                dim = "num_side_ss%d" % k
                nc.createDimension(dim, len(pairs))
                nc.createVariable("elem_ss%d" % k, "i4", (dim,))[:] = pairs[:, 0]
                nc.createVariable("side_ss%d" % k, "i4", (dim,))[:] = pairs[:, 1]
    print("wrote %s: %d nodes, %d hexahedra; element blocks %s; side sets %s"
          % (exo_path, len(points), len(all_hex), ", ".join(block_names), ", ".join(set_names)))
    return block_names, set_names

