#!/usr/bin/python3
"""Taylor anvil final shape: the y = 0 section (x against z) of the rod's
nodes in the final dump of each run directory, initial outline dashed.

Usage: plot_taylor.py -o out.png RUN_DIR [RUN_DIR ...]
"""
import argparse
import glob
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import dump  # noqa: E402


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("runs", nargs="+")
    p.add_argument("-o", "--out", required=True)
    args = p.parse_args()
    fig, ax = plt.subplots(figsize=(5, 7))
    for run in args.runs:
        files = sorted(glob.glob(os.path.join(run, "*_[0-9][0-9][0-9][0-9][0-9][0-9].h5")))
        d0, d1 = dump.load(files[0]), dump.load(files[-1])
        section = np.abs(d0["coordinates"][:, 1]) < 1e-12
        x0 = d0["coordinates"][section]
        x1 = d1["coordinates"][section]
        label = os.path.basename(os.path.normpath(run))
        ax.plot(x1[:, 0], x1[:, 2], ".", ms=2, label="%s, t = %.0f us" % (label,
                                                                     d1["attrs"]["time"]))
        ax.plot([x0[:, 0].max()] * 2, [x0[:, 2].min(), x0[:, 2].max()], "k--", lw=0.8)
    ax.set_xlabel("x (cm), section y = 0")
    ax.set_ylabel("z (cm)")
    ax.set_aspect("equal")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print("wrote " + args.out)


if __name__ == "__main__":
    main()
