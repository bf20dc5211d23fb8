#!/usr/bin/python3
"""Regression checks of impact3d runs, each on an exact or physical criterion.

Subcommands (all take --exe PATH and --mpiexec PATH and run in --workdir):
  bitwise  --deck D --ranks 1 2 3 4   dumps of every rank count identical (h5diff, no
                                      tolerance, /run excluded: it holds run metadata)
  restart  --deck D --np A --restart-np B --from-cycle C
                                      a run restarted from its cycle-C dump on B ranks
                                      ends bitwise identical to the uninterrupted run
  energy   --deck D --np N --tol T    max |relative total-energy error| in history.txt <= T
  failure  --deck D --np N --expect volume|nan|dt|any
                                      exit code 2, the message names zone/node, position,
                                      cycle and time, and a final *_failed.h5 dump exists
  compare  --deck D --np N --problem P --max KEY=VALUE ... --min KEY=VALUE ...
                                      run, compare the final dump with the exact solution
                                      (tools/compare.py) and check the summary values
  convergence --deck TEMPLATE --sizes 100 200 400 --problem P --key L1_rho
              --min-rate R [--max-at SIZE=VALUE]
                                      run the template ({n} = zones, {h} = 1/n) at each
                                      size; observed rates log2(e(n)/e(2n))/log2(2) >= R
  window   --deck D --np N --axis x --range A B --target 4 --tol 0.05
                                      zone densities with centroid in [A, B] all within
                                      tol (relative) of target
  wavefront --deck D --target C --target-velocity UP --origin X0 --tol T
                                      a planar front (|u| = UP/2) moves at C within T
  rebound  --deck D --target 2L/c --tol T
                                      bar on a rigid wall: momentum reversed within T,
                                      contact (momentum changing) lasts 2L/c within T
  stability --deck D --np N       runs to the end (exit 0) or stops through the failure
                                      path (exit 2 with its message and final dump); no
                                      dump holds a NaN or infinity
  interface --deck D --np N --zones-tol 2 [compare args]
                                      two-block Riemann problem: the material interface
                                      and the shock within 2 local zone widths of exact
  restartdeck --deck D --np A --restart-np B --from-cycle C
                                      /run of the cycle-C dump holds the deck text (byte
                                      for byte), version, command line and rank count; a
                                      restart with &material gamma changed is refused
                                      (exit 1, naming &material and gamma) unless
                                      --restart-force; one with only comments, blanks and
                                      &output changed ends bitwise identical
  twowave, shell_stop, stopfile, bars, mirror, patch: see their docstrings
  mirror   --deck D --reference WALL --axis z --tol T [--sym-tol S --all-dumps
           --energy-tol E --momentum-tol M --momentum-axes z --pair NAME]
  signal   --deck D --np A --restart-np B --signal USR1|USR2|TERM --to mpirun|rank
           [--replace OLD NEW ...]    a signal once the run has printed a cycle line:
                                      exit 3, restart dump, restart ends bitwise identical
  walllimit --deck D --np A --restart-np B [--replace OLD NEW ...]
                                      &control wall_limit set to stop well before the end:
                                      the same checks, and the run stops before the limit
  relative --deck D --reference R --problem P --key K --tol T [--max KEY=V] [--min KEY=V]
           [--pair NAME] [--energy-tol E] [--booked-pair NAME --momentum-tol M]
           [--radial-penetration INNER OUTER RADIUS MAX]
                                      contact run's K within (1 + T) of the reference's;
                                      optionally the energy balance, the momentum the
                                      pair books and the penetration across a curved
                                      interface
  impact   --deck D --pair NAME --tol T --max-pen P [--momentum-tol M --momentum-axes z]
                                      two bodies in contact: energy balance, penetration,
                                      momentum; final block velocities reported
  shape    --deck D --reference R --tol T
                                      Taylor rod: final length and foot diameter of D
                                      within T (relative) of R's
  slide    --deck D --v0 V --friction MU --pressure P --area A --tol T [--pair NAME]
                                      Coulomb friction: a block pressed on a plane by P
                                      over its contact area A slides from V: deceleration
                                      MU P A / m, stopping time and distance within T of
                                      the analytic values; friction work = the block's
                                      kinetic energy; energy balance to round-off
  same     --deck D --reference R --np N
                                      D and R write the same dumps, every one bitwise
                                      identical (h5diff, /run excluded): e.g. a material
                                      given by deck keys against its library set
Prints 'N passed, M failed' and exits 1 on failure. Needs tools/ on
PYTHONPATH (the impact3d_tools package; CTest sets it).
"""
import argparse
import glob
import os
import re
import shutil
import subprocess
import sys

from impact3d_tools import dump, history
from impact3d_tools.shapes import inner_radius_history, rod_shape

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")
results = []


def check(name, ok, detail=""):
    results.append(ok)
    print(("PASS " if ok else "FAIL ") + name + (": " + detail if detail else ""))
    sys.stdout.flush()


def run(args, np, workdir, deck, extra=()):
    """Run the program on np ranks in a fresh workdir; return (code, stdout, stderr)."""
    if os.path.isdir(workdir):
        shutil.rmtree(workdir)
    os.makedirs(workdir)
    shutil.copy(deck, os.path.join(workdir, "deck.nml"))
    cmd = [args.mpiexec, "-np", str(np), args.exe] + list(extra) + ["deck.nml"]
    proc = subprocess.run(cmd, cwd=workdir, env=ENV, capture_output=True, text=True)
    return proc.returncode, proc.stdout, proc.stderr


def read_history(workdir):
    """history.txt of a run: (column names, rows as a float array). The row of
    cycle 0 (the initial state, no step taken) is left out: the checks here
    are on the steps."""
    h = history.read(workdir).steps()
    return h.names, h.rows


def final_dump(workdir):
    dumps = sorted(glob.glob(os.path.join(workdir, "*_[0-9][0-9][0-9][0-9][0-9][0-9].h5")))
    return dumps[-1] if dumps else None


def h5same(a, b):
    proc = subprocess.run(["h5diff", "--exclude-path", "/run", a, b], capture_output=True,
                          text=True)
    return proc.returncode == 0, proc.stdout[-2000:]


def cmd_bitwise(args):
    ref = None
    deck = variant_deck(args) if args.replace else args.deck
    for np in args.ranks:
        wd = os.path.join(args.workdir, "np%d" % np)
        code, out, err = run(args, np, wd, deck)
        check("run on %d rank(s) exits 0" % np, code == 0, err[-2000:])
        if code != 0:
            return
        dumps = sorted(os.path.basename(p) for p in glob.glob(os.path.join(wd, "*.h5")))
        if ref is None:
            ref = (wd, dumps)
            check("dumps written", len(dumps) >= 2, " ".join(dumps))
            continue
        check("%d ranks wrote the same dumps as %d" % (np, args.ranks[0]), dumps == ref[1])
        for name in ref[1]:
            same, diff = h5same(os.path.join(ref[0], name), os.path.join(wd, name))
            check("%s bitwise identical on %d and %d ranks" % (name, args.ranks[0], np), same,
                  diff)


def cmd_restart(args):
    wd = os.path.join(args.workdir, "full")
    deck = variant_deck(args) if args.replace else args.deck
    code, out, err = run(args, args.np, wd, deck)
    check("uninterrupted run exits 0", code == 0, err[-2000:])
    full = final_dump(wd)
    start = os.path.join(wd, "dump_%06d.h5" % args.from_cycle)
    check("mid-run dump exists", os.path.exists(start), start)
    if code != 0 or not os.path.exists(start):
        return
    wr = os.path.join(args.workdir, "restarted")
    code, out, err = run(args, args.restart_np, wr, deck,
                         extra=["--restart", os.path.abspath(start)])
    check("restarted run on %d rank(s) exits 0" % args.restart_np, code == 0, err[-2000:])
    if code != 0:
        return
    mine = os.path.join(wr, os.path.basename(full))
    check("restarted run ends at the same cycle", os.path.exists(mine), mine)
    if os.path.exists(mine):
        same, diff = h5same(full, mine)
        check("final dump bitwise identical after restart", same, diff)


