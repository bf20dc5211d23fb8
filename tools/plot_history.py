#!/usr/bin/python3
"""Plot columns of impact3d time histories against time (or any column), to PNG.

Reads
  * history.txt: one header line '# name name ...', then rows of
    whitespace-separated numbers (docs/user-guide.md, Output);
  * probe CSV files: a header line of comma-separated column names, then rows
    of comma-separated numbers;
the kind told by the first line ('# ' starts a history file).

Usage:
  plot_history.py FILE [FILE ...] -y COLUMN [COLUMN ...] [-x time] [-o plot.png]
                  [--logy] [--title TEXT] [--list]

Every COLUMN is plotted from every FILE that has it, against -x (default:
the file's time column, 'time' in history.txt, 'time [us]' or the like in a
probe file). A column is named with or without its unit suffix: -y
velocity_z finds a probe's 'velocity_z [cm/us]'. A COLUMN (or the -x
column) that none of the files has is an error
(exit 2) naming the file(s), the column, the closest name and the valid ones.
--list prints each file's columns. Examples:

  tools/plot_history.py out/history.txt -y total_energy kinetic_energy -o energy.png
  tools/plot_history.py out/probe_rear.csv -y velocity_z -o rear.png
"""

import argparse
import difflib
import os
import sys

import numpy as np

from impact3d_tools import history


class InputError(Exception):
    """A problem with the command line or a file: reported, exit 2."""


def read_table(path):
    """Column names and the table (impact3d_tools.history.History) of a
    history or probe file."""
    try:
        table = history.read_table(path)
    except OSError as e:
        raise InputError("%s: cannot read it: %s" % (path, e.strerror))
    except ValueError as e:
        raise InputError(str(e))
    return table.names, table


def unknown_column(column, files, tables):
    names = sorted({history.base_name(n) for f in files for n in tables[f][0]})
    close = difflib.get_close_matches(history.base_name(column), names, n=1)
    hint = "; did you mean '%s'?" % close[0] if close else ""
    return ("%s: no column '%s'%s (columns: %s)"
            % (", ".join(files), column, hint, ", ".join(tables[files[0]][0])))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("files", nargs="+", help="history.txt or probe CSV files")
    ap.add_argument("-y", nargs="+", default=[], metavar="COLUMN", help="columns to plot")
    ap.add_argument("-x", default=None, metavar="COLUMN",
                    help="abscissa (default: the file's time column, 'time' or 'time [unit]')")
    ap.add_argument("-o", "--output", default="history.png", help="PNG file (default history.png)")
    ap.add_argument("--logy", action="store_true", help="logarithmic y axis (of |value|)")
    ap.add_argument("--title", default=None)
    ap.add_argument("--list", action="store_true", help="print the columns of each file")
    a = ap.parse_args(argv)
    try:
        tables = {f: read_table(f) for f in a.files}
        if a.list:
            for f in a.files:
                print("%s: %s" % (f, " ".join(tables[f][0])))
            return 0
        if not a.y:
            raise InputError("no column to plot: give -y COLUMN ... (--list shows them)")
        for f in a.files:
            if a.x is None and tables[f][1].time_name() is None:
                raise InputError("%s: no time column ('time' or 'time [unit]'; columns: %s): "
                                 "give -x COLUMN" % (f, ", ".join(tables[f][0])))
            if a.x is not None and a.x not in tables[f][1]:
                raise InputError(unknown_column(a.x, [f], tables) + " [the -x column]")
        for c in a.y:
            if not any(c in tables[f][1] for f in a.files):
                raise InputError(unknown_column(c, a.files, tables))
    except InputError as e:
        print("plot_history.py: error: %s" % e, file=sys.stderr)
        return 2

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 5))
    several = len(a.files) > 1
    xlabel = None
    for f in a.files:
        cols = tables[f][1]
        xname = cols.name_of(a.x) if a.x is not None else cols.time_name()
        xlabel = xlabel or xname
        for c in a.y:
            if c not in cols:
                continue
            y = np.abs(cols[c]) if a.logy else cols[c]
            name = cols.name_of(c)
            label = "%s: %s" % (os.path.basename(f), name) if several else name
            ax.plot(cols[xname], y, label=label)
    ax.set_xlabel(xlabel)
    if a.logy:
        ax.set_yscale("log")
    ax.grid(True, alpha=0.3)
    ax.legend()
    ax.set_title(a.title if a.title is not None else ", ".join(a.files))
    fig.tight_layout()
    fig.savefig(a.output, dpi=100)
    print("plot_history.py: wrote %s" % a.output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
