#!/usr/bin/python3
"""Draw a cross-section of an impact3d dump: the mesh cut by a plane,
coloured by any zone or node field, with the mesh edges and the block
outlines, to PNG.

Usage:
  section.py DUMP.h5 -f FIELD [--plane AXIS=VALUE | --point X Y Z --normal NX NY NZ]
             [-o section.png] [--size W H] [--range MIN MAX] [--cmap NAME]
             [--no-edges] [--no-outline] [--title TEXT]
  section.py DUMP.h5 --list

FIELD is any dataset of the dump under /zones (one colour per zone:
density, pressure, plastic_strain, von_mises_stress, ...) or /nodes
(interpolated along the cut edges and shaded between them: velocity,
displacement, contact_gap, ...), or `block`. A vector or a stress is shown
by its magnitude; `NAME:x` (or `_x`, `:1`, ...) picks a component
(deviatoric_stress components: xx yy zz xy yz zx). The default plane is
through the middle of the mesh normal to z. The picture is W x H pixels
(default 1000 x 800). Mesh edges are thin grey lines, block outlines (block
boundaries, the body's boundary, contact interfaces) thick black ones.

Prints the number of zones cut and of outline segments, and the field's
range. Errors (exit 2): an unknown field (the valid ones are listed), a
plane that cuts no zone (the mesh's extent is given), a bad option.

Example:
  tools/section.py out/dump_000400.h5 -f plastic_strain --plane y=0 -o ep.png
"""

import argparse
import os
import re
import sys

import numpy as np

from impact3d_tools import section

COMPONENTS = {3: ["x", "y", "z"], 6: ["xx", "yy", "zz", "xy", "yz", "zx"]}


class InputError(Exception):
    """A problem with the command line or the dump: reported, exit 2."""


def read_dump(path):
    """Coordinates, connectivity, block, attributes and the fields
    {name: (centre 'zone'|'node', array, units)} of a dump."""
    import h5py
    try:
        h = h5py.File(path, "r")
    except OSError as e:
        raise InputError("%s: cannot open it as HDF5: %s" % (path, e))
    with h:
        if "mesh/coordinates" not in h or "mesh/connectivity" not in h:
            raise InputError("%s: not an impact3d dump (no /mesh/coordinates)" % path)
        x = np.asarray(h["mesh/coordinates"][()], dtype=float)
        conn = np.asarray(h["mesh/connectivity"][()], dtype=np.int64)
        block = np.asarray(h["mesh/block"][()]) if "mesh/block" in h else np.ones(len(conn))
        names = h["mesh"].attrs.get("block_names", b"")
        names = names.decode() if isinstance(names, bytes) else str(names)
        attrs = {k: h.attrs[k] for k in h.attrs}
        length_units = h["mesh/coordinates"].attrs.get("units", b"")
        fields = {"block": ("zone", block.astype(float), "")}
        for group, centre in (("zones", "zone"), ("nodes", "node")):
            if group not in h:
                continue
            for name, ds in h[group].items():
                units = ds.attrs.get("units", b"")
                units = units.decode() if isinstance(units, bytes) else str(units)
                fields[name] = (centre, np.asarray(ds[()], dtype=float), units)
    length_units = length_units.decode() if isinstance(length_units, bytes) \
        else str(length_units)
    return x, conn, block, names, attrs, fields, length_units


def pick(fields, request):
    """(label, centre, values, units) of FIELD, a component or the magnitude."""
    if request in fields:
        centre, a, units = fields[request]
        if a.ndim == 2:
            return "|%s|" % request, centre, np.sqrt((a * a).sum(axis=1)), units
        return request, centre, a, units
    m = re.match(r"^(.*?)[:_]([a-z]+|\d)$", request)
    if m and m.group(1) in fields and fields[m.group(1)][1].ndim == 2:
        centre, a, units = fields[m.group(1)]
        comps = COMPONENTS.get(a.shape[1], [])
        c = m.group(2)
        k = int(c) - 1 if c.isdigit() else (comps.index(c) if c in comps else -1)
        if 0 <= k < a.shape[1]:
            return request, centre, a[:, k], units
    valid = []
    for name in sorted(fields):
        a = fields[name][1]
        valid.append(name + ("[:%s]" % "|".join(COMPONENTS.get(a.shape[1], ["1.."]))
                             if a.ndim == 2 else ""))
    raise InputError("no field '%s' in the dump (fields: %s)" % (request, ", ".join(valid)))