def cmd_restartdeck(args):
    import h5py
    wd = os.path.join(args.workdir, "full")
    code, out, err = run(args, args.np, wd, args.deck)
    check("uninterrupted run exits 0", code == 0, err[-2000:])
    full = final_dump(wd)
    start = os.path.join(wd, "dump_%06d.h5" % args.from_cycle)
    check("mid-run dump exists", os.path.exists(start), start)
    if code != 0 or not os.path.exists(start):
        return
    with open(args.deck) as f:
        text = f.read()
    with h5py.File(start, "r") as f:
        attrs = dict(f["run"].attrs)
    stored = attrs.get("deck", b"")
    stored = stored.decode() if isinstance(stored, bytes) else str(stored)
    check("/run deck equals the deck file's text", stored == text,
          "%d vs %d characters" % (len(stored), len(text)))
    version = attrs.get("version", b"")
    version = version.decode() if isinstance(version, bytes) else str(version)
    check("/run version is set", len(version) > 0, version)
    command = attrs.get("command", b"")
    command = command.decode() if isinstance(command, bytes) else str(command)
    check("/run command names the program and the deck",
          "impact3d" in command and "deck.nml" in command, command)
    check("/run ranks is the rank count", int(attrs.get("ranks", -1)) == args.np,
          str(attrs.get("ranks")))
    if "gamma = " not in text:
        check("deck has a gamma to change", False)
        return
    value = text.split("gamma = ")[1].split()[0].rstrip(",/")
    changed = os.path.join(args.workdir, "changed_gamma.nml")
    with open(changed, "w") as f:
        f.write(text.replace("gamma = " + value, "gamma = 1.6667", 1))
    wr = os.path.join(args.workdir, "refused")
    code, out, err = run(args, args.restart_np, wr, changed,
                         extra=["--restart", os.path.abspath(start)])
    check("restart with gamma changed exits 1", code == 1, err[-2000:])
    check("the refusal names &material and gamma",
          re.search(r"&material(\(\d+\))?: gamma: changed", err) is not None, err[-2000:])
    check("nothing written by the refused restart", not glob.glob(os.path.join(wr, "*.h5")))
    wr = os.path.join(args.workdir, "forced")
    code, out, err = run(args, args.restart_np, wr, changed,
                         extra=["--restart", os.path.abspath(start), "--restart-force"])
    check("restart with gamma changed and --restart-force exits 0", code == 0, err[-2000:])
    check("--restart-force warns about gamma", "gamma" in err and "warning" in err,
          err[-2000:])
    # Comments, blanks and the output controls may change: the restart is the same run.
    cosmetic = os.path.join(args.workdir, "cosmetic.nml")
    lines = ["! restarted with a reformatted deck"]
    for line in text.splitlines():
        lines.append("   " + line.replace(" = ", "=").replace(", ", " ,  ")
                     + ("  ! comment" if line.startswith("&") and line.rstrip().endswith("/")
                        and "'" not in line.split("/")[-1] else ""))
    with open(cosmetic, "w") as f:
        f.write("\n".join(lines) + "\n")
    wr = os.path.join(args.workdir, "cosmetic")
    code, out, err = run(args, args.restart_np, wr, cosmetic,
                         extra=["--restart", os.path.abspath(start)])
    check("restart with only comments and blanks changed exits 0", code == 0, err[-2000:])
    check("and warns about nothing", "warning" not in err, err[-2000:])
    mine = os.path.join(wr, os.path.basename(full))
    if code == 0:
        same, diff = h5same(full, mine) if os.path.exists(mine) else (False, mine)
        check("final dump bitwise identical after the reformatted restart", same, diff)


def cmd_energy(args):
    wd = os.path.join(args.workdir, "energy")
    code, out, err = run(args, args.np, wd, args.deck)
    check("run exits 0", code == 0, err[-2000:])
    if code != 0:
        return
    h = history.read(wd)
    rows = h.rows
    worst = max(abs(h["energy_error"]))
    check("history has the run's cycles", len(rows) > 10, "%d rows" % len(rows))
    check("max |relative energy error| %.3e <= %.1e" % (worst, args.tol), worst <= args.tol)


def cmd_failure(args):
    wd = os.path.join(args.workdir, "failure")
    code, out, err = run(args, args.np, wd, args.deck)
    check("exit code is 2", code == 2, "got %d; stderr: %s" % (code, err[-2000:]))
    what = {"volume": r"zero or negative volume in zone",
            "nan": r"NaN (?:energy in zone|velocity at node)",
            "dt": r"time step below dt_min, set by zone",
            "any": r"(?:zero or negative volume in zone|NaN (?:energy in zone|velocity at node)"
                   r"|time step below dt_min, set by zone)"}[args.expect]
    pattern = what + r" (\d+) at \(\s*(\S+)\s+(\S+)\s+(\S+)\) in cycle (\d+), time\s+(\S+)"
    m = re.search(pattern, err)
    check("message names the zone, its position, the cycle and the time", m is not None,
          err[-2000:])
    if m:
        pos = [float(m.group(i)) for i in (2, 3, 4)]
        check("reported position is finite", all(abs(p) < 1e300 for p in pos), str(pos))
    failed = glob.glob(os.path.join(wd, "*_failed.h5"))
    check("a final dump was written", len(failed) == 1, str(failed))
    if failed and m:
        d = dump.load(failed[0])
        check("final dump is at the failing cycle", int(d["attrs"]["cycle"]) == int(m.group(5)))


def cmd_compare(args):
    wd = os.path.join(args.workdir, "compare")
    code, out, err = run(args, args.np, wd, args.deck)
    check("run exits 0", code == 0, err[-2000:])
    if code != 0:
        return
    rc, values, err = compare_values(final_dump(wd), args.problem,
                                     args.compare_args + ["--out", os.path.join(wd, "summary.txt")])
    check("compare.py runs", rc == 0, err[-2000:])
    for spec in args.max or []:
        k, v = spec.split("=")
        got = values.get(k, float("nan"))
        check("%s = %.4e <= %s" % (k, got, v), got <= float(v))
    for spec in args.min or []:
        k, v = spec.split("=")
        got = values.get(k, float("nan"))
        check("%s = %.4e >= %s" % (k, got, v), got >= float(v))


def compare_values(dump_path, problem, extra):
    cmd = ["/usr/bin/python3", "-m", "impact3d_tools.compare", "--problem", problem,
           dump_path] + list(extra)
    proc = subprocess.run(cmd, capture_output=True, text=True)
    values = {}
    for line in proc.stdout.splitlines():
        if "=" in line:
            k, v = line.split("=", 1)
            try:
                values[k.strip()] = float(v)
            except ValueError:
                pass
    return proc.returncode, values, proc.stderr


def cmd_convergence(args):
    import math
    template = open(args.deck).read()
    errors = []
    for n in args.sizes:
        wd = os.path.join(args.workdir, "n%d" % n)
        deck = os.path.join(args.workdir, "deck_%d.nml" % n)
        os.makedirs(args.workdir, exist_ok=True)
        with open(deck, "w") as f:
            f.write(template.replace("{n}", str(n)).replace("{h}", repr(1.0 / n)))
        code, out, err = run(args, args.np, wd, deck)
        check("run at %d exits 0" % n, code == 0, err[-2000:])
        if code != 0:
            return
        rc, values, err = compare_values(final_dump(wd), args.problem, args.compare_args)
        e = values.get(args.key, float("nan"))
        errors.append(e)
        print("  n = %d: %s = %.5e" % (n, args.key, e))
        for spec in args.max_at or []:
            size, bound = spec.split("=")
            if int(size) == n:
                check("%s at %d = %.4e <= %s" % (args.key, n, e, bound), e <= float(bound))
    for i in range(len(errors) - 1):
        ratio = args.sizes[i + 1] / args.sizes[i]
        rate = math.log(errors[i] / errors[i + 1]) / math.log(ratio)
        check("observed rate %d -> %d = %.3f >= %.2f" % (args.sizes[i], args.sizes[i + 1], rate,
                                                        args.min_rate), rate >= args.min_rate)


