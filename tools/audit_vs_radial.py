#!/usr/bin/python3
"""The contact audit against the ray cast, on a curved interface that is
star-shaped about the origin (the D2 curved Sedov split of docs/problems.md).

For every dump of a run: the largest penetration of the inner block's
interface nodes beyond the outer block's faceted surface by
tools/radial_gap.py (a ray from the origin through each node) and by the
audit (the dump's /nodes/contact_gap: the signed distance to the nearest
point of the same faceted surface, negative inside), and their ratio.

The two measure along different directions: the ray is radial, the audit
takes the nearest point, whose direction is the facet's normal. For a node
at depth d behind a facet whose normal makes an angle a with the ray, the
ray gives d / cos(a) and the audit d; on a faceted sphere a is at most
about half the angle a segment subtends (h / (2R): 0.05 on the medium mesh)
so the two agree to 1 - cos(a) < 0.2% where the deepest node lies behind
a facet's interior. Near an edge of the faceting, the nearest point is on the
edge and the audit is the smaller by up to that angle's cosine too.

Usage: audit_vs_radial.py WORKDIR [INNER OUTER RADIUS]
"""

import glob
import os
import sys

import h5py
import numpy as np

import radial_gap  # noqa: E402


def compare(workdir, inner_block=1, outer_block=2, radius=0.5):
    """[(time, ray-cast max, audit max over the same nodes)] per dump."""
    paths = sorted(glob.glob(os.path.join(workdir, "*_[0-9][0-9][0-9][0-9][0-9][0-9].h5")))
    first = radial_gap.dump.load(paths[0])
    inner, faces = radial_gap.interface(first, inner_block, outer_block, radius)
    rows = []
    for path in paths:
        d = radial_gap.dump.load(path)
        ray = radial_gap.penetration(d["coordinates"], inner, faces)
        with h5py.File(path, "r") as f:
            gap = f["nodes/contact_gap"][...]
        rows.append((float(d["attrs"]["time"]), float(np.nanmax(ray)),
                     float(max(-gap[inner].min(), 0.0))))
    return rows


def main(argv):
    if len(argv) not in (1, 4):
        print(__doc__)
        return 2
    inner, outer, radius = (1, 2, 0.5) if len(argv) == 1 else \
        (int(argv[1]), int(argv[2]), float(argv[3]))
    print("%8s %12s %12s %8s" % ("time", "ray cast", "audit", "ratio"))
    for time, ray, audit in compare(argv[0], inner, outer, radius):
        ratio = audit / ray if ray > 0 else float("nan")
        print("%8.4f %12.4e %12.4e %8.4f" % (time, ray, audit, ratio))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
