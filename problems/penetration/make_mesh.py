#!/usr/bin/python3
"""Hexahedral quarter mesh of the Piekutowski et al. (1999) penetration
problem, written as an ASCII Gmsh 2.2 file (python3 + numpy only; no Gmsh
needed). SI units (m). Usage:

    make_mesh.py [--level coarse|fine|...] [-o FILE]

coarse -> penetration_coarse.msh, fine (the long deck's: 1.5x the coarse
channel's resolution across and along z) -> penetration_fine.msh, next to this
script. The other levels are studies (README.md): coarse_30 and fine_30 (the
deck levels' channel to 30 mm only), coarse12 and fine08 (the meshes before
issue 32's channel study), axis06, axis04, axis04z12 and axis.

Geometry (README.md): quarter model x >= 0, y >= 0.
* Rod (physical volume `rod`): radius a = 3.555 mm (7.11 mm diameter), tangent
  ogive nose of 3.0 CRH (ogive radius s = 6 a, sharp nose length
  l = a sqrt(11) = 11.79 mm), sharp-nose length 71.12 mm. The sharp tip is cut
  by a flat of axial length TIP_FLAT = 0.75 mm (radius 0.476 mm), so the rod
  spans 0 <= z <= 70.37 mm with the flat at z = 0. (--tip dome: a spherical
  cap of radius 0.556 mm tangent to the ogive at the flat's edge instead, 0.48
  mm of the sharp tip removed, apex at z = 0; not used by the decks.)
* Target (physical volume `target`): cylinder of radius 127 mm (254 mm
  diameter), -DEPTH <= z <= 0.
Both are O-grids: a square core and a ring in the cross-section, extruded
along z (the decks' rods have no ring: one kite-shaped zone per quarter
layer, whose outer corner lies on the circle). The rod's cross-section at
height z is its shank's scaled by r(z)/a along the nose. The target's cross-section is fine up to radius r_fine (the penetration
channel, radius a, and the material it pushes aside: 1.5 a for the decks'
levels, 2 a before), then polar rings graded out to 127 mm (optionally
coarsened 3:1 tangentially through a transition ring); along z it is fine to
Z_FINE below the face, then graded to the back face.
Face sets (physical surfaces of quadrilaterals): `xsym` (x = 0) and `ysym`
(y = 0) of both bodies, `target_top`, `target_bottom`, `target_side`,
`rod_side` (shank and nose), `rod_tip` (the flat), `rod_back`.
The rod and the target share no node (they meet through contact).
"""

import argparse
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))

A = 7.11e-3 / 2.0                 # rod radius (m)
CRH = 3.0                         # calibre-radius-head of the ogive
S = 2.0 * CRH * A                 # ogive radius
NOSE = A * math.sqrt(4.0 * CRH - 1.0)   # sharp nose length
ROD_LENGTH = 71.12e-3             # sharp-nose rod length
TIP_FLAT = 0.75e-3                # axial length cut off the sharp tip
TARGET_RADIUS = 127.0e-3          # 254 mm diameter
DEPTH = 300.0e-3                  # target thickness
Z_FINE = 250.0e-3                 # fine axial zones down to this depth
R_FINE = 2.0 * A                  # fine radial zones out to this radius