def cmd_window(args):
    import numpy as np
    wd = os.path.join(args.workdir, "window")
    code, out, err = run(args, args.np, wd, args.deck)
    check("run exits 0 (no tangling)", code == 0, err[-2000:])
    if code != 0:
        return
    d = dump.load(final_dump(wd))
    axis = "xyz".index(args.axis)
    c = dump.zone_centroids(d)[:, axis]
    sel = (c > args.range[0]) & (c < args.range[1])
    rho = d["density"][sel]
    dev = np.abs(rho / args.target - 1.0).max()
    check("%d zones in the window" % sel.sum(), sel.sum() > 0)
    check("density in [%.4g, %.4g], mean %.4f: largest deviation %.2f%% <= %.1f%%"
          % (rho.min(), rho.max(), rho.mean(), 100 * dev, 100 * args.tol), dev <= args.tol)


def cmd_interface(args):
    import numpy as np
    wd = os.path.join(args.workdir, "interface")
    code, out, err = run(args, args.np, wd, args.deck)
    check("run exits 0", code == 0, err[-2000:])
    if code != 0:
        return
    path = final_dump(wd)
    rc, values, err = compare_values(path, args.problem, args.compare_args)
    check("compare.py runs", rc == 0, err[-2000:])
    d = dump.load(path)
    x = d["coordinates"][:, 0]
    conn = d["connectivity"]
    block = d["block"]
    left = set(conn[block == 1].ravel())
    right = set(conn[block == 2].ravel())
    shared = np.array(sorted(left & right))
    x_interface = x[shared].mean()
    # local zone widths: the zones touching the interface, and those at the shock
    width = np.array([x[row].max() - x[row].min() for row in conn])
    centre = dump.zone_centroids(d)[:, 0]
    near = np.argsort(np.abs(centre - x_interface))[:2]
    dx_contact = width[near].mean()
    err_contact = abs(x_interface - values["contact_x_exact"])
    check("interface at %.5f, exact %.5f: error %.2f local zones <= %g"
          % (x_interface, values["contact_x_exact"], err_contact / dx_contact, args.zones_tol),
          err_contact <= args.zones_tol * dx_contact)
    behind = np.argsort(np.abs(centre - (values["shock_x_exact"] - 0.02)))[:2]
    dx_shock = width[behind].mean()
    check("shock at %.5f, exact %.5f: error %.2f local zones <= %g"
          % (values["shock_x"], values["shock_x_exact"], values["shock_x_error"] / dx_shock,
             args.zones_tol), values["shock_x_error"] <= args.zones_tol * dx_shock)
    for spec in args.max or []:
        k, v = spec.split("=")
        got = values.get(k, float("nan"))
        check("%s = %.4e <= %s" % (k, got, v), got <= float(v))


def cmd_stability(args):
    import numpy as np
    import h5py
    wd = os.path.join(args.workdir, "stability")
    code, out, err = run(args, args.np, wd, args.deck)
    check("exit code 0 (done) or 2 (clean failure), got %d" % code, code in (0, 2), err[-2000:])
    if code == 2:
        check("failure message and final dump", "writing a final dump" in err
              and len(glob.glob(os.path.join(wd, "*_failed.h5"))) == 1, err[-2000:])
    dumps = sorted(glob.glob(os.path.join(wd, "*.h5")))
    bad = []
    for path in dumps:
        with h5py.File(path, "r") as f:
            def visit(name, obj):
                if isinstance(obj, h5py.Dataset) and obj.dtype.kind == "f":
                    if not np.all(np.isfinite(obj[()])):
                        bad.append(os.path.basename(path) + ":" + name)
            f.visititems(visit)
    check("%d dumps, every value finite" % len(dumps), len(dumps) >= 2 and not bad, str(bad))


def cmd_wavefront(args):
    """Speed of a planar front: where the x velocity crosses half the piston speed."""
    import numpy as np
    wd = os.path.join(args.workdir, "wavefront")
    code, out, err = run(args, args.np, wd, args.deck)
    check("run exits 0", code == 0, err[-2000:])
    if code != 0:
        return
    d = dump.load(final_dump(wd))
    x = d["coordinates"][:, 0]
    v = d["node_velocity"][:, 0]
    t = float(d["attrs"]["time"])
    order = np.argsort(x)
    x, v = x[order], v[order]
    half = 0.5 * args.target_velocity
    k = np.where(np.abs(v) > abs(half))[0].max()
    front = x[k] + (x[k + 1] - x[k]) * (abs(v[k]) - abs(half)) / (abs(v[k]) - abs(v[k + 1]))
    speed = (front - args.origin) / t
    check("front speed %.5f vs expected %.5f: error %.3f%% <= %.2f%%"
          % (speed, args.target, 100 * abs(speed / args.target - 1), 100 * args.tol),
          abs(speed / args.target - 1) <= args.tol)


def cmd_rebound(args):
    """A bar hitting a rigid wall: contact time 2L/c and rebound at its speed."""
    import numpy as np
    wd = os.path.join(args.workdir, "rebound")
    code, out, err = run(args, args.np, wd, args.deck)
    check("run exits 0", code == 0, err[-2000:])
    if code != 0:
        return
    header, rows = read_history(wd)
    t = rows[:, header.index("time")]
    p = rows[:, header.index("momentum_x")]
    p0 = p[0]
    final = p[-1]
    check("rebound velocity ratio %.4f vs -1 within %.1f%%" % (final / p0, 100 * args.tol),
          abs(final / p0 + 1.0) <= args.tol)
    # contact ends when the momentum reaches its final value (no force after release)
    moving = np.where(np.abs(p - final) > 1e-3 * abs(p0))[0]
    t_end = t[moving.max() + 1] if moving.size else t[0]
    check("contact duration %.5f vs 2L/c = %.5f within %.1f%%"
          % (t_end, args.target, 100 * args.tol), abs(t_end / args.target - 1) <= args.tol)


def cmd_bars(args):
    """Two elastic bars meeting through a contact pair (docs/problems.md, section C).

    Left bar (block 1) at --v-left, right bar (block 2) at --v-right, 1D strain.
    Criteria (each within --tol): contact lasts --duration (from the pair's
    active column of the history); the interface stress (pair force / --area)
    over the middle half of the contact equals --stress; the interface nodes
    move at the impedance-matched velocity --v-interface during contact
    (within --tol of |v_left - v_right|: the velocity never reverses); after
    separation each bar's mean velocity is --final-left / --final-right."""
    import numpy as np
    wd = os.path.join(args.workdir, "bars")
    code, out, err = run(args, args.np, wd, args.deck)
    check("run exits 0", code == 0, err[-2000:])
    if code != 0:
        return
    header, rows = read_history(wd)
    t = rows[:, header.index("time")]
    dt = rows[:, header.index("dt")]
    active = rows[:, header.index(args.pair + "_active")] > 0
    force = rows[:, header.index(args.pair + "_force")]
    pen = rows[:, header.index(args.pair + "_pen_max")]
    on = np.where(active)[0]
    check("contact found", on.size > 0)
    if not on.size:
        return
    t_start = t[on[0]] - dt[on[0]]
    t_stop = t[on[-1]]
    duration = t_stop - t_start
    gaps = np.where(np.diff(on) > 1)[0]
    check("contact never opens while the bars are in contact (%d interruptions)" % gaps.size,
          gaps.size == 0)
    if args.duration > 0:
        check("contact duration %.5f vs %.5f within %.1f%%" % (duration, args.duration,
              100 * args.tol), abs(duration / args.duration - 1) <= args.tol)
    mid = (t > t_start + 0.25 * duration) & (t < t_start + 0.75 * duration)
    stress = force[mid] / args.area
    check("interface stress %.6e (range %.4e..%.4e) vs %.6e within %.1f%%"
          % (stress.mean(), stress.min(), stress.max(), args.stress, 100 * args.tol),
          abs(stress.mean() / args.stress - 1) <= args.tol)
    print("largest penetration %.3e (bar length units)" % pen.max())
    # Interface velocity from the dumps taken during contact.
    dumps = sorted(glob.glob(os.path.join(wd, "*_[0-9][0-9][0-9][0-9][0-9][0-9].h5")))
    dv = abs(args.v_left - args.v_right)
    worst = 0.0
    used = 0
    final = None
    for path in dumps:
        d = dump.load(path)
        time = float(d["attrs"]["time"])
        conn = d["connectivity"]
        left_nodes = np.unique(conn[d["block"] == 1].ravel())
        right_nodes = np.unique(conn[d["block"] == 2].ravel())
        final = (d, left_nodes, right_nodes)
        if not (t_start + 0.1 * duration < time < t_start + 0.9 * duration):
            continue
        x = d["coordinates"][:, 0]
        vx = d["node_velocity"][:, 0]
        face_l = left_nodes[np.isclose(x[left_nodes], x[left_nodes].max(), atol=1e-6)]
        face_r = right_nodes[np.isclose(x[right_nodes], x[right_nodes].min(), atol=1e-6)]
        for face in (face_l, face_r):
            worst = max(worst, np.abs(vx[face] - args.v_interface).max())
        used += 1
    check("interface velocity within %.1f%% of |v_left - v_right| of %.4e over %d dumps "
          "(worst %.3e)" % (100 * args.tol, args.v_interface, used, worst),
          used >= 3 and worst <= args.tol * dv)
    if final is not None and args.final_left is not None:
        d, ln, rn = final
        m = d["node_mass"]
        vx = d["node_velocity"][:, 0]
        # interface nodes belong to one bar each (parts share no node)
        vl = (m[ln] * vx[ln]).sum() / m[ln].sum()
        vr = (m[rn] * vx[rn]).sum() / m[rn].sum()
        check("left bar leaves at %.5e vs %.5e within %.1f%% of |v|" % (vl, args.final_left,
              100 * args.tol), abs(vl - args.final_left) <= args.tol * dv / 2)
        check("right bar leaves at %.5e vs %.5e within %.1f%% of |v|" % (vr, args.final_right,
              100 * args.tol), abs(vr - args.final_right) <= args.tol * dv / 2)
    if args.momentum_tol > 0 and dumps:
        d0 = dump.load(dumps[0])
        scale = (d0["node_mass"] * np.abs(d0["node_velocity"][:, 0])).sum()
        p = rows[:, header.index("momentum_x")]
        drift = np.abs(p - p[0]).max() / scale
        check("total momentum conserved: largest drift %.3e of sum m|v| (tolerance %.1e)"
              % (drift, args.momentum_tol), drift <= args.momentum_tol)


