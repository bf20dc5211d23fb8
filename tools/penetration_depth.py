#!/usr/bin/python3
"""Depth of penetration from impact3d dumps (problems/penetration).

Usage:
  penetration_depth.py DUMP.h5|DIRECTORY ... [--block rod] [--surface Z]
                       [--max-gap DT] [--quiet]

P is the depth below the target face z = Z (default 0) of the deepest node of
a live zone of the rod block (default `rod`), the largest over the dumps
given (a directory stands for its dump_*.h5, failed-run dumps included). A
zone is live unless the dump has /zones/alive and it is 0 there (eroded
zones are left out; their nodes stay in /mesh/coordinates at their last
position). The dumps must be at most --max-gap apart in simulated time
(default 10 us, in the dumps' units), else the deepest point may fall between
two of them: exit code 2 with the widest gap named.

Prints per dump: time (us), depth (mm), the rod's kinetic energy, its
mean axial velocity (momentum/mass, m/s) from its nodes and the largest
distance of a live rod node from the z axis (mm; above the shank's radius
the nose has mushroomed); then
`P = ... mm`. Length and time units from the dumps' `units` attribute
('si': m, s; 'cm-g-us-mbar': cm, us).
"""

import argparse
import glob
import os
import sys

import h5py
import numpy as np

from impact3d_tools import dump

SCALES = {"si": dict(mm=1e3, us=1e6, mps=1.0, joule=1.0),
          "cm-g-us-mbar": dict(mm=10.0, us=1.0, mps=1e4, joule=1e5)}


def dump_files(paths):
    """The dump files named or found in the directories given, sorted by time."""
    files = []
    for path in paths:
        if os.path.isdir(path):
            files += glob.glob(os.path.join(path, "dump_*.h5"))
        else:
            files.append(path)
    if not files:
        raise SystemExit("penetration_depth: no dump found in " + ", ".join(paths))
    timed = []
    for path in files:
        with h5py.File(path, "r") as handle:
            timed.append((float(np.ravel(handle.attrs["time"])[0]), path))
    return [path for _, path in sorted(timed)]


def block_id(path, name):
    """1-based id of block name in a dump (/mesh attribute block_names)."""
    with h5py.File(path, "r") as handle:
        names = handle["mesh"].attrs["block_names"]
    if isinstance(names, bytes):
        names = names.decode()
    names = [n.strip() for n in str(names).split(",")]
    if name not in names:
        raise SystemExit(f"penetration_depth: {path}: no block '{name}' (blocks: "
                         f"{', '.join(names)})")
    return names.index(name) + 1


def measure(path, block, surface):
    """Time, depth, rod kinetic energy and mean axial velocity of one dump."""
    data = dump.load(path)
    live = data["block"] == block
    if "alive" in data:
        live &= data["alive"] != 0
    nodes = np.unique(data["connectivity"][live])
    time = dump.problem_time(data)
    if nodes.size == 0:
        return time, float("nan"), 0.0, float("nan"), data["attrs"].get("units", ""), float("nan")
    depth = max(surface - data["coordinates"][nodes, 2].min(), 0.0)
    radius = float(np.hypot(data["coordinates"][nodes, 0], data["coordinates"][nodes, 1]).max())
    mass = data["node_mass"][nodes]
    velocity = data["node_velocity"][nodes]
    kinetic = 0.5 * float(np.sum(mass * np.sum(velocity ** 2, axis=1)))
    axial = float(np.sum(mass * velocity[:, 2]) / np.sum(mass))
    return time, depth, kinetic, axial, data["attrs"].get("units", ""), radius


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("paths", nargs="+")
    parser.add_argument("--block", default="rod")
    parser.add_argument("--surface", type=float, default=0.0,
                        help="z of the target face (dump length units)")
    parser.add_argument("--max-gap", type=float,
                        help="largest time between dumps (dump time units; default 10 us)")
    parser.add_argument("--quiet", action="store_true", help="print P only")
    args = parser.parse_args(argv)
    files = dump_files(args.paths)
    block = block_id(files[0], args.block)
    rows = [measure(path, block, args.surface) for path in files]
    units = rows[0][4]
    if units not in SCALES:
        raise SystemExit(f"penetration_depth: units '{units}' not known (si, cm-g-us-mbar)")
    scale = SCALES[units]
    gap_limit = args.max_gap if args.max_gap is not None else 10.0 / scale["us"]
    if not args.quiet:
        print(f"{'time (us)':>12} {'depth (mm)':>11} {'rod KE (J)':>12} {'rod vz (m/s)':>13} "
              f"{'rod r (mm)':>11}  dump")
        for (time, depth, kinetic, axial, _, radius), path in zip(rows, files):
            print(f"{time * scale['us']:12.3f} {depth * scale['mm']:11.4f} "
                  f"{kinetic / scale['joule'] * 4.0:12.5g} {axial * scale['mps']:13.3f} "
                  f"{radius * scale['mm']:11.4f}  {os.path.basename(path)}")
        print("(rod KE: the quarter model's times 4; rod r: the largest distance of a live rod "
              "node from the axis, the nose's spread when above the shank's radius)")
    depths = np.array([r[1] for r in rows])
    best = int(np.nanargmax(depths))
    times = np.array([r[0] for r in rows])
    gaps = np.diff(times)
    print(f"P = {depths[best] * scale['mm']:.4f} mm (block '{args.block}', dump at "
          f"t = {times[best] * scale['us']:.3f} us, {len(files)} dumps)")
    if gaps.size and gaps.max() > gap_limit * (1.0 + 1e-9):
        worst = int(np.argmax(gaps))
        print(f"penetration_depth: dumps {gaps.max() * scale['us']:.3f} us apart (t = "
              f"{times[worst] * scale['us']:.3f} to {times[worst + 1] * scale['us']:.3f} us), "
              f"more than the {gap_limit * scale['us']:.3f} us allowed", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