LEVELS = {
    # rod: core zones per square edge and ring zones across the radius (0: one
    # kite-shaped zone per quarter cross-section, its outer corner on the arc),
    # rod axial zone size; target: zone size near the axis and along the
    # penetration channel (h), largest zone far away (h_far), optionally the
    # channel's radius (r_fine, default 2a) and its zones across the core's
    # edge (n_fine, default from h), the core's half-width as a fraction of
    # r_fine (core, default 0.5), the first polar ring's width (h_ring,
    # default h), the axial zone size in the channel (h_z, default h), the
    # channel's depth (z_fine, default Z_FINE), the target's radius and depth
    # (radius, depth; default TARGET_RADIUS, DEPTH) and radii beyond which the
    # polar rings coarsen 3:1 tangentially (coarsen). The rod's tip zone is
    # r_tip / (n_core + n_ring) across and 0.48 mm for the kite.
    #
    # The decks' meshes (issue 32, README.md "Channel resolution"): the
    # channel r_fine = 1.5 a with 4 (coarse) or 6 (fine) zones across the
    # core's edge: zones 0.54-0.8 mm (coarse) and 0.36-0.59 mm (fine)
    # across near the rod's radius; 2.0 mm (coarse) and 1.33 mm (fine) along
    # z. The fine level is 1.5x the coarse in the channel (across and along).
    "coarse": dict(n_core=1, n_ring=0, h_rod=1.2e-3, r_fine=1.5 * A, n_fine=4, core=0.42,
                   h=0.65e-3, h_ring=0.75e-3, h_z=2.0e-3, h_far=60.0e-3),
    "fine": dict(n_core=1, n_ring=0, h_rod=1.2e-3, r_fine=1.5 * A, n_fine=6, core=0.42,
                 h=0.45e-3, h_ring=0.5e-3, h_z=1.333e-3, h_far=60.0e-3, coarsen=(8.0e-3,)),
    # The committed meshes before issue 32's channel study: 1.2 mm zones to
    # r = 2a (coarse12; resists 3.6 times the cavity-expansion model over the
    # first 10 us at 569 m/s, 2.2 over 20 us) and a 2-zone rod on 0.8 mm (fine08).
    "coarse12": dict(n_core=1, n_ring=0, h_rod=1.2e-3, h=1.2e-3, h_far=30.0e-3),
    "fine08": dict(n_core=1, n_ring=1, h_rod=0.8e-3, h=0.8e-3, h_far=20.0e-3),
    # Studies of the nose flow (README.md): the coarse rod on a target with
    # 0.4 mm or 0.6 mm zones near the axis, fine only down to 20 mm (the first
    # microseconds of a shot; not for whole shots).
    "axis04": dict(n_core=1, n_ring=0, h_rod=1.2e-3, h=0.4e-3, h_far=30.0e-3, z_fine=20.0e-3),
    "axis06": dict(n_core=1, n_ring=0, h_rod=1.2e-3, h=0.6e-3, h_far=30.0e-3, z_fine=20.0e-3),
    "axis04z12": dict(n_core=1, n_ring=0, h_rod=1.2e-3, h=0.4e-3, h_z=1.2e-3, h_far=30.0e-3,
                      z_fine=20.0e-3),
    # The coarse rod on a target with 0.4 mm zones across and 1.2 mm along the
    # axis down to 250 mm (115 290 zones; no deck uses it).
    "axis": dict(n_core=1, n_ring=0, h_rod=1.2e-3, h=0.4e-3, h_z=1.2e-3, h_far=30.0e-3),
}
# The 20 us channel study at 569 m/s (README.md): each deck level with the
# channel fine only to 30 mm ("<level>_30").
for _name in ("coarse", "fine", "coarse12"):
    LEVELS[_name + "_30"] = dict(LEVELS[_name], z_fine=30.0e-3)
# The target-size study (README.md): the coarse deck's target 1.5 times as
# wide (radius 190.5 mm) and as deep (450 mm), the same zones near the axis
# and along the channel (the polar rings and the axial zones below the
# channel graded on to the larger size).
LEVELS["coarse_big"] = dict(LEVELS["coarse"], radius=1.5 * TARGET_RADIUS, depth=1.5 * DEPTH)


def arc_nodes(nodes, rho, count):
    """Append count + 1 nodes evenly along the quarter circle of radius rho
    (from the x axis to the y axis) to nodes; return their indices."""
    first = len(nodes)
    for m in range(count + 1):
        t = 0.5 * math.pi * m / count
        nodes.append((rho * math.cos(t), rho * math.sin(t)))
    return list(range(first, first + count + 1))


def nose_radius(x):
    """Radius of the sharp tangent ogive at distance x from its tip (0 <= x <= NOSE)."""
    u = NOSE - x
    return math.sqrt(S * S - u * u) - (S - A)


