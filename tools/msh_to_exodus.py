#!/usr/bin/python3
"""Convert a Gmsh mesh of 8-node hexahedra to Exodus II (impact3d_tools.exodus,
whose docstring describes the file written).

Usage: tools/msh_to_exodus.py MESH.msh OUT.exo
"""
import sys

from impact3d_tools.exodus import convert

if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    convert(sys.argv[1], sys.argv[2])