def cmd_mirror(args):
    """Mirror test (docs/problems.md, section C): --deck (a body and its mirror image joined
    by contact, the body's part first) against --reference (the body on the
    rigid unilateral wall): the body's node positions at the end agree to
    --tol of its size, and the image stays the mirror of the body (to
    --sym-tol, default --tol). Options: --all-dumps compares every dump the
    two runs share (same cycles) instead of the final one only; --energy-tol
    checks both runs' energy balance; --momentum-tol checks the contact run's
    total momentum along --momentum-axes (zero by symmetry) against the body's
    initial momentum there."""
    import numpy as np
    wd_ref = os.path.join(args.workdir, "wall")
    wd = os.path.join(args.workdir, "mirror")
    code, out, err = run(args, args.np, wd_ref, args.reference)
    check("wall run exits 0", code == 0, err[-2000:])
    code2, out, err = run(args, args.np, wd, args.deck)
    check("mirror run exits 0", code2 == 0, err[-2000:])
    if code or code2:
        return
    sym_tol = args.tol if args.sym_tol is None else args.sym_tol
    pattern = "*_[0-9][0-9][0-9][0-9][0-9][0-9].h5"
    if args.all_dumps:
        names = sorted(set(os.path.basename(f) for f in glob.glob(os.path.join(wd_ref, pattern)))
                       & set(os.path.basename(f) for f in glob.glob(os.path.join(wd, pattern))))
        pairs = [(os.path.join(wd_ref, f), os.path.join(wd, f)) for f in names]
    else:
        pairs = [(final_dump(wd_ref), final_dump(wd))]
    worst, worst_sym, at = 0.0, 0.0, 0.0
    for path_ref, path in pairs:
        ref = dump.load(path_ref)
        mir = dump.load(path)
        check("both runs reach t = %g" % float(mir["attrs"]["time"]),
              float(ref["attrs"]["time"]) == float(mir["attrs"]["time"]))
        x0 = ref["coordinates"]
        n = x0.shape[0]
        size = np.linalg.norm(x0.max(axis=0) - x0.min(axis=0))
        diff = np.abs(mir["coordinates"][:n] - x0).max() / size
        if diff >= worst:
            worst, at = diff, float(ref["attrs"]["time"])
        image = mir["coordinates"][n:].copy()
        axis = "xyz".index(args.axis)
        image[:, axis] *= -1.0
        body = mir["coordinates"][:n]
        # the image's nodes, mirrored, are the body's nodes (nearest-point match)
        if image.shape == body.shape:
            sym = 0.0
            for start in range(0, image.shape[0], 256):
                chunk = image[start:start + 256]
                dist = np.linalg.norm(chunk[:, None, :] - body[None, :, :], axis=2)
                sym = max(sym, dist.min(axis=1).max())
            worst_sym = max(worst_sym, sym / size)
    check("body node positions: largest difference %.3e of the body size%s (tolerance %.1e)"
          % (worst, " (at t = %g, %d dumps)" % (at, len(pairs)) if args.all_dumps else "",
             args.tol), worst <= args.tol)
    if image.shape == body.shape:
        check("the image stays the mirror of the body: %.3e of the size" % worst_sym,
              worst_sym <= sym_tol)
    moved = np.abs(x0 - dump.load(sorted(glob.glob(os.path.join(
        wd_ref, pattern)))[0])["coordinates"]).max() / size
    print("largest node displacement of the body: %.3e of its size" % moved)
    if args.energy_tol > 0.0:
        for name, w in (("wall", wd_ref), ("mirror", wd)):
            header, rows = read_history(w)
            e = np.abs(rows[:, header.index("energy_error")]).max()
            check("%s run energy balance |error| %.2e <= %.1e" % (name, e, args.energy_tol),
                  e <= args.energy_tol)
    if args.momentum_tol > 0.0:
        header, rows = read_history(wd)
        hr, rr = read_history(wd_ref)
        cols = ["momentum_" + c for c in args.momentum_axes]
        body = np.linalg.norm(rr[0, [hr.index(c) for c in cols]])
        p = rows[:, [header.index(c) for c in cols]]
        drift = np.linalg.norm(p - p[0], axis=1).max() / max(body, 1e-300)
        check("mirror run momentum (%s) drift %.2e of the body's initial momentum <= %.1e"
              % (args.momentum_axes, drift, args.momentum_tol), drift <= args.momentum_tol)
    if args.pair:
        header, rows = read_history(wd)
        if args.pair + "_active" in header:
            t = rows[:, header.index("time")]
            active = rows[:, header.index(args.pair + "_active")] > 0
            if active.any():
                print("contact from t = %.3f to t = %.3f; largest penetration %.3e"
                      % (t[active][0], t[active][-1],
                         rows[:, header.index(args.pair + "_pen_max")].max()))


def cmd_patch(args):
    """Patch test (docs/problems.md, section C): after a planar wave crossed a contact
    interface between non-matching meshes, the normal stress sigma_xx of the
    zones with centroid x in --range (behind the front) is uniform across the
    section, (max - min)/|mean| <= --tol, and its mean equals --target within
    --tol (the applied pressure, transmitted through matched impedances)."""
    import numpy as np
    wd = os.path.join(args.workdir, "patch")
    code, out, err = run(args, args.np, wd, args.deck)
    check("run exits 0", code == 0, err[-2000:])
    if code != 0:
        return
    d = dump.load(final_dump(wd))
    c = dump.zone_centroids(d)
    sxx = -d["pressure"] + d["deviatoric_stress"][:, 0]
    sel = (c[:, 0] > args.range[0]) & (c[:, 0] < args.range[1])
    check("zones in the window", sel.sum() > 0)
    if not sel.any():
        return
    worst = 0.0
    for x0 in np.unique(np.round(c[sel, 0], 9)):
        layer = sel & (np.abs(c[:, 0] - x0) < 1e-9 * (1 + abs(x0)))
        s = sxx[layer]
        worst = max(worst, (s.max() - s.min()) / abs(s.mean()))
    check("transverse variation of sigma_xx behind the interface %.3e (tolerance %.1e)"
          % (worst, args.tol), worst <= args.tol)
    mean = sxx[sel].mean()
    check("transmitted sigma_xx %.6e vs %.6e within %.1f%%" % (mean, args.target,
          100 * args.tol), abs(mean / args.target - 1) <= args.tol)


