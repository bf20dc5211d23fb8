"""Plot zone profiles of an impact3d dump against the exact solution.

Usage:
    plot_profiles.py --problem {sod,riemann2,sedov,noh} dump.h5 [-o out.png]
                     [--title TEXT] [--dpi N] [--region MIN MAX] [problem options]

Four panels: density, pressure, velocity and specific internal energy
against x (Riemann problems) or the centroid radius (sedov, noh).  Each zone
is a dot (u is the velocity component along the axis, or the radial
component); the exact solution at the dump time is a line.  --region limits
the horizontal axis.  The problem options and their defaults are those of
compare.py (see `compare.py --help`).  Writes a PNG (matplotlib, Agg
backend); default name: <dump without .h5>_profiles.png.
"""

import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from impact3d_tools import compare, dump  # noqa: E402

PANELS = (("rho", "density"), ("p", "pressure"), ("u", "velocity"),
          ("e", "specific internal energy"))


def _limits(numeric, exact):
    """Vertical limits: the zone values' range, widened to show the exact
    values but by at most 1.5 times that range on each side (the Sedov e
    diverges at the centre and would otherwise flatten the panel), plus a
    5% margin."""
    numeric = numeric[np.isfinite(numeric)]
    exact = exact[np.isfinite(exact)]
    if numeric.size == 0:
        return None
    low, high = float(numeric.min()), float(numeric.max())
    span = high - low if high > low else max(abs(high), 1.0)
    if exact.size:
        low = min(low, max(float(exact.min()), low - 1.5 * span))
        high = max(high, min(float(exact.max()), high + 1.5 * span))
    pad = 0.05 * (high - low)
    return low - pad, high + pad


def plot(args):
    """Make the figure for parsed arguments; return the output path."""
    compare.fill_defaults(args)
    data = dump.load(args.dump)
    time = args.time if args.time is not None else dump.problem_time(data)
    setup = compare.Setup(args, time)
    state = compare.zone_state(data, args)
    keep = state["keep"]
    coord = state["coord"][keep]
    numeric = {"rho": state["rho"][keep], "p": state["p"][keep],
               "u": state["u"][keep], "e": state["e"][keep]}
    at_zones = dict(zip(("rho", "u", "p", "e"), setup.exact(coord)))

    if args.region is not None:
        low, high = args.region
    elif setup.planar:
        low, high = float(coord.min()), float(coord.max())
    else:
        low, high = 0.0, float(coord.max())
    line_x = np.linspace(low, high, 4001)
    if not setup.planar:
        line_x = line_x[line_x > 0.0]
    line = dict(zip(("rho", "u", "p", "e"), setup.exact(line_x)))
    in_view = (coord >= low) & (coord <= high)

    figure, axes = plt.subplots(2, 2, figsize=(11, 8), sharex=True)
    marker = 4.0 if coord.size < 5000 else 1.0
    for axis, (key, label) in zip(axes.ravel(), PANELS):
        axis.plot(coord, numeric[key], ".", ms=marker, color="tab:blue",
                  label="impact3d zones", rasterized=True)
        axis.plot(line_x, line[key], "-", lw=1.2, color="k", label="exact")
        limits = _limits(numeric[key][in_view], at_zones[key][in_view])
        if limits is not None:
            axis.set_ylim(*limits)
        axis.set_ylabel(label)
        axis.set_xlim(low, high)
        axis.grid(alpha=0.3)
    xlabel = f"{args.axis}" if setup.planar else "radius"
    for axis in axes[1]:
        axis.set_xlabel(xlabel)
    axes[0, 0].legend(loc="best", fontsize=8)
    title = args.title or (f"{args.problem}: {os.path.basename(args.dump)}, "
                           f"t = {time:.6g}, {coord.size} zones")
    figure.suptitle(title)
    figure.tight_layout()
    out = args.output or os.path.splitext(args.dump)[0] + "_profiles.png"
    figure.savefig(out, dpi=args.dpi)
    plt.close(figure)
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    compare.add_problem_arguments(parser)
    parser.add_argument("-o", "--output", default=None, help="PNG file to write")
    parser.add_argument("--title", default=None)
    parser.add_argument("--dpi", type=int, default=120)
    args = parser.parse_args(argv)
    try:
        out = plot(args)
    except (OSError, ValueError, KeyError) as error:
        print(f"plot_profiles.py: {args.dump}: {error}", file=sys.stderr)
        return 1
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
