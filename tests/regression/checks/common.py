"""What every check shares: running the program, the PASS/FAIL record, the
run directory's files, and the options several subcommands take.

Every check prints one `PASS name` or `FAIL name: detail` line per criterion
(check()); the entry point (tests/regression/check.py) prints
'N passed, M failed' and exits 1 on any failure or when nothing was checked.
"""
import glob
import os
import shutil
import subprocess
import sys

import numpy as np

from impact3d_tools import compare, history

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")
DUMPS = "*_[0-9][0-9][0-9][0-9][0-9][0-9].h5"
results = []


def check(name, ok, detail=""):
    results.append(ok)
    print(("PASS " if ok else "FAIL ") + name + (": " + detail if detail else ""))
    sys.stdout.flush()


def fresh(workdir, deck):
    """An empty workdir holding the deck as deck.nml."""
    if os.path.isdir(workdir):
        shutil.rmtree(workdir)
    os.makedirs(workdir)
    shutil.copy(deck, os.path.join(workdir, "deck.nml"))


def command(args, np, extra=()):
    return [args.mpiexec, "-np", str(np), args.exe] + list(extra) + ["deck.nml"]


def run(args, np, workdir, deck, extra=()):
    """Run the program on np ranks in a fresh workdir; return (code, stdout, stderr)."""
    fresh(workdir, deck)
    proc = subprocess.run(command(args, np, extra), cwd=workdir, env=ENV, capture_output=True,
                          text=True)
    return proc.returncode, proc.stdout, proc.stderr


def run_in(args, subdir, name="run exits 0"):
    """Run --deck on --np ranks in --workdir/subdir; check that it exits 0
    (criterion `name`); return (the run directory, or None when the run
    failed, and its stdout)."""
    workdir = os.path.join(args.workdir, subdir)
    code, out, err = run(args, args.np, workdir, args.deck)
    check(name, code == 0, err[-2000:])
    return (workdir if code == 0 else None), out


def run_pair(args, reference_dir, run_dir, reference_name="reference", run_name="run"):
    """Run --reference and --deck on --np ranks; True when both exit 0."""
    code, out, err = run(args, args.np, reference_dir, args.reference)
    check(reference_name + " run exits 0", code == 0, err[-2000:])
    code2, out, err = run(args, args.np, run_dir, args.deck)
    check(run_name + " run exits 0", code2 == 0, err[-2000:])
    return not code and not code2, out


def read_history(workdir):
    """history.txt of a run: (column names, rows as a float array). The row of
    cycle 0 (the initial state, no step taken) is left out: the checks here
    are on the steps."""
    h = history.read(workdir).steps()
    return h.names, h.rows


def dumps(workdir):
    """The numbered dumps of a run, in cycle order."""
    return sorted(glob.glob(os.path.join(workdir, DUMPS)))


def final_dump(workdir):
    found = dumps(workdir)
    return found[-1] if found else None


def dump_names(workdir):
    return sorted(os.path.basename(p) for p in glob.glob(os.path.join(workdir, "*.h5")))


def h5same(a, b):
    proc = subprocess.run(["h5diff", "--exclude-path", "/run", a, b], capture_output=True,
                          text=True)
    return proc.returncode == 0, proc.stdout[-2000:]


def variant_deck(args):
    """The deck with each --replace OLD NEW applied (each OLD must occur), written
    to the work directory; returns its path."""
    text = open(args.deck).read()
    for old, new in args.replace or []:
        if old not in text:
            raise SystemExit("check.py: --replace: %r not in %s" % (old, args.deck))
        text = text.replace(old, new)
    os.makedirs(args.workdir, exist_ok=True)
    path = os.path.join(args.workdir, "variant.nml")
    with open(path, "w") as f:
        f.write(text)
    return path


def compare_values(dump_path, problem, extra):
    """The summary of impact3d_tools.compare for a dump, as the `key = value`
    lines it prints read back (floats in %.6e): (exit code, values, error text)."""
    return compare.summary_values(["--problem", problem, dump_path] + list(extra))


def check_bounds(values, args, what="", reference=None):
    """--max KEY=VALUE: values[KEY] <= VALUE; --min KEY=VALUE: values[KEY] >= VALUE."""
    for specs, sign, holds in ((getattr(args, "max", None), "<=", lambda a, b: a <= b),
                               (getattr(args, "min", None), ">=", lambda a, b: a >= b)):
        for spec in specs or []:
            k, v = spec.split("=")
            got = values.get(k, float("nan"))
            note = "" if reference is None else " (reference %.4e)" % reference.get(
                k, float("nan"))
            check("%s%s = %.4e %s %s%s" % (what, k, got, sign, v, note), holds(got, float(v)))


def report_contact_energy(workdir):
    """Print the energy the contact forces did (relative to the initial total)
    and the largest energy_error of the balance that books it."""
    header, rows = read_history(workdir)
    e0 = rows[0, header.index("total_energy")]
    if "contact_work" in header:
        print("contact work %.3e of the initial total energy"
              % (rows[-1, header.index("contact_work")] / e0))
    print("largest |energy_error| / E0 %.2e"
          % (np.abs(rows[:, header.index("energy_error")]).max() / abs(e0)))


# Options several subcommands share (each subcommand adds only those it reads).

def add_replace(p, what="before running"):
    p.add_argument("--replace", nargs=2, action="append", metavar=("OLD", "NEW"),
                   help="edit the deck text " + what)


def add_reference(p, help_text="reference deck", required=True):
    p.add_argument("--reference", required=required, help=help_text)


def add_bounds(p):
    p.add_argument("--max", action="append", metavar="KEY=VALUE",
                   help="the summary's KEY is at most VALUE")
    p.add_argument("--min", action="append", metavar="KEY=VALUE",
                   help="the summary's KEY is at least VALUE")


def add_problem(p):
    p.add_argument("--problem", required=True, help="compare's problem (sod, riemann2, sedov, noh)")
    p.add_argument("--compare-args", default="", help="extra arguments for compare")


def add_restart(p, from_cycle=True):
    p.add_argument("--restart-np", type=int, default=1)
    if from_cycle:
        p.add_argument("--from-cycle", type=int, default=0)
        p.add_argument("--from-time", type=float, default=None,
                       help="restart from the uninterrupted run's dump at this time "
                            "(its dump.dumps index) instead of --from-cycle")