def graded(length, h0, h1):
    """Node positions 0..length, first zone h0, last about h1 (geometric)."""
    if abs(h1 - h0) < 1e-3 * h0:
        n = max(1, round(length / h0))
        return np.linspace(0.0, length, n + 1)
    # zones n and ratio q with h0 (q^n - 1)/(q - 1) = length, h0 q^(n-1) ~ h1
    q = (length - h0) / (length - h1)
    n = max(1, round(1.0 + math.log(h1 / h0) / math.log(q)))
    lo, hi = (1.0 + 1e-12, 10.0) if h1 > h0 else (1e-3, 1.0 - 1e-12)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        total = h0 * (mid ** n - 1.0) / (mid - 1.0)
        if (total > length) == (h1 > h0):
            hi = mid
        else:
            lo = mid
    q = 0.5 * (lo + hi)
    sizes = h0 * q ** np.arange(n)
    x = np.concatenate([[0.0], np.cumsum(sizes)])
    x[-1] = length
    return x


class Section:
    """Quarter O-grid cross-section in units of its ring's outer radius 1 (plus
    polar rings beyond it): 2D nodes, counter-clockwise quads and the edges on
    x = 0 and y = 0 and on the outer boundary."""

    def __init__(self, n_core, ring_t, polar_radii=(), arc_radius=1.0, coarsen=(), core=0.5):
        # core: half-width of the square core (0.5: the ring is 0.29 thick on the
        # diagonals and 0.5 on the axes; about 0.42 evens the ring's zones out)
        nodes, index = [], {}

        def add(key, point):
            index[key] = len(nodes)
            nodes.append(point)

        kite = len(ring_t) == 1  # no ring: one quad, its outer corner on the arc
        if kite:
            if n_core != 1:
                raise ValueError("a section without a ring has one core zone")
            core = arc_radius
        for j in range(n_core + 1):
            for i in range(n_core + 1):
                add(("c", i, j), (core * i / n_core, core * j / n_core))
        if kite:
            nodes[index[("c", 1, 1)]] = (arc_radius * math.sqrt(0.5), arc_radius * math.sqrt(0.5))
        n_tan = 2 * n_core
        theta = 0.5 * math.pi * np.arange(n_tan + 1) / n_tan

        def square(m):
            if m <= n_core:
                return ("c", n_core, m)
            return ("c", n_tan - m, n_core)

        for layer, t in enumerate(ring_t[1:], start=1):
            for m in range(n_tan + 1):
                sq = np.array(nodes[index[square(m)]])
                arc = arc_radius * np.array([math.cos(theta[m]), math.sin(theta[m])])
                add(("r", layer, m), tuple((1.0 - t) * sq + t * arc))
        n_layer = len(ring_t) - 1

        def ring_key(layer, m):
            return square(m) if layer == 0 else ("r", layer, m)

        quads, xsym, ysym, outer = [], [], [], []
        for j in range(n_core):
            for i in range(n_core):
                quads.append([index[("c", i, j)], index[("c", i + 1, j)],
                              index[("c", i + 1, j + 1)], index[("c", i, j + 1)]])
        for j in range(n_core):
            xsym.append((index[("c", 0, j + 1)], index[("c", 0, j)]))
        for i in range(n_core):
            ysym.append((index[("c", i, 0)], index[("c", i + 1, 0)]))
        for layer in range(n_layer):
            for m in range(n_tan):
                quads.append([index[ring_key(layer, m)], index[ring_key(layer + 1, m)],
                              index[ring_key(layer + 1, m + 1)], index[ring_key(layer, m + 1)]])
            ysym.append((index[ring_key(layer, 0)], index[ring_key(layer + 1, 0)]))
            xsym.append((index[ring_key(layer + 1, n_tan)], index[ring_key(layer, n_tan)]))
        # Polar rings: node ids of the ring just made, counter-clockwise. A
        # ring in `coarsen` is a 3:1 transition: each three tangential zones
        # inside meet one outside, through two nodes half-way out (four
        # quadrilaterals per group, the standard 3-to-1 template).
        ring = [index[ring_key(n_layer, m)] for m in range(n_tan + 1)]
        inner_rho = arc_radius
        for p, rho in enumerate(polar_radii, start=1):
            count = len(ring) - 1
            if p in coarsen:
                if count % 3:
                    raise ValueError("a 3:1 transition needs a multiple of 3 zones")
                count_out = count // 3
                theta_in = 0.5 * math.pi * np.arange(count + 1) / count
                mid_rho = 0.5 * (inner_rho + rho)
                new = arc_nodes(nodes, rho, count_out)
                for g in range(count_out):
                    a0, a1, a2, a3 = ring[3 * g:3 * g + 4]
                    c1, c2 = len(nodes), len(nodes) + 1
                    for m in (3 * g + 1, 3 * g + 2):
                        nodes.append((mid_rho * math.cos(theta_in[m]),
                                      mid_rho * math.sin(theta_in[m])))
                    b0, b1 = new[g], new[g + 1]
                    quads += [[a0, b0, c1, a1], [a1, c1, c2, a2], [a2, c2, b1, a3],
                              [c1, b0, b1, c2]]
            else:
                new = arc_nodes(nodes, rho, count)
                for m in range(count):
                    quads.append([ring[m], new[m], new[m + 1], ring[m + 1]])
            ysym.append((ring[0], new[0]))
            xsym.append((new[-1], ring[-1]))
            ring, inner_rho = new, rho
        for m in range(len(ring) - 1):
            outer.append((ring[m], ring[m + 1]))
        self.xy = np.array(nodes)
        self.quads = np.array(quads)
        self.xsym, self.ysym, self.outer = xsym, ysym, outer


