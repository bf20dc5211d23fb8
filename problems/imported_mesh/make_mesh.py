#!/usr/bin/python3
"""Make rod_quarter.exo from rod_quarter.geo: gmsh (Debian) meshes it, then
tools/msh_to_exodus.py writes Exodus II (meshio, block names and side sets
added with netCDF4). Needs gmsh only here; the deck uses the committed
rod_quarter.exo."""

import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
CONVERT = os.path.join(HERE, "..", "..", "tools", "msh_to_exodus.py")

with tempfile.TemporaryDirectory() as tmp:
    msh = os.path.join(tmp, "rod_quarter.msh")
    subprocess.run(["gmsh", "-3", "-format", "msh41", os.path.join(HERE, "rod_quarter.geo"),
                    "-o", msh], check=True, stdout=subprocess.DEVNULL)
    subprocess.run([sys.executable, CONVERT, msh, os.path.join(HERE, "rod_quarter.exo")], check=True)
