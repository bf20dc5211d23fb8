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

tools/radial_gap.py WORKDIR [INNER OUTER RADIUS] prints the largest penetration
of each dump; tools/audit_vs_radial.py compares it with the contact audit
(audit_compare).
"""

import glob
import os

import h5py
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


def run_interface(workdir, inner_block, outer_block, radius):
    """(the run's numbered dumps in cycle order, inner nodes, outer faces) with
    the interface taken from the first dump."""
    paths = sorted(glob.glob(os.path.join(workdir, "*_[0-9][0-9][0-9][0-9][0-9][0-9].h5")))
    inner, faces = interface(dump.load(paths[0]), inner_block, outer_block, radius)
    return paths, inner, faces


def history(workdir, inner_block=1, outer_block=2, radius=0.5):
    """[(time, largest penetration, its node's unit direction)] over the
    dumps of a run."""
    paths, inner, faces = run_interface(workdir, inner_block, outer_block, radius)
    rows = []
    for path in paths:
        d = dump.load(path)
        x = d["coordinates"]
        pen = penetration(x, inner, faces)
        k = int(np.nanargmax(pen))
        rows.append((float(d["attrs"]["time"]), float(pen[k]),
                     x[inner[k]] / np.linalg.norm(x[inner[k]])))
    return rows


def audit_compare(workdir, inner_block=1, outer_block=2, radius=0.5):
    """The contact audit against the ray cast: [(time, ray-cast max, audit
    max over the same nodes)] per dump.

    The audit is the dump's /nodes/contact_gap: the signed distance to the
    nearest point of the same faceted surface, negative inside.
    The two measure along different directions: the ray is radial, the audit
    takes the nearest point, whose direction is the facet's normal. For a node
    at depth d behind a facet whose normal makes an angle a with the ray, the
    ray gives d / cos(a) and the audit d; on a faceted sphere a is at most
    about half the angle a segment subtends (h / (2R): 0.05 on the medium mesh)
    so the two agree to 1 - cos(a) < 0.2% where the deepest node lies behind
    a facet's interior. Near an edge of the faceting, the nearest point is on the
    edge and the audit is the smaller by up to that angle's cosine too.
    """
    paths, inner, faces = run_interface(workdir, inner_block, outer_block, radius)
    rows = []
    for path in paths:
        d = dump.load(path)
        ray = penetration(d["coordinates"], inner, faces)
        with h5py.File(path, "r") as f:
            gap = f["nodes/contact_gap"][...]
        rows.append((float(d["attrs"]["time"]), float(np.nanmax(ray)),
                     float(max(-gap[inner].min(), 0.0))))
    return rows


def cli_args(argv):
    """WORKDIR [INNER OUTER RADIUS] of the command-line tools:
    (workdir, inner, outer, radius), or None when malformed."""
    if len(argv) not in (1, 4):
        return None
    if len(argv) == 1:
        return argv[0], 1, 2, 0.5
    return argv[0], int(argv[1]), int(argv[2]), float(argv[3])