def cmd_relative(args):
    """A contact run against its single-mesh reference (docs/problems.md, section D): the
    --key of compare.py (--problem) for --deck is at most (1 + --tol) times
    the reference's (--reference); --max / --min bound other keys of the
    contact run; with --pair, the interface is in contact on every cycle and
    never releases; with --energy-tol, max |energy_error| (the balance that
    books the contact work) is at most that; with --booked-pair and
    --momentum-tol, the momentum that pair's forces added over the run (sum of
    its dmom columns) is at most that fraction of the largest |momentum|."""
    import numpy as np
    wd_ref = os.path.join(args.workdir, "reference")
    wd = os.path.join(args.workdir, "contact")
    code, out, err = run(args, args.np, wd_ref, args.reference)
    check("reference run exits 0", code == 0, err[-2000:])
    code2, out, err = run(args, args.np, wd, args.deck)
    check("contact run exits 0", code2 == 0, err[-2000:])
    if code or code2:
        return
    rc, ref, err = compare_values(final_dump(wd_ref), args.problem, args.compare_args)
    rc2, got, err2 = compare_values(final_dump(wd), args.problem, args.compare_args)
    check("compare.py runs", rc == 0 and rc2 == 0, (err + err2)[-2000:])
    a, b = got.get(args.key, float("nan")), ref.get(args.key, float("nan"))
    check("%s = %.4e vs reference %.4e: ratio %.4f <= %.3f" % (args.key, a, b, a / b,
          1 + args.tol), a <= (1 + args.tol) * b)
    for spec in args.max or []:
        k, v = spec.split("=")
        value = got.get(k, float("nan"))
        check("contact run: %s = %.4e <= %s (reference %.4e)" % (k, value, v,
              ref.get(k, float("nan"))), value <= float(v))
    for spec in args.min or []:
        k, v = spec.split("=")
        value = got.get(k, float("nan"))
        check("contact run: %s = %.4e >= %s (reference %.4e)" % (k, value, v,
              ref.get(k, float("nan"))), value >= float(v))
    report_contact_energy(wd)
    if args.energy_tol > 0.0:
        header, rows = read_history(wd)
        worst = np.abs(rows[:, header.index("energy_error")]).max()
        check("energy balance with the contact work booked: |error| %.2e <= %.1e"
              % (worst, args.energy_tol), worst <= args.energy_tol)
    if args.booked_pair and args.momentum_tol > 0.0:
        header, rows = read_history(wd)
        booked = np.array([rows[:, header.index(args.booked_pair + "_dmom_" + c)].sum()
                           for c in "xyz"])
        p = rows[:, [header.index("momentum_" + c) for c in "xyz"]]
        scale = max(np.linalg.norm(p, axis=1).max(), 1e-300)
        check("momentum booked by contact pair %s: |sum dmom| / max |p| %.2e <= %.1e"
              % (args.booked_pair, np.linalg.norm(booked) / scale, args.momentum_tol),
              np.linalg.norm(booked) / scale <= args.momentum_tol)
    if args.pair != "none":
        header, rows = read_history(wd)
        active = rows[:, header.index(args.pair + "_active")]
        released = rows[:, header.index(args.pair + "_released")]
        check("interface in contact on every cycle (%d of %d)" % ((active > 0).sum(),
              active.size), bool((active > 0).all()))
        check("no node released (%d)" % released.sum(), released.sum() == 0)
        pen = rows[:, header.index(args.pair + "_pen_max")]
        print("largest penetration %.3e" % pen.max())
    if args.radial_penetration:
        from impact3d_tools import radial
        inner, outer, radius, limit = args.radial_penetration
        rows = radial.history(wd, int(inner), int(outer), float(radius))
        time, worst, direction = max(rows, key=lambda row: row[1])
        check("curved interface: largest radial penetration %.3e (t = %.3f, direction %s) "
              "<= %s" % (worst, time, np.array2string(direction, precision=3), limit),
              worst <= float(limit))
        # The contact audit (the dumps' contact_gap) against the ray cast on
        # the same faceting: they differ only by the direction they measure
        # in (nearest point against radial), which on the faceted sphere is
        # at most the half-angle of a segment, 1 - cos(h / 2R) < 1%; 10% is
        # the bound the contact issue set. Dumps where the ray cast sees
        # less than 1e-4 (round-off-scale overlap) are not compared.
        ratios = [(t, a / r) for t, r, a in radial.audit_compare(
            wd, int(inner), int(outer), float(radius)) if r > 1e-4]
        worst_ratio = max((abs(q - 1.0) for _, q in ratios), default=0.0)
        check("audit agrees with the ray cast within 10%% at every dump (worst |ratio - 1| "
              "%.4f over %d dumps)" % (worst_ratio, len(ratios)),
              len(ratios) > 0 and worst_ratio <= 0.1)


def report_contact_energy(workdir):
    """Print the energy the contact forces did (relative to the initial total)
    and the largest energy_error of the balance that books it."""
    import numpy as np
    header, rows = read_history(workdir)
    e0 = rows[0, header.index("total_energy")]
    if "contact_work" in header:
        print("contact work %.3e of the initial total energy"
              % (rows[-1, header.index("contact_work")] / e0))
    print("largest |energy_error| / E0 %.2e"
          % (np.abs(rows[:, header.index("energy_error")]).max() / abs(e0)))


def cmd_shape(args):
    """Taylor rods: the final length L and foot diameter D of --deck are within
    --tol (relative) of those of --reference."""
    wd_ref = os.path.join(args.workdir, "reference")
    wd = os.path.join(args.workdir, "run")
    code, out, err = run(args, args.np, wd_ref, args.reference)
    check("reference run exits 0", code == 0, err[-2000:])
    code2, out, err = run(args, args.np, wd, args.deck)
    check("run exits 0", code2 == 0, err[-2000:])
    if code or code2:
        return
    lr, dr = rod_shape(final_dump(wd_ref))
    l, d = rod_shape(final_dump(wd))
    check("final length %.4f vs reference %.4f: %+.2f%% within %.1f%%"
          % (l, lr, 100 * (l / lr - 1), 100 * args.tol), abs(l / lr - 1) <= args.tol)
    check("foot diameter %.4f vs reference %.4f: %+.2f%% within %.1f%%"
          % (d, dr, 100 * (d / dr - 1), 100 * args.tol), abs(d / dr - 1) <= args.tol)
    report_contact_energy(wd)
    print(out.strip().splitlines()[-2] if out.strip() else "")


