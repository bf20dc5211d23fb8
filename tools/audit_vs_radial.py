#!/usr/bin/python3
"""The contact audit against the ray cast, on a curved interface that is
star-shaped about the origin (the D2 curved Sedov split of docs/problems.md):
for every dump, the largest penetration of the inner block's interface nodes
by the ray cast and by the audit (the dump's /nodes/contact_gap), and their
ratio (impact3d_tools.radial.audit_compare, whose docstring says why the two
agree to about 1%).

Usage: tools/audit_vs_radial.py WORKDIR [INNER OUTER RADIUS]   (default 1 2 0.5)
"""
import sys

from impact3d_tools import radial


def main(argv):
    args = radial.cli_args(argv)
    if args is None:
        print(__doc__)
        return 2
    print("%8s %12s %12s %8s" % ("time", "ray cast", "audit", "ratio"))
    for time, ray, audit in radial.audit_compare(*args):
        ratio = audit / ray if ray > 0 else float("nan")
        print("%8.4f %12.4e %12.4e %8.4f" % (time, ray, audit, ratio))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