class Mesh:
    """Nodes, hexahedra with a volume name, quadrilaterals with a surface name."""

    def __init__(self):
        self.nodes = []
        self.hexes = []   # (volume, [8 node ids, 0-based])
        self.quads = []   # (surface, [4 node ids])

    def extrude(self, volume, section, stations, scale, names, shift=None):
        """Body: section at each z of stations, scaled (x, y) by scale(z) and moved along
        z by shift(layer, section xy) (none: 0); face sets named by names: dict with
        keys xsym, ysym, outer, bottom, top (None: no set)."""
        base = len(self.nodes)
        n2 = len(section.xy)
        for k, z in enumerate(stations):
            f = scale(z)
            dz = shift(k, section.xy) if shift else np.zeros(n2)
            for (x, y), d in zip(section.xy, dz):
                self.nodes.append((f * x, f * y, z + d))

        def nid(node, layer):
            return base + layer * n2 + node

        for k in range(len(stations) - 1):
            for q in section.quads:
                self.hexes.append((volume, [nid(n, k) for n in q] + [nid(n, k + 1) for n in q]))
            for key in ("xsym", "ysym", "outer"):
                if names.get(key):
                    for n0, n1 in getattr(section, key):
                        self.quads.append((names[key], [nid(n0, k), nid(n1, k),
                                                        nid(n1, k + 1), nid(n0, k + 1)]))
        top = len(stations) - 1
        for q in section.quads:
            if names.get("bottom"):
                self.quads.append((names["bottom"], [nid(n, 0) for n in q[::-1]]))
            if names.get("top"):
                self.quads.append((names["top"], [nid(n, top) for n in q]))

    def write(self, path):
        volumes = sorted({v for v, _ in self.hexes})
        surfaces = sorted({s for s, _ in self.quads})
        tags = {name: i + 1 for i, name in enumerate(volumes + surfaces)}
        with open(path, "w") as out:
            out.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n")
            out.write(f"$PhysicalNames\n{len(tags)}\n")
            for name in surfaces:
                out.write(f'2 {tags[name]} "{name}"\n')
            for name in volumes:
                out.write(f'3 {tags[name]} "{name}"\n')
            out.write("$EndPhysicalNames\n")
            out.write(f"$Nodes\n{len(self.nodes)}\n")
            for i, (x, y, z) in enumerate(self.nodes, start=1):
                out.write(f"{i} {x:.10g} {y:.10g} {z:.10g}\n")
            out.write("$EndNodes\n")
            out.write(f"$Elements\n{len(self.quads) + len(self.hexes)}\n")
            e = 0
            for name, q in self.quads:
                e += 1
                out.write(f"{e} 3 2 {tags[name]} {tags[name]} " + " ".join(str(n + 1) for n in q)
                          + "\n")
            for name, h in self.hexes:
                e += 1
                out.write(f"{e} 5 2 {tags[name]} {tags[name]} " + " ".join(str(n + 1) for n in h)
                          + "\n")
            out.write("$EndElements\n")


