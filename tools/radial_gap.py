#!/usr/bin/python3
"""Penetration across a curved contact interface that is star-shaped about
the origin (the D2 curved split of docs/problems.md: a ball octant inside the box
minus the ball, meshed apart on the sphere r = RADIUS).

The interface nodes of each side are the nodes of its block that lie on the
sphere in the initial dump. The outer side's surface is the union of its
quadrilateral faces on the sphere, each cut into four triangles about its
node-average centre (the faceting the contact module uses for its overlaps,
up to the mid-edge points, which lie in the same triangles). For every inner
node the ray from the origin through it meets that faceted surface at one
radius; the node's penetration is its own radius less that one (> 0: beyond
the outer surface). This sees every node, including one the contact no
longer holds, so it checks the contact rather than repeating its own
diagnostics.

Run as a script: python3 radial_gap.py WORKDIR [INNER OUTER RADIUS] prints
the largest penetration of each dump.
"""

import glob
import os
import sys

import numpy as np

from impact3d_tools import dump

# Faces of a hexahedron (0-based local nodes of the connectivity).
HEX_FACES = ((0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6),
             (3, 0, 4, 7))


def interface(first, inner_block, outer_block, radius, tol=1e-9):
    """(inner nodes on the sphere, outer faces on the sphere as n x 4 node
    ids) from the initial dump."""
    on = np.abs(np.linalg.norm(first["coordinates"], axis=1) - radius) < tol * radius
    conn, block = first["connectivity"], first["block"]
    inner = np.unique(conn[block == inner_block].ravel())
    inner = inner[on[inner]]
    faces = [conn[z, list(f)] for z in np.where(block == outer_block)[0] for f in HEX_FACES
             if on[conn[z, list(f)]].all()]
    return inner, np.array(faces, dtype=int).reshape(-1, 4)


def penetration(x, inner, faces):
    """Radial penetration of each inner node beyond the faceted outer surface
    at coordinates x (nan where the ray meets no facet)."""
    centre = x[faces].mean(axis=1)
    tri = np.concatenate([np.stack([x[faces[:, i]], x[faces[:, (i + 1) % 4]], centre], axis=1)
                          for i in range(4)])
    p = x[inner]
    r = np.linalg.norm(p, axis=1)
    d = p / r[:, None]
    # Moller-Trumbore with the ray origin at 0: t d = v0 + u e1 + v e2.
    e1, e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    s = -tri[:, 0]
    h = np.cross(d[:, None, :], e2[None, :, :])
    det = np.einsum("ntk,tk->nt", h, e1)
    with np.errstate(divide="ignore", invalid="ignore"):
        u = np.einsum("ntk,tk->nt", h, s) / det
        sxe1 = np.cross(s, e1)
        v = np.einsum("nk,tk->nt", d, sxe1) / det
        t = np.einsum("tk,tk->t", e2, sxe1)[None, :] / det
    eps = 1e-12
    hit = (u >= -eps) & (v >= -eps) & (u + v <= 1 + eps) & (t > 0)
    t = np.where(hit, t, np.inf).min(axis=1)
    return np.where(np.isfinite(t), r - t, np.nan)


def history(workdir, inner_block=1, outer_block=2, radius=0.5):
    """[(time, largest penetration, its node's unit direction)] over the
    dumps of a run."""
    paths = sorted(glob.glob(os.path.join(workdir, "*_[0-9][0-9][0-9][0-9][0-9][0-9].h5")))
    first = dump.load(paths[0])
    inner, faces = interface(first, inner_block, outer_block, radius)
    rows = []
    for path in paths:
        d = dump.load(path)
        x = d["coordinates"]
        pen = penetration(x, inner, faces)
        k = int(np.nanargmax(pen))
        rows.append((float(d["attrs"]["time"]), float(pen[k]),
                     x[inner[k]] / np.linalg.norm(x[inner[k]])))
    return rows


def main(argv):
    if len(argv) not in (1, 4):
        print(__doc__)
        return 2
    inner, outer, radius = (1, 2, 0.5) if len(argv) == 1 else \
        (int(argv[1]), int(argv[2]), float(argv[3]))
    for time, pen, direction in history(argv[0], inner, outer, radius):
        print("t = %.4f  largest penetration %.3e  direction %s"
              % (time, pen, np.array2string(direction, precision=3)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