def plane_of(args, x):
    """Point, normal and a description of the cutting plane."""
    if args.point is not None or args.normal is not None:
        if args.point is None or args.normal is None:
            raise InputError("--point and --normal go together")
        if not np.any(args.normal):
            raise InputError("--normal: the zero vector is not a normal")
        return (np.array(args.point), np.array(args.normal),
                "the plane through (%g, %g, %g) normal (%g, %g, %g)"
                % tuple(list(args.point) + list(args.normal)))
    plane = args.plane or "z=%r" % float(0.5 * (x[:, 2].min() + x[:, 2].max()))
    m = re.match(r"^\s*([xyz])\s*=\s*([-+0-9.eE]+)\s*$", plane)
    if not m:
        raise InputError("--plane '%s': expected AXIS=VALUE, e.g. z=0.5" % plane)
    try:
        value = float(m.group(2))
    except ValueError:
        raise InputError("--plane '%s': '%s' is not a number" % (plane, m.group(2)))
    k = section.AXES[m.group(1)]
    point = np.zeros(3)
    point[k] = value
    return point, np.eye(3)[k], "the plane %s = %g" % (m.group(1), value)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dump")
    ap.add_argument("-f", "--field", help="zone or node field (see --list)")
    ap.add_argument("--plane", help="AXIS=VALUE, e.g. z=0.5 (default: z through the middle)")
    ap.add_argument("--point", type=float, nargs=3, metavar=("X", "Y", "Z"))
    ap.add_argument("--normal", type=float, nargs=3, metavar=("NX", "NY", "NZ"))
    ap.add_argument("-o", "--output", default="section.png")
    ap.add_argument("--size", type=int, nargs=2, default=[1000, 800], metavar=("W", "H"),
                    help="picture size in pixels (default 1000 800)")
    ap.add_argument("--range", type=float, nargs=2, metavar=("MIN", "MAX"))
    ap.add_argument("--cmap", default="viridis")
    ap.add_argument("--no-edges", action="store_true", help="no mesh edges")
    ap.add_argument("--no-outline", action="store_true", help="no block outlines")
    ap.add_argument("--title")
    ap.add_argument("--list", action="store_true", help="print the dump's fields")
    a = ap.parse_args(argv)
    try:
        x, conn, block, block_names, attrs, fields, length_units = read_dump(a.dump)
        if a.list:
            for name in sorted(fields):
                centre, arr, units = fields[name]
                print("%-28s %s %s%s" % (name, centre, "x".join(str(s) for s in arr.shape[1:])
                                        or "scalar", " [%s]" % units if units else ""))
            return 0
        if not a.field:
            raise InputError("no field: give -f FIELD (--list shows them)")
        if a.size[0] < 50 or a.size[1] < 50:
            raise InputError("--size %d %d: at least 50 x 50 pixels" % tuple(a.size))
        label, centre, values, units = pick(fields, a.field)
        point, normal, where = plane_of(a, x)
        s = section.cut(x, conn, point, normal)
        if len(s) == 0:
            lo, hi = x.min(axis=0), x.max(axis=0)
            raise InputError("%s cuts no zone of the mesh (it spans x %g to %g, y %g to "
                             "%g, z %g to %g)" % (where, lo[0], hi[0], lo[1], hi[1], lo[2],
                                                  hi[2]))
    except InputError as e:
        print("section.py: error: %s" % e, file=sys.stderr)
        return 2

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection, PolyCollection
    from matplotlib.tri import Triangulation

    if centre == "zone":
        shown = values[s.zones]
    else:
        corner_values = s.node_values(values)
        shown = np.concatenate(corner_values)
    vmin, vmax = (a.range if a.range else (float(shown.min()), float(shown.max())))
    if vmax <= vmin:
        vmin, vmax = vmin - 0.5 * max(abs(vmin), 1e-30), vmax + 0.5 * max(abs(vmax), 1e-30)
    fig = plt.figure(figsize=(a.size[0] / 100.0, a.size[1] / 100.0), dpi=100)
    ax = fig.add_subplot(1, 1, 1)
    if centre == "zone":
        art = PolyCollection(s.polygons, array=shown, cmap=a.cmap, edgecolors="none")
        art.set_clim(vmin, vmax)
        ax.add_collection(art)
    else:
        # Fans of triangles over each polygon, shaded between the corners.
        pts, tris, start = [], [], 0
        for p in s.polygons:
            pts.append(p)
            tris.extend([start, start + j, start + j + 1] for j in range(1, len(p) - 1))
            start += len(p)
        pts = np.concatenate(pts)
        art = ax.tripcolor(Triangulation(pts[:, 0], pts[:, 1], np.array(tris)), shown,
                           shading="gouraud", cmap=a.cmap, vmin=vmin, vmax=vmax)
    if not a.no_edges:
        ax.add_collection(LineCollection(s.edges(), colors="0.35", linewidths=0.4))
    outline = s.outline(block)
    if not a.no_outline:
        ax.add_collection(LineCollection(outline, colors="black", linewidths=1.6))
    allp = np.concatenate(s.polygons)
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    pad = 0.03 * max(hi - lo)
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    axis_names = "xyz"
    lu = " [%s]" % length_units if length_units else ""
    if np.count_nonzero(s.u) == 1 and np.count_nonzero(s.v) == 1:
        ax.set_xlabel(axis_names[int(np.argmax(np.abs(s.u)))] + lu)
        ax.set_ylabel(axis_names[int(np.argmax(np.abs(s.v)))] + lu)
    else:
        ax.set_xlabel("u = (%.3g, %.3g, %.3g)%s" % (tuple(s.u) + (lu,)))
        ax.set_ylabel("v = (%.3g, %.3g, %.3g)%s" % (tuple(s.v) + (lu,)))
    bar = fig.colorbar(art, ax=ax)
    bar.set_label(label + (" [%s]" % units if units else ""))
    t = attrs.get("time", 0.0)
    t = float(np.asarray(t).reshape(-1)[0])
    cyc = int(np.asarray(attrs.get("cycle", 0)).reshape(-1)[0])
    ax.set_title(a.title if a.title is not None else
                 "%s, %s, t = %.6g, cycle %d" % (label, where, t, cyc))
    fig.savefig(a.output, dpi=100)
    plt.close(fig)
    print("section.py: %s cut at %s: %d zones, %d outline segments; %s from %.6g to %.6g; "
          "wrote %s (%d x %d)" % (os.path.basename(a.dump), where, len(s), len(outline),
                                  label, float(shown.min()), float(shown.max()), a.output,
                                  a.size[0], a.size[1]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