def cmd_slide(args):
    """A block (block 1) pressed onto a fixed plane by an applied pressure
    (--pressure over its contact area --area) slides along x from --v0 under
    Coulomb friction (--friction). While it slides the friction force is
    mu p A, so its velocity falls at a = mu p A / m (m its mass, from the
    first dump) and it stops after v0/a, having moved v0^2/(2a).

    Measured: deceleration: least-squares slope of the block's own mean
    velocity (its nodes' momentum over its mass, from the dumps) over the
    dumps with 0.2 v0 < v < 0.8 v0 (away from the start and the stop);
    stopping time: the first cycle with momentum_x / m <= 0 in the history
    (every cycle; the plane's x momentum, at most 2e-3 m v0 at every dump -
    checked - shifts it by at most 0.2%); stopping distance: the
    displacement of the block's centre of mass from the first dump to the
    last (the run ends after the stop). Each within --tol of the analytic
    value. Also: the energy balance to 1e-12
    (friction work booked), and the friction work - the pair's work column
    (--pair) or, without contact, the boundary work - ends within --tol of
    minus the block's initial kinetic energy and never exceeds 1e-3 of it."""
    import numpy as np
    wd = os.path.join(args.workdir, "slide")
    code, out, err = run(args, args.np, wd, args.deck)
    check("run exits 0", code == 0, err[-2000:])
    if code != 0:
        return
    header, rows = read_history(wd)
    t = rows[:, header.index("time")]
    dumps = sorted(glob.glob(os.path.join(wd, "*_[0-9][0-9][0-9][0-9][0-9][0-9].h5")))
    first = dump.load(dumps[0])
    nodes = np.unique(first["connectivity"][first["block"] == 1].ravel())
    m = first["node_mass"][nodes].sum()
    v0 = args.v0
    a = args.friction * args.pressure * args.area / m
    t_stop = v0 / a
    d_stop = v0 * v0 / (2.0 * a)
    print("block mass %.6e; analytic deceleration %.6e, stopping time %.4f, distance %.5f"
          % (m, a, t_stop, d_stop))
    v = rows[:, header.index("momentum_x")] / m

    def centre(d):
        w = d["node_mass"][nodes]
        return (w * d["coordinates"][nodes, 0]).sum() / w.sum()

    worst = 0.0
    last = None
    td, vd = [], []
    for path in dumps:
        d = dump.load(path)
        time = float(d["attrs"]["time"])
        last = d
        mine = (d["node_mass"][nodes] * d["node_velocity"][nodes, 0]).sum()
        td.append(time)
        vd.append(mine / m)
        j = np.argmin(np.abs(t - time))
        if time > 0.0 and abs(t[j] - time) <= 1e-9 * max(time, 1.0):
            worst = max(worst, abs(rows[j, header.index("momentum_x")] - mine))
    check("x momentum of the plane at the dumps within %.3e of m v0 (<= 2e-3)"
          % (worst / (m * v0)), worst <= 2e-3 * m * v0)
    td, vd = np.array(td), np.array(vd)
    sliding = (vd > 0.2 * v0) & (vd < 0.8 * v0)
    slope = np.polyfit(td[sliding], vd[sliding], 1)[0]
    check("deceleration %.6e vs mu p A / m = %.6e within %.1f%% (%+.3f%%, %d dumps)"
          % (-slope, a, 100 * args.tol, 100 * (-slope / a - 1), sliding.sum()),
          sliding.sum() >= 10 and abs(-slope / a - 1) <= args.tol)
    stopped = np.where(v <= 0.0)[0]
    check("the block stops", stopped.size > 0)
    if stopped.size:
        ts = t[stopped[0]]
        check("stopping time %.4f vs v0/a = %.4f within %.1f%% (%+.3f%%)"
              % (ts, t_stop, 100 * args.tol, 100 * (ts / t_stop - 1)),
              abs(ts / t_stop - 1) <= args.tol)
    dist = centre(last) - centre(first)
    check("stopping distance %.5f vs v0^2/(2a) = %.5f within %.1f%% (%+.3f%%)"
          % (dist, d_stop, 100 * args.tol, 100 * (dist / d_stop - 1)),
          abs(dist / d_stop - 1) <= args.tol)
    vend = (last["node_mass"][nodes] * last["node_velocity"][nodes, 0]).sum() / m
    check("at rest at the end: |v| = %.3e <= 1%% of v0" % abs(vend), abs(vend) <= 0.01 * v0)
    err_max = np.abs(rows[:, header.index("energy_error")]).max()
    check("energy balance with friction work: max |energy_error| %.3e <= 1e-12" % err_max,
          err_max <= 1e-12)
    col = (args.pair + "_work") if args.pair in [h[:-5] for h in header if
                                                  h.endswith("_work")] else "boundary_work"
    work = rows[:, header.index(col)]
    ke0 = 0.5 * m * v0 * v0
    check("friction work (%s) %.6e = -(initial kinetic energy %.6e) within %.1f%%, "
          "never above 1e-3 of it (max %.3e)" % (col, work[-1], ke0, 100 * args.tol,
                                                  work.max()),
          abs(-work[-1] / ke0 - 1) <= args.tol and work.max() <= 1e-3 * ke0)


def cmd_same(args):
    """--deck and --reference, run on --np ranks, write the same dumps and every one
    is bitwise identical (h5diff, /run excluded)."""
    wd_ref = os.path.join(args.workdir, "reference")
    wd = os.path.join(args.workdir, "run")
    code, out, err = run(args, args.np, wd_ref, args.reference)
    check("reference run exits 0", code == 0, err[-2000:])
    code2, out, err = run(args, args.np, wd, args.deck)
    check("run exits 0", code2 == 0, err[-2000:])
    if code or code2:
        return
    ref = sorted(os.path.basename(p) for p in glob.glob(os.path.join(wd_ref, "*.h5")))
    mine = sorted(os.path.basename(p) for p in glob.glob(os.path.join(wd, "*.h5")))
    check("same dumps written (%d)" % len(ref), mine == ref and len(ref) >= 2, " ".join(mine))
    for name in ref:
        if name in mine:
            same, diff = h5same(os.path.join(wd_ref, name), os.path.join(wd, name))
            check("%s bitwise identical to the reference's" % name, same, diff)


def cmd_impact(args):
    """Two bodies through contact (pair --pair): the energy balance closes to
    --tol, the largest penetration stays below --max-pen, the total momentum
    stays within --momentum-tol of its initial value (relative to its norm;
    give it for DLM, exact); reports the contact work and the final
    mass-weighted velocity of each block."""
    import numpy as np
    wd = os.path.join(args.workdir, "impact")
    code, out, err = run(args, args.np, wd, args.deck)
    check("run exits 0", code == 0, err[-2000:])
    if code != 0:
        return
    header, rows = read_history(wd)
    e0 = abs(rows[0, header.index("total_energy")])
    worst = np.abs(rows[:, header.index("energy_error")]).max()
    check("energy balance |error| %.2e <= %.1e" % (worst, args.tol), worst <= args.tol)
    pen = rows[:, header.index(args.pair + "_pen_max")].max()
    check("largest penetration %.3e <= %.3e" % (pen, args.max_pen), pen <= args.max_pen)
    p = rows[:, [header.index("momentum_" + c) for c in args.momentum_axes]]
    drift = np.linalg.norm(p - p[0], axis=1).max() / max(np.linalg.norm(p[0]), 1e-300)
    if args.momentum_tol > 0.0:
        check("momentum drift (%s) %.2e <= %.1e" % (args.momentum_axes, drift,
                                                    args.momentum_tol),
              drift <= args.momentum_tol)
    else:
        print("momentum drift %.2e of the initial momentum" % drift)
    active = rows[:, header.index(args.pair + "_active")] > 0
    t = rows[:, header.index("time")]
    if active.any():
        print("contact from t = %.2f to t = %.2f" % (t[active][0], t[active][-1]))
    print("contact work %.3e of the initial total energy"
          % (rows[-1, header.index("contact_work")] / e0))
    d = dump.load(final_dump(wd))
    for b in np.unique(d["block"]):
        nodes = np.unique(d["connectivity"][d["block"] == b].ravel())
        m = d["node_mass"][nodes]
        v = (m[:, None] * d["node_velocity"][nodes]).sum(axis=0) / m.sum()
        print("block %d final mean velocity (%.4e, %.4e, %.4e)" % (b, v[0], v[1], v[2]))
    print(out.strip().splitlines()[-2] if out.strip() else "")


