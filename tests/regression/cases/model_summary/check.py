#!/usr/bin/python3
"""The model summary printed by --check and at the start of a run (issue 34).

Usage: check.py EXE WORKDIR [--mpiexec mpirun] [--ranks 1 3]

boxes.nml: a 2 x 1 x 0.5 cm box, 8 x 4 x 2 zones, block 'left' (x < 1,
al6061, no density given: the library's rho0 = 2.703 by default) and block
'right' (x > 1, cu_ofhc, density 8.93), every node at v = (0, 0, -0.01) cm/us;
a probe at the point (0.3, 0.3, 0.2).
rod.nml: a quarter rod (radius R = 0.5, length L = 2) of ti6al4v without a
density (the library's rho0 = 4.419), v = (0, 0, -0.02).

Criteria (each line of the summary parsed from the standard output of
`impact3d --check` on every rank count asked):
  boxes     zones 32 per block; volume 0.5 cm^3 each; mass 0.5 rho (1.3515 g,
            4.465 g), momentum (0, 0, -0.01 m), kinetic energy m 0.01^2 / 2;
            totals the sums: all to 1e-13 relative (round-off of sums of
            64 zones; a wrong corner mass, block or default density is
            off by percents).
  sets      face set areas 0.5 (xmin, xmax), 1 (ymin, ymax), 2 (zmin, zmax)
            with 8, 8, 16, 16, 32, 32 faces: to 1e-13 relative.
  probe     the probe's node is the mesh node nearest the point, (0.25, 0.25,
            0.25): distance sqrt(3) 0.05 to 1e-13 relative.
  rod       the faceted rod: the run's initial dump gives the side nodes on
            the bottom face; the polygon through them and the axis has area
            A_p (shoelace), the extruded mesh volume is A_p L exactly, so the
            summary's volume is A_p L and its mass rho0 A_p L to 1e-12
            relative; against the true quarter cylinder (pi R^2 L / 4) the
            deficit d = 1 - V / (pi R^2 L / 4) lies in (0, 1 - sin(t)/t]
            with t the largest angle between neighbouring side nodes (the
            chord deficit of an inscribed polygon: the faceting error).
  ranks     every number is the same on 1 and 3 ranks to 1e-13 relative
            (sums over the ranks' owned zones, in another order).
"""

import argparse
import math
import os
import re
import shutil
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                                "..", "tools"))
from impact3d_tools import dump as dumpmod  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
NUMBER = r"([-+0-9.Ee]+)"
BLOCK = re.compile(r"^  (?:block '(\w+)' \(material '\w+'\)|(totals)): zones (\d+), volume "
                   + NUMBER + r" \S+, mass " + NUMBER + r" \S+, momentum \(" + NUMBER + ", "
                   + NUMBER + ", " + NUMBER + r"\) \S+ \S+, kinetic energy " + NUMBER, re.M)
FACESET = re.compile(r"^  face set '(\w+)': faces (\d+), area " + NUMBER, re.M)
PROBE = re.compile(r"^  probe '(\w+)': node (\d+) at " + NUMBER + r" \S+ from the point asked",
                   re.M)

failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def close(a, b, rel):
    return abs(a - b) <= rel * max(abs(b), 1e-300)


def summary(args, deck, np_, workdir, check_only=True):
    os.makedirs(workdir, exist_ok=True)
    shutil.copy(os.path.join(HERE, deck), workdir)
    command = [args.exe] + (["--check"] if check_only else []) + [deck]
    if np_ > 1:
        command = [args.mpiexec, "--allow-run-as-root", "--oversubscribe", "-np", str(np_)] \
            + command
    run = subprocess.run(command, cwd=workdir, capture_output=True, text=True, timeout=300)
    if run.returncode != 0:
        print(run.stdout, run.stderr)
        check(False, f"{deck} on {np_} rank(s) exits 0 (got {run.returncode})")
        return None
    out = run.stdout
    blocks = {(m.group(1) or m.group(2)): [float(x) for x in m.groups()[2:]]
              for m in BLOCK.finditer(out)}
    sets = {m.group(1): (int(m.group(2)), float(m.group(3))) for m in FACESET.finditer(out)}
    probes = {m.group(1): (int(m.group(2)), float(m.group(3))) for m in PROBE.finditer(out)}
    return blocks, sets, probes


