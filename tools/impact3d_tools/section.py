"""A dump's hexahedral mesh cut by a plane: one polygon per zone the plane
crosses, the values of a zone or node field on it, and the segments of the
polygons' sides that outline the blocks.

    s = section.cut(coordinates, connectivity, point, normal)
    s.polygons          # list of (k, 2) arrays, in-plane coordinates
    s.zones             # the zone of each polygon
    s.node_values(f)    # per polygon, f (nnode,) interpolated at its corners
    s.outline(block)    # (m, 2, 2) segments between blocks and on the boundary

A node is on the plane's positive side when its signed distance d >= 0, so
a plane through a layer of nodes cuts the zones on one side of it only, and
every zone it crosses once. Along each edge whose ends are on different
sides the crossing point and the node values are interpolated linearly; a
zone's polygon is its crossing points in angular order about their mean (the
section of a convex hexahedron is convex). The side of a polygon that lies
on a hexahedron face is shared by the neighbouring zone's polygon when that
zone is cut too (same face nodes): a side with no partner, or whose partner
is in another block, is a block outline (a contact interface between
separate bodies, whose faces have different nodes, is one too).
"""

import numpy as np

# VTK hexahedron: nodes 0-3 one face, 4-7 the opposite one.
EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
         (0, 4), (1, 5), (2, 6), (3, 7)]
FACES = [(0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
AXES = {"x": 0, "y": 1, "z": 2}


def plane_basis(normal):
    """Unit normal and two in-plane unit vectors (u, v). For a normal along a
    coordinate axis, u and v are the other two axes in order (x: y, z;
    y: x, z; z: x, y)."""
    n = np.asarray(normal, dtype=float)
    n = n / np.linalg.norm(n)
    k = int(np.argmax(np.abs(n)))
    if np.count_nonzero(n) == 1:
        others = [i for i in range(3) if i != k]
        u, v = np.eye(3)[others[0]], np.eye(3)[others[1]]
        return n, u, v
    helper = np.eye(3)[int(np.argmin(np.abs(n)))]
    u = np.cross(helper, n)
    u /= np.linalg.norm(u)
    v = np.cross(n, u)
    return n, u, v


class Section:
    """The polygons of one cut (see the module's description)."""

    def __init__(self, polygons, zones, corners, weights, face_segments, u, v):
        self.polygons = polygons
        self.zones = np.asarray(zones, dtype=np.int64)
        self._corners = corners          # per polygon: (k, 2) node indices of its edges
        self._weights = weights          # per polygon: (k,) weight t of the second node
        self._face_segments = face_segments
        self.u, self.v = u, v

    def __len__(self):
        return len(self.polygons)

    def node_values(self, values):
        """Per polygon, the node field values (nnode,) at its corners."""
        values = np.asarray(values, dtype=float)
        return [values[c[:, 0]] + w * (values[c[:, 1]] - values[c[:, 0]])
                for c, w in zip(self._corners, self._weights)]

    def edges(self):
        """Every polygon side, (m, 2, 2)."""
        segs = [np.stack([p, np.roll(p, -1, axis=0)], axis=1) for p in self.polygons]
        return np.concatenate(segs) if segs else np.zeros((0, 2, 2))

    def outline(self, block):
        """Polygon sides on a face with no cut neighbour (the boundary of the
        section) or whose neighbour is in another block: (m, 2, 2)."""
        block = np.asarray(block)
        out = []
        for key, items in self._face_segments.items():
            if len(items) == 1 or len({block[z] for z, _ in items}) > 1:
                out.append(items[0][1])
        return np.array(out).reshape(-1, 2, 2)


def cut(coordinates, connectivity, point, normal):
    """The section of the mesh (coordinates (nnode, 3), connectivity
    (nzone, 8), 0-based) by the plane through point with normal."""
    x = np.asarray(coordinates, dtype=float)
    conn = np.asarray(connectivity, dtype=np.int64)
    n, u, v = plane_basis(normal)
    d = (x - np.asarray(point, dtype=float)) @ n
    side = d >= 0.0
    s = side[conn]
    cut_zones = np.nonzero(s.any(axis=1) & ~s.all(axis=1))[0]
    # Crossing of every edge of the cut zones (nan where it does not cross).
    c = conn[cut_zones]
    ncut = len(cut_zones)
    t = np.full((ncut, 12), np.nan)
    for e, (a, b) in enumerate(EDGES):
        da, db = d[c[:, a]], d[c[:, b]]
        crosses = side[c[:, a]] != side[c[:, b]]
        t[crosses, e] = da[crosses] / (da[crosses] - db[crosses])
    ea = np.array([a for a, _ in EDGES])
    eb = np.array([b for _, b in EDGES])
    xa, xb = x[c[:, ea]], x[c[:, eb]]                    # (ncut, 12, 3)
    p3 = xa + t[:, :, None] * (xb - xa)
    p2 = np.stack([p3 @ u, p3 @ v], axis=-1)             # (ncut, 12, 2)
    polygons, corners, weights = [], [], []
    for i in range(ncut):
        k = np.nonzero(~np.isnan(t[i]))[0]
        pts = p2[i, k]
        centre = pts.mean(axis=0)
        order = np.argsort(np.arctan2(pts[:, 1] - centre[1], pts[:, 0] - centre[0]),
                           kind="stable")
        k = k[order]
        polygons.append(p2[i, k])
        corners.append(np.stack([c[i, ea[k]], c[i, eb[k]]], axis=1))
        weights.append(t[i, k])
    # Sides on faces: the two crossings of a face's edges.
    edge_of = {frozenset(ab): e for e, ab in enumerate(EDGES)}
    face_segments = {}
    for f in FACES:
        fe = [edge_of[frozenset((f[j], f[(j + 1) % 4]))] for j in range(4)]
        for i in range(ncut):
            hit = [e for e in fe if not np.isnan(t[i, e])]
            if len(hit) < 2:
                continue
            key = tuple(sorted(int(c[i, j]) for j in f))
            for j in range(0, len(hit) - 1, 2):
                seg = np.array([p2[i, hit[j]], p2[i, hit[j + 1]]])
                face_segments.setdefault((key, j), []).append((int(cut_zones[i]), seg))
    return Section(polygons, cut_zones, corners, weights, face_segments, u, v)
