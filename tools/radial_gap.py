#!/usr/bin/python3
"""Penetration across a curved contact interface that is star-shaped about the
origin (impact3d_tools.radial, whose docstring gives the method): the largest
radial penetration of the inner block's interface nodes in each dump.

Usage: tools/radial_gap.py WORKDIR [INNER OUTER RADIUS]   (default 1 2 0.5)
"""
import sys

import numpy as np

from impact3d_tools import radial


def main(argv):
    args = radial.cli_args(argv)
    if args is None:
        print(__doc__)
        return 2
    for time, pen, direction in radial.history(*args):
        print("t = %.4f  largest penetration %.3e  direction %s"
              % (time, pen, np.array2string(direction, precision=3)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