def check_boxes(args, ranks):
    results = {}
    for n in ranks:
        got = summary(args, "boxes.nml", n, os.path.join(args.workdir, f"boxes_np{n}"))
        if got is None:
            return
        results[n] = got
        blocks, sets, probes = got
        v = -0.01
        for name, rho in (("left", 2.703), ("right", 8.93)):
            m = 0.5 * rho
            want = [32, 0.5, m, 0.0, 0.0, v * m, 0.5 * m * v * v]
            have = blocks.get(name)
            check(have is not None and all(close(h, w, 1e-13) or (w == 0 and h == 0)
                                           for h, w in zip(have, want)),
                  f"np {n}: block {name}: {have} == {want} (1e-13)")
        m = 0.5 * 2.703 + 0.5 * 8.93
        want = [64, 1.0, m, 0.0, 0.0, v * m, 0.5 * m * v * v]
        have = blocks.get("totals")
        check(have is not None and all(close(h, w, 1e-13) or (w == 0 and h == 0)
                                       for h, w in zip(have, want)),
              f"np {n}: totals: {have} == {want} (1e-13)")
        for name, faces, area in (("xmin", 8, 0.5), ("xmax", 8, 0.5), ("ymin", 16, 1.0),
                                  ("ymax", 16, 1.0), ("zmin", 32, 2.0), ("zmax", 32, 2.0)):
            have = sets.get(name)
            check(have is not None and have[0] == faces and close(have[1], area, 1e-13),
                  f"np {n}: face set {name}: {have} == ({faces}, {area})")
        have = probes.get("p")
        check(have is not None and close(have[1], math.sqrt(3.0) * 0.05, 1e-13),
              f"np {n}: probe p: distance {have} == sqrt(3) 0.05")
    compare_ranks(results, "boxes")


def compare_ranks(results, what):
    if len(results) < 2:
        return
    first = results[min(results)]
    for n, got in results.items():
        same = all(close(a, b, 1e-13) or a == b == 0
                   for key in first[0] for a, b in zip(first[0][key], got[0].get(key, [])))
        same = same and all(close(first[1][k][1], got[1][k][1], 1e-13) for k in first[1])
        check(same, f"{what}: np {n} summary == np {min(results)} summary (1e-13)")


def check_rod(args, ranks):
    results = {}
    radius, length, rho0 = 0.5, 2.0, 4.419
    for n in ranks:
        got = summary(args, "rod.nml", n, os.path.join(args.workdir, f"rod_np{n}"))
        if got is None:
            return
        results[n] = got
    # One short run for the initial dump (the node positions).
    workdir = os.path.join(args.workdir, "rod_run")
    got = summary(args, "rod.nml", 1, workdir, check_only=False)
    if got is None:
        return
    data = dumpmod.load(os.path.join(workdir, "out_rod", "dump_000000.h5"))
    x = data["coordinates"]
    bottom = x[np.abs(x[:, 2] - x[:, 2].min()) < 1e-12]
    r = np.hypot(bottom[:, 0], bottom[:, 1])
    side = bottom[np.abs(r - radius) < 1e-12 * radius]
    angle = np.sort(np.arctan2(side[:, 1], side[:, 0]))
    check(len(angle) >= 3 and abs(angle[0]) < 1e-12 and abs(angle[-1] - math.pi / 2) < 1e-12,
          f"rod: {len(angle)} side nodes from 0 to 90 degrees")
    # Polygon origin -> side nodes in angle order -> origin.
    area = 0.5 * radius * radius * float(np.sum(np.sin(np.diff(angle))))
    theta = float(np.max(np.diff(angle)))
    exact = math.pi * radius * radius * length / 4.0
    bound = 1.0 - math.sin(theta) / theta
    for n, (blocks, _, _) in results.items():
        have = blocks.get("rod")
        if have is None:
            check(False, f"np {n}: rod: no block line")
            continue
        volume, mass = have[1], have[2]
        check(close(volume, area * length, 1e-12),
              f"np {n}: rod volume {volume!r} == faceted A_p L {area * length!r} (1e-12)")
        check(close(mass, rho0 * area * length, 1e-12),
              f"np {n}: rod mass {mass!r} == rho0 A_p L {rho0 * area * length!r} (1e-12)")
        deficit = 1.0 - volume / exact
        check(0.0 < deficit <= bound * (1 + 1e-9),
              f"np {n}: rod deficit against pi R^2 L/4: {deficit:.5e} in (0, {bound:.5e}] "
              f"(largest facet angle {math.degrees(theta):.3f} deg)")
        check(close(have[5], -0.02 * mass, 1e-13),
              f"np {n}: rod momentum z {have[5]!r} == -0.02 m")
    compare_ranks(results, "rod")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("exe")
    parser.add_argument("workdir")
    parser.add_argument("--mpiexec", default="mpirun")
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 3])
    args = parser.parse_args()
    args.exe = os.path.abspath(args.exe)
    shutil.rmtree(args.workdir, ignore_errors=True)
    os.makedirs(args.workdir)
    check_boxes(args, args.ranks)
    check_rod(args, args.ranks)
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
