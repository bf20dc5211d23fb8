"""Read a run's history.txt: one `# ` header line naming the columns, then
whitespace-separated numeric rows, the first for cycle 0 (the initial state,
no step taken), then one per history_every cycles (docs/user-guide.md,
"Output").

    h = history.read(run_dir)        # or the path of history.txt
    h.names                          # column names, header order
    h.rows                           # (nrow, ncol) float array, cycle 0 included
    h["energy_error"]                # one column
    h.steps()                        # the same without the cycle-0 row
    history.columns(run_dir)         # {name: column}
"""

import os

import numpy as np


class History:
    """The columns of a history file: names, rows, and lookup by name."""

    def __init__(self, names, rows):
        self.names = list(names)
        self.rows = rows

    def __getitem__(self, name):
        return self.rows[:, self.names.index(name)]

    def __contains__(self, name):
        return name in self.names

    def __len__(self):
        return len(self.rows)

    def index(self, name):
        return self.names.index(name)

    def steps(self):
        """The rows after steps: the cycle-0 row (if any) left out."""
        if len(self.rows) and self.rows[0, 0] == 0:
            return History(self.names, self.rows[1:])
        return self

    def columns(self):
        return {name: self.rows[:, i] for i, name in enumerate(self.names)}


def path_of(source):
    """history.txt of a run directory, or source itself if it is a file."""
    return os.path.join(source, "history.txt") if os.path.isdir(source) else source


def read(source):
    """The history of a run (its directory or the file's path)."""
    with open(path_of(source), encoding="utf-8") as handle:
        header = handle.readline()
        if not header.startswith("#"):
            raise ValueError("%s: the first line is not the '# ' header" % path_of(source))
        names = header[1:].split()
        rows = [[float(x) for x in line.split()] for line in handle if line.strip()]
    rows = np.array(rows, dtype=float).reshape(-1, len(names))
    return History(names, rows)


def columns(source):
    """The history of a run as {name: column}."""
    return read(source).columns()