def hex_volumes(points, hexes):
    """Volumes of hexahedra (Gmsh order) by 6 tetrahedra each."""
    p = points[hexes]
    tets = [(0, 1, 2, 6), (0, 2, 3, 6), (0, 3, 7, 6), (0, 7, 4, 6), (0, 4, 5, 6), (0, 5, 1, 6)]
    vol = np.zeros(len(hexes))
    for a, b, c, d in tets:
        vol += np.einsum("ij,ij->i", p[:, b] - p[:, a],
                         np.cross(p[:, c] - p[:, a], p[:, d] - p[:, a])) / 6.0
    return vol


def build(level, tip="flat"):
    spec = LEVELS[level]
    h, h_rod, n_core, n_ring = spec["h"], spec["h_rod"], spec["n_core"], spec["n_ring"]
    mesh = Mesh()
    # Rod: the shank's O-grid, scaled by r(z)/a along the nose. Its outer nodes
    # at radius a sqrt(theta/sin(theta)), theta the angle of one boundary
    # segment: the faceted cross-section then has the circle's area (the rod's
    # mass and its projected area, which set its depth).
    theta = 0.5 * math.pi / (2 * n_core)
    rod_section = Section(n_core, np.linspace(0.0, 1.0, n_ring + 1),
                          arc_radius=math.sqrt(theta / math.sin(theta)))
    nose_top = NOSE - TIP_FLAT          # height of the nose base above the flat
    rod_top = ROD_LENGTH - TIP_FLAT
    r_tip = nose_radius(TIP_FLAT)
    # First nose layer as thick as the tip's zones are wide (r_tip / radial zones).
    h_tip = r_tip / (n_core + n_ring)
    z_nose = graded(nose_top, h_tip, h_rod)
    z_shank = nose_top + graded(rod_top - nose_top, h_rod, h_rod)[1:]
    stations = np.concatenate([z_nose, z_shank])

    def rod_scale(z):
        if z >= nose_top:
            return A
        return nose_radius(z + TIP_FLAT)

    # Tip: the flat at TIP_FLAT from the sharp tip (the default), or (tip =
    # 'dome') a spherical cap tangent to the ogive at the flat's edge, which
    # bulges `rise` below the flat: radius r_tip/n_r, n the ogive's unit
    # normal there (n_r radial, n_z axial). The first two layers follow the cap,
    # the next three blend to the flat stations (each layer keeps its thickness
    # or thickens), and the rod is raised so that the cap's apex is at z = 0.
    slope = (NOSE - TIP_FLAT) / math.sqrt(S * S - (NOSE - TIP_FLAT) ** 2)  # dr/dx at the edge
    n_r, n_z = 1.0 / math.hypot(1.0, slope), slope / math.hypot(1.0, slope)
    cap_radius = r_tip / n_r
    rise = cap_radius * (1.0 - n_z) if tip == "dome" else 0.0
    arc = math.sqrt(theta / math.sin(theta))

    def dome(k, xy):
        if tip != "dome":
            return np.zeros(len(xy))
        weight = min(1.0, max(0.0, 1.0 - (k - 1) / 3.0))
        r = r_tip * np.minimum(np.hypot(xy[:, 0], xy[:, 1]) / arc, 1.0)
        return rise + weight * (cap_radius * n_z - np.sqrt(cap_radius ** 2 - r ** 2))

    mesh.extrude("rod", rod_section, stations, rod_scale,
                 dict(xsym="xsym", ysym="ysym", outer="rod_side", bottom="rod_tip",
                      top="rod_back"), shift=dome)
    # Target: fine O-grid to R_FINE, polar rings graded to the outer radius.
    r_fine = spec.get("r_fine", R_FINE)
    n_fine = spec.get("n_fine", max(1, round(0.5 * r_fine / h)))
    radii = r_fine + graded(spec.get("radius", TARGET_RADIUS) - r_fine, spec.get("h_ring", h), spec["h_far"])[1:]
    # 3:1 tangential transitions at the first polar rings beyond the radii in
    # spec["coarsen"] (1-based ring numbers).
    coarsen = [1 + int(np.searchsorted(radii, r)) for r in spec.get("coarsen", ())]
    target_section = Section(n_fine, np.linspace(0.0, 1.0, n_fine + 1), radii / r_fine,
                             coarsen=coarsen, core=spec.get("core", 0.5))
    fine_depth = spec.get("z_fine", Z_FINE)
    h_z = spec.get("h_z", h)  # axial zone size of the target's fine part
    z_fine = -graded(fine_depth, h_z, h_z)
    z_deep = -fine_depth - graded(spec.get("depth", DEPTH) - fine_depth, h_z, spec["h_far"] / 2.0)[1:]
    z_target = np.concatenate([z_deep[::-1], z_fine[::-1]])
    mesh.extrude("target", target_section, z_target, lambda z: r_fine,
                 dict(xsym="xsym", ysym="ysym", outer="target_side", bottom="target_bottom",
                      top="target_top"))
    return mesh, dict(r_tip=r_tip, h_tip=h_tip, rod_layers=len(stations) - 1,
                      target_layers=len(z_target) - 1, cap_radius=cap_radius, rise=rise,
                      cut=TIP_FLAT - rise)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--level", choices=sorted(LEVELS), default="coarse")
    parser.add_argument("--tip", choices=["dome", "flat"], default="flat",
                        help="tip shape: flat (default) or dome (a spherical cap tangent to the ogive)")
    parser.add_argument("-o", "--output")
    args = parser.parse_args(argv)
    mesh, info = build(args.level, args.tip)
    path = args.output or os.path.join(HERE, f"penetration_{args.level}.msh")
    points = np.array(mesh.nodes)
    for name in ("rod", "target"):
        hexes = np.array([h for v, h in mesh.hexes if v == name])
        vol = hex_volumes(points, hexes)
        if vol.min() <= 0.0:
            print(f"make_mesh: {name}: a zone of volume {vol.min():.3e} <= 0", file=sys.stderr)
            return 1
        edges = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
                 (0, 4), (1, 5), (2, 6), (3, 7)]
        p = points[hexes]
        shortest = min(np.linalg.norm(p[:, i] - p[:, j], axis=1).min() for i, j in edges)
        extra = ""
        if name == "rod":
            extra = f", mass {4.0 * vol.sum() * 7830.0 * 1e3:.3f} g (whole rod, 7830 kg/m^3)"
        print(f"{name}: {len(hexes)} zones, quarter volume {vol.sum():.6e} m^3, shortest edge "
              f"{shortest * 1e3:.4f} mm{extra}")
    print(f"rod tip ({args.tip}): edge radius {info['r_tip'] * 1e3:.4f} mm, cap radius "
          f"{info['cap_radius'] * 1e3:.4f} mm, apex {info['rise'] * 1e3:.4f} mm below the flat, "
          f"{info['cut'] * 1e3:.4f} mm of the sharp tip removed")
    print(f"rod: {info['rod_layers']} layers, tip flat radius {info['r_tip'] * 1e3:.4f} mm; "
          f"target: {info['target_layers']} layers; {len(mesh.nodes)} nodes")
    mesh.write(path)
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
