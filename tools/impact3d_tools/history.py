"""Read a run's history.txt: one `# ` header line naming the columns, then
whitespace-separated numeric rows, the first for cycle 0 (the initial state,
no step taken), then one per history_every cycles (docs/user-guide.md,
"Output"); and its probe files, probe_<name>.csv: a header of
comma-separated names with their units (`time [us]`, `velocity_z [cm/us]`),
then comma-separated rows.

A column is found by its full name or by its name without the unit suffix
(`velocity_z` finds `velocity_z [cm/us]`); time_name() is the file's time
column, whatever its unit.

    h = history.read(run_dir)        # or the path of history.txt
    h.names                          # column names, header order
    h.rows                           # (nrow, ncol) float array, cycle 0 included
    h["energy_error"]                # one column
    h.steps()                        # the same without the cycle-0 row
    history.columns(run_dir)         # {name: column}
    t = history.read_table("probe_rear.csv")   # history.txt or a probe CSV
    t["velocity_z"], t[t.time_name()]
"""

import os
import re

import numpy as np


class History:
    """The columns of a history file: names, rows, and lookup by name."""

    def __init__(self, names, rows):
        self.names = list(names)
        self.rows = rows

    def __getitem__(self, name):
        return self.rows[:, self.index(name)]

    def __contains__(self, name):
        return self.find(name) is not None

    def __len__(self):
        return len(self.rows)

    def find(self, name):
        """Index of the column called name, or whose name without its unit
        suffix is name (the first one); None when there is none."""
        if name in self.names:
            return self.names.index(name)
        bare = base_name(name)
        for i, n in enumerate(self.names):
            if base_name(n) == bare:
                return i
        return None

    def index(self, name):
        i = self.find(name)
        if i is None:
            raise KeyError(name)
        return i

    def name_of(self, name):
        """The column's full name (with its unit, if it has one)."""
        return self.names[self.index(name)]

    def time_name(self):
        """The full name of the time column (`time`, `time [us]`, ...); None
        when the file has none."""
        i = self.find("time")
        return None if i is None else self.names[i]

    def steps(self):
        """The rows after steps: the cycle-0 row (if any) left out."""
        if len(self.rows) and self.rows[0, 0] == 0:
            return History(self.names, self.rows[1:])
        return self

    def columns(self):
        return {name: self.rows[:, i] for i, name in enumerate(self.names)}


def base_name(name):
    """A column name without its unit suffix: 'time [us]' -> 'time'."""
    return re.sub(r"\s*\[[^\]]*\]\s*$", "", name.strip())


def read_table(path):
    """A history.txt (first line '# ...') or probe CSV file (first line of
    comma-separated names) as a History. Raises ValueError naming the file
    and line for a row that does not match the header."""
    with open(path, encoding="utf-8") as handle:
        lines = [line for line in handle if line.strip()]
    if not lines:
        raise ValueError("%s: the file is empty (expected a header line)" % path)
    head = lines[0].strip()
    if head.startswith("#"):
        names = head[1:].split()
        split = str.split
    else:
        names = [n.strip() for n in head.split(",")]
        split = lambda line: line.split(",")
    rows = []
    for k, line in enumerate(lines[1:], start=2):
        if line.lstrip().startswith("#"):
            continue
        fields = split(line.strip())
        if len(fields) != len(names):
            raise ValueError("%s: line %d has %d values, the header names %d columns"
                             % (path, k, len(fields), len(names)))
        try:
            rows.append([float(v) for v in fields])
        except ValueError:
            raise ValueError("%s: line %d: a value is not a number: %s"
                             % (path, k, line.strip()[:80]))
    return History(names, np.array(rows, dtype=float).reshape(-1, len(names)))


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
