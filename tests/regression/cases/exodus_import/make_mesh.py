#!/usr/bin/python3
"""Make two_blocks.exo, the Exodus II test mesh of this case, with tools this
project does not write: gmsh (Debian) meshes two_blocks.geo, then
tools/msh_to_exodus.py writes Exodus II with meshio (Debian python3-meshio)
and adds the block names and side sets meshio leaves out with netCDF4
(Debian python3-netcdf4), following the Exodus II file format (see that
script). Run it from anywhere: ./make_mesh.py (needs gmsh; the test uses the
committed two_blocks.exo)."""

import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
CONVERT = os.path.join(HERE, "..", "..", "..", "..", "tools", "msh_to_exodus.py")


def main():
    with tempfile.TemporaryDirectory() as tmp:
        msh = os.path.join(tmp, "two_blocks.msh")
        subprocess.run(["gmsh", "-3", "-format", "msh41", os.path.join(HERE, "two_blocks.geo"),
                        "-o", msh], check=True, stdout=subprocess.DEVNULL)
        subprocess.run([sys.executable, CONVERT, msh, os.path.join(HERE, "two_blocks.exo")], check=True)


if __name__ == "__main__":
    main()
