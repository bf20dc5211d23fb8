"""Running verification decks and reading their results, for the report
scripts tools/verify.py (hydro) and tools/verify_contact.py (contact): deck
text edits, the problems' decks at a given resolution, one run per work
directory (with --reuse), the compare summary of a dump, convergence rates.

run_case starts `mpirun -np NP EXE deck.nml` with OMPI_ALLOW_RUN_AS_ROOT=1,
OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 and OMPI_MCA_rmaps_base_oversubscribe=1; with
opts.reuse a directory whose run.json records exit 0 with the same executable
(path and mtime), rank count and deck text is used as it is.
"""
import argparse
import glob
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

from impact3d_tools import compare, dump
from impact3d_tools import history as impact3d_history

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MPI_ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
           "OMPI_MCA_rmaps_base_oversubscribe": "1"}
GAMMA_RIGHT = 5.0 / 3.0


def read(path):
    with open(path, encoding="utf-8") as handle:
        return handle.read()


def substitute(text, key, value, group=None):
    """Replace the value of `key = ...` (a whole line, or up to the end of a
    one-line group) in the deck text; exactly one occurrence must exist."""
    pattern = re.compile(r"^(\s*" + re.escape(key) + r"\s*=\s*)([^\n/!]*?)(\s*(?:!.*)?)$",
                         re.MULTILINE)
    new, count = pattern.subn(lambda m: m.group(1) + value + m.group(3), text)
    if count != 1:
        raise ValueError(f"deck: expected one line '{key} = ...', found {count}")
    return new


def replace_group(text, group, replacement):
    """Replace every `&group ... /` of the deck by replacement (once, at the first)."""
    pattern = re.compile(r"^&" + group + r"\b.*?^/[ \t]*\n", re.MULTILINE | re.DOTALL)
    matches = list(pattern.finditer(text))
    if not matches:
        raise ValueError(f"deck: no &{group} group")
    out, last = [], 0
    for i, match in enumerate(matches):
        out.append(text[last:match.start()])
        if i == 0:
            out.append(replacement)
        last = match.end()
    out.append(text[last:])
    return "".join(out)


def sod_deck(n):
    text = read(os.path.join(ROOT, "problems", "sod", "sod.nml"))
    h = repr(1.0 / n)
    text = substitute(text, "title", f"'Sod shock tube, {n} zones'")
    text = substitute(text, "nx", str(n))
    text = substitute(text, "y", f"0.0, {h}")
    text = substitute(text, "z", f"0.0, {h}")
    return text


def riemann2_deck(n):
    text = sod_deck(n)
    text = substitute(text, "title", f"'Two-gamma Riemann problem, {n} zones'")
    text = replace_group(text, "material",
                         "&material\n  name = 'gas_left', eos = 'ideal_gas', gamma = 1.4\n/\n"
                         "&material\n  name = 'gas_right', eos = 'ideal_gas', "
                         f"gamma = {GAMMA_RIGHT!r}\n/\n")
    text = replace_group(text, "block",
                         "&block\n  name = 'left', material = 'gas_left', "
                         "box = 0.0, 0.5, -1, 1, -1, 1\n/\n"
                         "&block\n  name = 'right', material = 'gas_right', "
                         "box = 0.5, 1.0, -1, 1, -1, 1\n/\n")
    return text


def sedov_deck(n):
    text = read(os.path.join(ROOT, "problems", "sedov", "sedov.nml"))
    text = substitute(text, "title", f"'Sedov octant {n}^3'")
    for key in ("nx", "ny", "nz"):
        text = substitute(text, key, str(n))
    return text


def noh_deck():
    return read(os.path.join(ROOT, "problems", "noh", "noh.nml"))


def saltzman_deck():
    return read(os.path.join(ROOT, "problems", "saltzman", "saltzman.nml"))


def final_dump(workdir):
    """The dump of the highest cycle (the final one), failed dumps excluded."""
    dumps = sorted(glob.glob(os.path.join(workdir, "*_[0-9][0-9][0-9][0-9][0-9][0-9].h5")))
    return dumps[-1] if dumps else None


def first_dump(workdir):
    dumps = sorted(glob.glob(os.path.join(workdir, "*_[0-9][0-9][0-9][0-9][0-9][0-9].h5")))
    return dumps[0] if dumps else None


def run_case(name, deck, opts):
    """Run one deck in workdir/name; return a dict with rc, wall time, paths."""
    workdir = os.path.join(opts.workdir, name)
    exe = os.path.abspath(opts.exe)
    record_path = os.path.join(workdir, "run.json")
    if opts.reuse and os.path.isfile(record_path):
        with open(record_path, encoding="utf-8") as handle:
            record = json.load(handle)
        if (record.get("rc") == 0 and record.get("exe") == exe
                and record.get("exe_mtime") == os.path.getmtime(exe)
                and record.get("np") == opts.np
                and os.path.isfile(os.path.join(workdir, "deck.nml"))
                and read(os.path.join(workdir, "deck.nml")) == deck
                and final_dump(workdir)):
            record["reused"] = True
            record["dump"] = final_dump(workdir)
            print(f"  {name}: reused ({record['wall']:.1f} s when run)", flush=True)
            return record
    if os.path.isdir(workdir):
        shutil.rmtree(workdir)
    os.makedirs(workdir)
    with open(os.path.join(workdir, "deck.nml"), "w", encoding="utf-8") as handle:
        handle.write(deck)
    # (the deck text is compared as written for --reuse)
    cmd = [opts.mpirun, "-np", str(opts.np), exe, "deck.nml"]
    print(f"  {name}: {' '.join(cmd)} ...", end="", flush=True)
    start = time.monotonic()
    with open(os.path.join(workdir, "run.log"), "w", encoding="utf-8") as log:
        proc = subprocess.run(cmd, cwd=workdir, env=dict(os.environ, **MPI_ENV),
                              stdout=log, stderr=subprocess.STDOUT)
    wall = time.monotonic() - start
    path = final_dump(workdir)
    record = {"name": name, "rc": proc.returncode, "wall": wall, "exe": exe,
              "exe_mtime": os.path.getmtime(exe), "np": opts.np, "cmd": " ".join(cmd),
              "workdir": workdir, "reused": False}
    if path:
        data = dump.load(path)
        record["cycles"] = int(data["attrs"].get("cycle", 0))
        record["nzone"] = int(data["connectivity"].shape[0])
        record["time"] = float(data["attrs"].get("time", math.nan))
    with open(record_path, "w", encoding="utf-8") as handle:
        json.dump(record, handle, indent=1)
    status = "ok" if proc.returncode == 0 else f"FAILED (exit {proc.returncode})"
    print(f" {status}, {wall:.1f} s, {record.get('cycles', '?')} cycles", flush=True)
    if proc.returncode != 0:
        with open(os.path.join(workdir, "run.log"), encoding="utf-8", errors="replace") as log:
            sys.stdout.write("".join(log.readlines()[-15:]))
    record["dump"] = path
    return record


def compare_args(problem, path, extra=()):
    parser = argparse.ArgumentParser()
    compare.add_problem_arguments(parser)
    return parser.parse_args(["--problem", problem, path] + list(extra))


def summarize(problem, path, extra=()):
    return compare.summarize(compare_args(problem, path, extra))


def rate(coarse, fine, ratio=2.0):
    if coarse > 0.0 and fine > 0.0:
        return math.log(coarse / fine) / math.log(ratio)
    return math.nan


def history(workdir):
    """history.txt as a dict of columns (names from its '#' header line)."""
    return impact3d_history.columns(workdir)


def fmt(value, spec=".3e"):
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "n/a"
    return format(value, spec)