def cmd_twowave(args):
    """Elastic-plastic piston problem: elastic precursor and plastic wave.

    --target is the longitudinal speed c_L, --hel the 1D-strain Hugoniot
    elastic limit (stress), --c0 and --s1 the Hugoniot fit, --rho0 the density,
    --target-velocity the piston speed; the run starts at t = 0 with the piston
    at --origin."""
    import numpy as np
    wd = os.path.join(args.workdir, "twowave")
    code, out, err = run(args, args.np, wd, args.deck)
    check("run exits 0", code == 0, err[-2000:])
    if code != 0:
        return
    d = dump.load(final_dump(wd))
    t = float(d["attrs"]["time"])
    x = d["coordinates"][:, 0]
    v = d["node_velocity"][:, 0]
    order = np.argsort(x)
    x, v = x[order], v[order]
    up = args.target_velocity
    u_hel = args.hel / (args.rho0 * args.target)

    def crossing(level):
        k = np.where(v > level)[0].max()
        return x[k] + (x[k + 1] - x[k]) * (v[k] - level) / (v[k] - v[k + 1])
    elastic = (crossing(0.5 * u_hel) - args.origin) / t
    check("elastic precursor speed %.5f vs c_L %.5f within 2%%" % (elastic, args.target),
          abs(elastic / args.target - 1) <= 0.02)
    # Precursor plateau: zones between the two fronts.
    c = dump.zone_centroids(d)[:, 0]
    plastic_front = crossing(0.5 * (u_hel + up))
    elastic_front = crossing(0.5 * u_hel)
    gap = elastic_front - plastic_front
    sel = (c > plastic_front + 0.25 * gap) & (c < elastic_front - 0.25 * gap)
    sxx = d["deviatoric_stress"][:, 0] if d["deviatoric_stress"].ndim == 2 else None
    sigma = d["pressure"][sel] - sxx[sel]
    hel = float(np.median(sigma))
    check("precursor amplitude %.6f vs HEL %.6f within 3%% (%d zones)" % (hel, args.hel, sel.sum()),
          sel.sum() > 0 and abs(hel / args.hel - 1) <= 0.03)
    # Plastic wave: speed relative to the material ahead of it against c0 + s1 up.
    plastic_lab = (plastic_front - args.origin) / t
    behind = (c > args.origin + 0.1 * plastic_lab * t) & (c < plastic_front - 0.05 * plastic_lab * t)
    u_measured = float(np.median(dump.zone_velocity(d)[behind, 0])) if behind.any() else up
    expected = args.c0 + args.s1 * u_measured
    check("plastic wave speed %.5f vs c0 + s up = %.5f (up = %.5f) within 3%%"
          % (plastic_lab, expected, u_measured), abs(plastic_lab / expected - 1) <= 0.03)


def cmd_shell_stop(args):
    """Imploding shell: the inner surface (nodes at radius --origin at t = 0)
    stops at --target within --tol (absolute); the stopping radius is the
    smallest mean radius over the dumps."""
    import numpy as np
    target = args.target
    if args.reference:
        wd_ref = os.path.join(args.workdir, "reference")
        code, out, err = run(args, args.np, wd_ref, args.reference)
        check("reference run exits 0", code == 0, err[-2000:])
        if code != 0:
            return
        target = min(inner_radius_history(wd_ref, args.origin), key=lambda h: h[1])[1]
        print("  reference (single shell) stops at r = %.4f" % target)
    wd = os.path.join(args.workdir, "shell")
    code, out, err = run(args, args.np, wd, args.deck)
    check("run exits 0", code == 0, err[-2000:])
    if code != 0:
        return
    history = inner_radius_history(wd, args.origin)
    t_stop, r_stop = min(history, key=lambda h: h[1])
    print("  inner radius history: " + ", ".join("%.0f:%.3f" % h for h in history))
    check("inner surface stops at r = %.4f (t = %.1f) vs %.4f within %.2f"
          % (r_stop, t_stop, target, args.tol), abs(r_stop - target) <= args.tol)
    from impact3d_tools.exact import verney as exact_verney
    a_stop, t_end, a, t = exact_verney.verney()
    times = np.array([h[0] for h in history])
    radii = np.array([h[1] for h in history])
    exact = exact_verney.radius_at(times, a, t, a_stop, t_end)
    worst = float(np.max(np.abs(radii / exact - 1.0)))
    check("inner radius history within 2%% of the rigid-plastic energy balance (worst %.2f%%)"
          % (100 * worst), worst <= 0.02)
    if args.reference:
        report_contact_energy(wd)


def cmd_stopfile(args):
    """A STOP file in the output directory: the run writes a restart dump and
    exits with code 3 at its first check; restarted (without the file) on
    another rank count it ends bitwise identical to an uninterrupted run."""
    wd = os.path.join(args.workdir, "full")
    code, out, err = run(args, args.np, wd, args.deck)
    check("uninterrupted run exits 0", code == 0, err[-2000:])
    full = final_dump(wd)
    ws = os.path.join(args.workdir, "stopped")
    if os.path.isdir(ws):
        shutil.rmtree(ws)
    os.makedirs(ws)
    shutil.copy(args.deck, os.path.join(ws, "deck.nml"))
    open(os.path.join(ws, "STOP"), "w").close()
    cmd = [args.mpiexec, "-np", str(args.np), args.exe, "deck.nml"]
    proc = subprocess.run(cmd, cwd=ws, env=ENV, capture_output=True, text=True)
    stopped_restart_check(args, args.deck, full, ws, proc.returncode, proc.stdout, proc.stderr,
                          "stop file")


def variant_deck(args):
    """The deck with each --replace OLD NEW applied (each OLD must occur), written
    to the work directory; returns its path."""
    text = open(args.deck).read()
    for old, new in args.replace or []:
        if old not in text:
            raise SystemExit("regress.py: --replace: %r not in %s" % (old, args.deck))
        text = text.replace(old, new)
    os.makedirs(args.workdir, exist_ok=True)
    path = os.path.join(args.workdir, "variant.nml")
    with open(path, "w") as f:
        f.write(text)
    return path


def dump_cycle(path):
    m = re.search(r"_(\d{6})\.h5$", path or "")
    return int(m.group(1)) if m else -1


