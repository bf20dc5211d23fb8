#!/usr/bin/python3
"""Verney shell plots: inner radius history against the rigid-plastic energy
balance (impact3d_tools.exact.verney) and the energy conversion (kinetic -> internal,
i.e. plastic work) from history.txt.

Usage: plot_verney.py RUN_DIR [-o PREFIX]   (RUN_DIR holds the dumps and history.txt)
Writes PREFIX_radius.png and PREFIX_energy.png (default docs/img/verney).
"""
import argparse
import glob
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from impact3d_tools import dump  # noqa: E402
from impact3d_tools import history  # noqa: E402
from impact3d_tools.exact import verney as exact_verney  # noqa: E402


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("run")
    p.add_argument("-o", "--out", default=os.path.join(os.path.dirname(__file__), "..", "docs",
                                                         "img", "verney"))
    args = p.parse_args()
    files = sorted(glob.glob(os.path.join(args.run, "*_[0-9][0-9][0-9][0-9][0-9][0-9].h5")))
    d0 = dump.load(files[0])
    r0 = np.linalg.norm(d0["coordinates"], axis=1)
    inner = np.abs(r0 - r0.min()) < 1e-9 * r0.min()
    times, radii = [], []
    for path in files:
        d = dump.load(path)
        times.append(float(d["attrs"]["time"]))
        radii.append(float(np.linalg.norm(d["coordinates"], axis=1)[inner].mean()))
    a_stop, t_stop, a, t = exact_verney.verney()
    tt = np.linspace(0.0, max(times), 400)
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(tt, exact_verney.radius_at(tt, a, t, a_stop, t_stop), "k-",
            label="rigid-plastic energy balance")
    ax.plot(times, radii, "o", label="impact3d (mean inner radius)")
    ax.set_xlabel("time (us)")
    ax.set_ylabel("inner radius (cm)")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out + "_radius.png", dpi=110)
    h = history.read(args.run)
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(h["time"], h["kinetic_energy"], label="kinetic")
    ax.plot(h["time"], h["internal_energy"], label="internal (plastic work + elastic)")
    ax.plot(h["time"], h["total_energy"], "k--", label="total")
    ax.set_xlabel("time (us)")
    ax.set_ylabel("energy, octant (Mbar cm^3)")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out + "_energy.png", dpi=110)
    print("wrote %s_radius.png and %s_energy.png" % (args.out, args.out))


if __name__ == "__main__":
    main()
