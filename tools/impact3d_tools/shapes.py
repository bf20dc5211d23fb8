"""Measures of a run's shape from its dumps: a Taylor rod's final length and
foot diameter, an imploding shell's inner radius over time."""

import glob
import os

import numpy as np

from impact3d_tools import dump


def rod_shape(path):
    """Final length (z extent) and largest diameter (2 max sqrt(x^2 + y^2)) of
    the rod, the block of the first zone, in a dump."""
    d = dump.load(path)
    rod = np.unique(d["connectivity"][d["block"] == d["block"][0]].ravel())
    x = d["coordinates"][rod]
    return x[:, 2].max() - x[:, 2].min(), 2.0 * np.hypot(x[:, 0], x[:, 1]).max()


def inner_radius_history(wd, origin):
    """(time, mean radius) over the dumps of the nodes at radius origin at t = 0."""
    files = sorted(glob.glob(os.path.join(wd, "*_[0-9][0-9][0-9][0-9][0-9][0-9].h5")))
    d0 = dump.load(files[0])
    inner = np.abs(np.linalg.norm(d0["coordinates"], axis=1) - origin) < 1e-9 * origin
    history = []
    for path in files:
        d = dump.load(path)
        history.append((float(d["attrs"]["time"]),
                        float(np.linalg.norm(d["coordinates"], axis=1)[inner].mean())))
    return history