def rank_pids(parent, np):
    """pids of the impact3d processes started by mpirun `parent`, by MPI rank
    (OMPI_COMM_WORLD_RANK in their environment): {rank: pid}."""
    found = {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open("/proc/%s/stat" % entry) as f:
                ppid = int(f.read().rsplit(")", 1)[1].split()[1])
            if ppid != parent:
                continue
            with open("/proc/%s/environ" % entry, "rb") as f:
                env = dict(v.split(b"=", 1) for v in f.read().split(b"\0") if b"=" in v)
        except (OSError, ValueError, IndexError):
            continue
        if b"OMPI_COMM_WORLD_RANK" in env:
            found[int(env[b"OMPI_COMM_WORLD_RANK"])] = int(entry)
    return found


def stopped_restart_check(args, deck, full, ws, code, out, err, why):
    """Common end of the signal and walllimit commands: exit code 3, the message,
    a restart dump before the final cycle; restarted on --restart-np ranks the
    run ends bitwise identical to the uninterrupted one."""
    check("stopped run exits with code 3", code == 3, "got %d: %s" % (code, err[-2000:]))
    check("it says why", why in out, out[-1000:])
    stop_dump = final_dump(ws)
    print("  stopped at cycle %d of %d" % (dump_cycle(stop_dump), dump_cycle(full)))
    check("restart dump written before the end", stop_dump is not None
          and 0 < dump_cycle(stop_dump) < dump_cycle(full), str(stop_dump))
    if code != 3 or stop_dump is None:
        return
    wr = os.path.join(args.workdir, "restarted")
    code, out, err = run(args, args.restart_np, wr, deck,
                         extra=["--restart", os.path.abspath(stop_dump)])
    check("restarted run on %d rank(s) exits 0" % args.restart_np, code == 0, err[-2000:])
    mine = os.path.join(wr, os.path.basename(full))
    if os.path.exists(mine):
        same, diff = h5same(full, mine)
        check("final dump bitwise identical after the stop and restart", same, diff)
    else:
        check("restarted run ends at the same cycle", False, mine)


def cmd_signal(args):
    """A real signal: start the run, wait for its first status line (the deck
    should print them, e.g. status_every = 10), send --signal to mpirun (which
    forwards USR1 and USR2 to every rank) or, with --to rank, to the last rank's
    process only (the stop must still reach every rank); then as stopfile."""
    import signal
    import time
    deck = variant_deck(args)
    wd = os.path.join(args.workdir, "full")
    t0 = time.time()
    code, out, err = run(args, args.np, wd, deck)
    check("uninterrupted run exits 0 (%.1f s)" % (time.time() - t0), code == 0, err[-2000:])
    full = final_dump(wd)
    if code != 0 or full is None:
        return
    ws = os.path.join(args.workdir, "stopped")
    if os.path.isdir(ws):
        shutil.rmtree(ws)
    os.makedirs(ws)
    shutil.copy(deck, os.path.join(ws, "deck.nml"))
    signum = getattr(signal, "SIG" + args.signal)
    cmd = [args.mpiexec, "-np", str(args.np), args.exe, "deck.nml"]
    with open(os.path.join(ws, "stderr.txt"), "w+") as errfile:
        proc = subprocess.Popen(cmd, cwd=ws, env=ENV, stdout=subprocess.PIPE, stderr=errfile,
                                text=True)
        lines = []
        sent = None
        deadline = time.time() + args.timeout
        for line in proc.stdout:
            lines.append(line)
            if sent is None and re.match(r"\s*cycle\s+\d+", line):
                if args.to == "mpirun":
                    target = proc.pid
                else:
                    pids = {}
                    while len(pids) < args.np and time.time() < deadline:
                        pids = rank_pids(proc.pid, args.np)
                        time.sleep(0.01)
                    target = pids.get(args.np - 1)
                if target is not None:
                    os.kill(target, signum)
                    sent = line.split()[1]
                    print("  SIG%s sent to %s (pid %d) after cycle %s"
                          % (args.signal, args.to, target, sent))
            if time.time() > deadline:
                proc.kill()
                break
        code = proc.wait()
        errfile.seek(0)
        err = errfile.read()
    out = "".join(lines)
    check("signal sent once the run printed a cycle line", sent is not None, out[-1000:])
    stopped_restart_check(args, deck, full, ws, code, out, err,
                          "signal SIG%s received" % args.signal)


def cmd_walllimit(args):
    """&control wall_limit: timed uninterrupted run T, then the same deck with
    wall_limit = 1 s + T/3 (the run budgets three cycles, two dumps and 1 s), so
    that the stop comes well before the end whatever the machine; should that
    run still finish (the machine got faster), again with 1 s + a third of the
    rest, up to three times. The run must report its stop before the limit;
    then as stopfile."""
    import time
    deck = variant_deck(args)
    wd = os.path.join(args.workdir, "full")
    t0 = time.time()
    code, out, err = run(args, args.np, wd, deck)
    elapsed = time.time() - t0
    check("uninterrupted run exits 0 (%.1f s)" % elapsed, code == 0, err[-2000:])
    full = final_dump(wd)
    if code != 0 or full is None:
        return
    text = open(deck).read()
    m = re.search(r"^&control\b", text, flags=re.M)
    check("deck has a &control group", m is not None)
    if m is None:
        return
    limit = 1.0 + elapsed / 3.0
    ws = os.path.join(args.workdir, "stopped")
    limited = os.path.join(args.workdir, "limited.nml")
    for attempt in range(3):
        with open(limited, "w") as f:
            f.write(text[:m.end()] + " wall_limit = %.3f," % limit + text[m.end():])
        code, out, err = run(args, args.np, ws, limited)
        if code != 0:
            break
        print("  finished within wall_limit = %.2f s; again with a smaller limit" % limit)
        limit = 1.0 + (limit - 1.0) / 3.0
    found = re.search(r"with a restart dump, (\S+) s after the start", out)
    used = float(found.group(1)) if found else float("inf")
    check("stopped %.2f s after the start, before wall_limit = %.2f s" % (used, limit),
          used < limit, out[-1000:])
    stopped_restart_check(args, deck, full, ws, code, out, err, "close to the wall-time limit")


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("command", choices=["bitwise", "restart", "energy", "failure", "compare",
                                        "convergence", "window", "interface", "stability",
                                        "wavefront", "rebound", "twowave", "shell_stop",
                                        "stopfile", "bars", "mirror", "patch", "relative",
                                        "shape", "impact", "signal", "walllimit", "same",
                                        "restartdeck", "slide"])
    p.add_argument("--exe", required=True)
    p.add_argument("--mpiexec", default="mpirun")
    p.add_argument("--workdir", required=True)
    p.add_argument("--deck", required=True)
    p.add_argument("--ranks", type=int, nargs="+", default=[1, 2, 3, 4])
    p.add_argument("--np", type=int, default=1)
    p.add_argument("--restart-np", type=int, default=1)
    p.add_argument("--from-cycle", type=int, default=0)
    p.add_argument("--tol", type=float, default=1e-12)
    p.add_argument("--expect", choices=["volume", "nan", "dt", "any"], default="volume")
    p.add_argument("--problem")
    p.add_argument("--max", action="append")
    p.add_argument("--min", action="append")
    p.add_argument("--sizes", type=int, nargs="+", default=[100, 200, 400])
    p.add_argument("--key", default="L1_rho")
    p.add_argument("--min-rate", type=float, default=0.8)
    p.add_argument("--max-at", action="append")
    p.add_argument("--axis", default="x")
    p.add_argument("--range", type=float, nargs=2)
    p.add_argument("--target", type=float)
    p.add_argument("--zones-tol", type=float, default=2.0)
    p.add_argument("--target-velocity", type=float, default=0.0)
    p.add_argument("--origin", type=float, default=0.0)
    p.add_argument("--hel", type=float)
    p.add_argument("--c0", type=float)
    p.add_argument("--s1", type=float)
    p.add_argument("--rho0", type=float)
    p.add_argument("--reference", help="reference deck (mirror)")
    p.add_argument("--pair", default="mid", help="contact pair name (bars)")
    p.add_argument("--duration", type=float, default=0.0)
    p.add_argument("--area", type=float, default=1.0)
    p.add_argument("--stress", type=float)
    p.add_argument("--v-left", type=float, default=0.0)
    p.add_argument("--v-right", type=float, default=0.0)
    p.add_argument("--v-interface", type=float, default=0.0)
    p.add_argument("--final-left", type=float)
    p.add_argument("--final-right", type=float)
    p.add_argument("--momentum-tol", type=float, default=0.0)
    p.add_argument("--booked-pair", default=None,
                   help="relative: with --momentum-tol, check the momentum this contact "
                        "pair books (sum of its dmom columns) against the largest |momentum|")
    p.add_argument("--momentum-axes", default="xyz",
                   help="impact: the momentum components no boundary acts on (a symmetry "
                        "plane's reaction changes the component along its normal)")
    p.add_argument("--max-pen", type=float, default=float("inf"))
    p.add_argument("--radial-penetration", nargs=4, metavar=("INNER", "OUTER", "RADIUS", "MAX"),
                   help="relative: in every dump, no node of block INNER on the sphere RADIUS "
                        "(at t = 0) lies more than MAX radially beyond the faceted surface of "
                        "block OUTER (tools/radial_gap.py)")
    p.add_argument("--sym-tol", type=float, default=None,
                   help="mirror: tolerance of the image's symmetry (default: --tol)")
    p.add_argument("--all-dumps", action="store_true",
                   help="mirror: compare every dump of the two runs, not only the final one")
    p.add_argument("--energy-tol", type=float, default=0.0,
                   help="mirror: largest |energy_error| of both runs; relative: of the "
                        "contact run (0: not checked)")
    p.add_argument("--compare-args", default="", help="extra arguments for compare.py")
    p.add_argument("--v0", type=float, help="slide: the block's initial speed along x")
    p.add_argument("--friction", type=float, help="slide: the Coulomb coefficient")
    p.add_argument("--pressure", type=float, help="slide: the applied pressure")
    p.add_argument("--replace", nargs=2, action="append", metavar=("OLD", "NEW"),
                   help="signal, walllimit, bitwise, restart: edit the deck text before "
                        "running")
    p.add_argument("--signal", default="USR1", choices=["USR1", "USR2", "TERM"])
    p.add_argument("--to", default="mpirun", choices=["mpirun", "rank"],
                   help="signal: send to mpirun, or to the last rank's process only")
    p.add_argument("--timeout", type=float, default=900.0,
                   help="signal: seconds before the signalled run is killed")
    args = p.parse_args()
    args.deck = os.path.abspath(args.deck)
    if args.reference:
        args.reference = os.path.abspath(args.reference)
    args.workdir = os.path.abspath(args.workdir)
    args.compare_args = args.compare_args.split()
    args.exe = os.path.abspath(args.exe)
    globals()["cmd_" + args.command](args)
    npass = sum(results)
    print("%d passed, %d failed" % (npass, len(results) - npass))
    sys.exit(0 if results and all(results) else 1)


if __name__ == "__main__":
    main()
