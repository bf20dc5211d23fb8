#!/usr/bin/python3
"""The same deck on the same rank count gives the same partition every
time: a Sedov cube of 20^3 zones (the deck of tools/impact3d_tools/weak.py
with one layer) on 4 ranks, where no cut is obvious, is set up three times with --check and the partition lines (faces cut, imbalance,
ghost nodes, set-up bytes) must be identical, and the imbalance at most 3%.

Usage: partition_twice.py EXE WORKDIR [--mpiexec mpirun]

A non-reproducible partitioner fails it: PT-Scotch's ParMETIS-compatible
interface gave a different cut on every run of such a deck."""

import argparse
import os
import re
import sys

from impact3d_tools.weak import run_stack, sedov_stack_deck


def main():
    p = argparse.ArgumentParser()
    p.add_argument("exe")
    p.add_argument("workdir")
    p.add_argument("--mpiexec", default="mpirun")
    args = p.parse_args()
    lines = []
    for i in range(3):
        code, rep, out = run_stack(os.path.abspath(args.exe), 20, 4,
                                   os.path.join(args.workdir, f"run{i}"), args.mpiexec,
                                   deck_text=sedov_stack_deck(20, 1), extra=("--check",))
        m = re.search(r"^partition: .*$", out, re.M)
        if code != 0 or not m:
            print(out[-2000:])
            print(f"FAIL run {i}: exit {code}")
            return 1
        lines.append(m.group(0))
        print(m.group(0))
    same = len(set(lines)) == 1
    imbalance = float(re.search(r"imbalance ([\d.]+)%", lines[0]).group(1))
    print(f"{'PASS' if same else 'FAIL'} the same partition three times")
    print(f"{'PASS' if imbalance <= 3.0 else 'FAIL'} imbalance {imbalance}% <= 3%")
    return 0 if same and imbalance <= 3.0 else 1


if __name__ == "__main__":
    sys.exit(main())
