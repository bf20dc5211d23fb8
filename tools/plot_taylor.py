#!/usr/bin/python3
"""Taylor anvil final shape: the y = 0 section (x against z) of the rod's
nodes (the block of the first zone: an anvil is left out) in the final dump of
each run directory, initial outline dashed.

Usage: plot_taylor.py -o out.png [--panels] [--titles T1,T2,...]
                      [--final-length L --foot-diameter D] RUN_DIR [RUN_DIR ...]

--panels draws one column per run, side by side (default: all runs in one
panel): the whole rod above, its foot enlarged below.
--final-length and --foot-diameter draw a measured final length (a horizontal
line at the rod's lowest z plus L) and foot radius D/2 (a vertical line), e.g.
an experiment's, to compare the final shape with.
"""
import argparse
import glob
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from impact3d_tools import dump  # noqa: E402

FOOT = 1.2  # cm, height of the foot panels of --panels


def rod_nodes(d):
    """Indices of the nodes of the rod, the block of the first zone."""
    return np.unique(d["connectivity"][d["block"] == d["block"][0]].ravel())


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("runs", nargs="+")
    p.add_argument("-o", "--out", required=True)
    p.add_argument("--panels", action="store_true", help="one panel per run")
    p.add_argument("--titles", default=None, help="comma-separated labels, one per run")
    p.add_argument("--final-length", type=float, default=None,
                   help="measured final length to draw (cm)")
    p.add_argument("--foot-diameter", type=float, default=None,
                   help="measured foot diameter to draw (cm)")
    args = p.parse_args()
    titles = args.titles.split(",") if args.titles else None
    n = len(args.runs) if args.panels else 1
    if args.panels:
        # Whole rod (true aspect) above, the foot below (z < FOOT cm above the lowest point).
        fig, axes = plt.subplots(2, n, figsize=(3.0 * n + 0.6, 10), squeeze=False,
                                 gridspec_kw={"height_ratios": [2.2, 1.0]})
        rows = [(axes[0][i], axes[1][i]) for i in range(n)]
    else:
        fig, axes = plt.subplots(figsize=(5, 7), squeeze=False)
        rows = [(axes[0][0], None)]
    for i, run in enumerate(args.runs):
        whole, foot = rows[i] if args.panels else rows[0]
        files = sorted(glob.glob(os.path.join(run, "*_[0-9][0-9][0-9][0-9][0-9][0-9].h5")))
        d0, d1 = dump.load(files[0]), dump.load(files[-1])
        rod = np.zeros(d0["coordinates"].shape[0], dtype=bool)
        rod[rod_nodes(d0)] = True
        section = rod & (np.abs(d0["coordinates"][:, 1]) < 1e-12)
        x0 = d0["coordinates"][section]
        x1 = d1["coordinates"][section]
        label = titles[i] if titles else os.path.basename(os.path.normpath(run))
        zmin = d1["coordinates"][rod][:, 2].min()
        for ax in (whole, foot):
            if ax is None:
                continue
            ax.plot(x1[:, 0], x1[:, 2], ".", ms=2, label="%s, t = %.0f us" % (
                label, d1["attrs"]["time"]))
            ax.plot([x0[:, 0].max()] * 2, [x0[:, 2].min(), x0[:, 2].max()], "k--", lw=0.8,
                    label="initial radius" if ax is foot else None)
            if args.final_length is not None and ax is whole:
                ax.axhline(zmin + args.final_length, color="tab:red", lw=1.0,
                           label="measured final length %.2f cm" % args.final_length)
            if args.foot_diameter is not None:
                ax.axvline(0.5 * args.foot_diameter, color="tab:green", lw=1.0,
                           label="measured foot radius %.3f cm" % (0.5 * args.foot_diameter))
            ax.set_xlabel("x (cm), section y = 0")
            ax.set_ylabel("z (cm)")
            ax.grid(alpha=0.3)
        if args.panels:
            whole.set_aspect("equal")
            right = 1.05 * max(x1[:, 0].max(), 0.5 * (args.foot_diameter or 0.0))
            whole.set_xlim(0.0, max(1.6, right))
            whole.set_title(label, fontsize=9)
            foot.set_ylim(zmin - 0.05, zmin + FOOT)
            foot.set_xlim(0.6 * x0[:, 0].max(), max(1.3, right))
            foot.set_title("foot, z < %g cm" % FOOT, fontsize=9)
            foot.legend(fontsize=6, loc="upper left")
        else:
            whole.set_aspect("equal")
    if not args.panels:
        rows[0][0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print("wrote " + args.out)


if __name__ == "__main__":
    main()
