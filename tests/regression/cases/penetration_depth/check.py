#!/usr/bin/python3
"""tools/penetration_depth.py on dumps written here with known answers.

Three dumps (SI units) of two unit-cube zones of block `rod` and one of block
`target`; the rod's lowest node goes to z = -0.0123 m, then -0.0456 m; in the
third dump the zone holding the deepest node is eroded (/zones/alive = 0) and
the other rod zone's lowest node is at -0.0300 m; a target node lies deeper
still (-0.5 m) and must be ignored. Criteria (each can fail):
* P = 45.6 mm exactly to the printed digits (the deepest live rod node over
  the dumps: the second dump; the eroded zone of the third is left out);
* dumps 10 us apart pass, 10.5 us apart exit with code 2;
* an unknown block name exits with an error naming the valid ones.
"""

import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

from impact3d_tools import dump

TOOL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "..",
                    "tools", "penetration_depth.py")


def cube(origin):
    """Nodes and connectivity of a unit-size (1 cm) hexahedron at origin."""
    o = np.asarray(origin, dtype=float)
    corners = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                        [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], dtype=float) * 0.01
    return o + corners


def write(path, time, rod_bottoms, alive=None):
    """Two rod zones whose bottoms are at rod_bottoms, one target zone below."""
    points = np.vstack([cube([0.0, 0.0, rod_bottoms[0]]), cube([0.02, 0.0, rod_bottoms[1]]),
                        cube([0.0, 0.0, -0.5])])
    connectivity = np.arange(24).reshape(3, 8)
    mass = np.full(24, 0.1)
    velocity = np.zeros((24, 3))
    velocity[:16, 2] = -100.0
    zones = {"density": np.ones(3), "volume": np.full(3, 1e-6)}
    if alive is not None:
        zones["alive"] = np.asarray(alive, dtype=np.int32)
    dump.write(path, points, connectivity, zones, node_velocity=velocity, node_mass=mass,
               block=[1, 1, 2], attrs={"time": time, "units": "si"})
    with h5py.File(path, "a") as handle:
        handle["mesh"].attrs["block_names"] = np.bytes_("rod,target")


def run(*args):
    result = subprocess.run([sys.executable, TOOL, *args], capture_output=True, text=True)
    return result.returncode, result.stdout + result.stderr


def main():
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        write(os.path.join(tmp, "dump_000000.h5"), 0.0, [0.0, 0.0])
        write(os.path.join(tmp, "dump_000100.h5"), 10.0e-6, [-0.0123, -0.0456], [1, 1, 1])
        write(os.path.join(tmp, "dump_000200.h5"), 20.0e-6, [-0.0300, -0.0700], [1, 0, 1])
        code, text = run(tmp)
        print(text)
        if code != 0 or "P = 45.6000 mm" not in text or "t = 10.000 us" not in text:
            failures.append(f"expected P = 45.6000 mm at t = 10 us, exit 0 (got exit {code})")
        late = os.path.join(tmp, "late")
        os.mkdir(late)
        write(os.path.join(late, "dump_000000.h5"), 0.0, [0.0, 0.0])
        write(os.path.join(late, "dump_000100.h5"), 10.5e-6, [-0.001, -0.001])
        code, text = run(late, "--quiet")
        print(text)
        if code != 2 or "10.500 us apart" not in text:
            failures.append(f"dumps 10.5 us apart: expected exit 2 naming the gap (got {code})")
        code, text = run(tmp, "--block", "projectile")
        print(text)
        if code == 0 or "blocks: rod, target" not in text:
            failures.append("unknown block: expected an error listing rod, target")
    if failures:
        print("penetration_depth: FAILED: " + "; ".join(failures))
        return 1
    print("penetration_depth: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
