"""Restarts and batch stops: a run resumed from a dump, on another rank
count, ends bitwise identical (h5diff, /run excluded) to the uninterrupted run.

  restart --deck D --np A --restart-np B --from-cycle C [--replace OLD NEW ...]
      a run restarted from its cycle-C dump on B ranks ends bitwise identical
      to the uninterrupted run, and its history rows after cycle C equal the
      uninterrupted run's (to the rank-order round-off of the sums; with
      --history-bitwise, history.txt and the probe CSVs are byte for byte
      those of the uninterrupted run)
  restartdeck --deck D --np A --restart-np B --from-cycle C
      /run of the cycle-C dump holds the deck text (byte for byte), version,
      command line and rank count; a restart with &material gamma changed is
      refused (exit 1, naming &material and gamma) unless --restart-force; one
      with only comments, blanks and &output changed ends bitwise identical
  stopfile --deck D --np A --restart-np B
      a STOP file: exit 3 with a restart dump; the restart ends bitwise identical
  signal --deck D --np A --restart-np B --signal USR1|USR2|TERM --to mpirun|rank
         [--replace OLD NEW ...]
      a signal once the run has printed a cycle line: exit 3, restart dump,
      restart ends bitwise identical
  walllimit --deck D --np A --restart-np B [--replace OLD NEW ...]
      &control wall_limit set to stop well before the end: the same checks,
      and the run stops before the limit
"""
import glob
import os
import re
import subprocess

from checks.common import (ENV, add_replace, add_restart, check, command, final_dump, fresh,
                           h5same, run, variant_deck)


def full_run(args, deck):
    """The uninterrupted run of deck on --np ranks: (its final dump, its
    --from-cycle dump; None for the latter when the run failed or did not
    write it)."""
    wd = os.path.join(args.workdir, "full")
    code, out, err = run(args, args.np, wd, deck)
    check("uninterrupted run exits 0", code == 0, err[-2000:])
    full = final_dump(wd)
    if args.from_time is not None:
        args.from_cycle = dump_cycle_at(wd, args.from_time)
    start = os.path.join(wd, "dump_%06d.h5" % args.from_cycle)
    check("mid-run dump exists", os.path.exists(start), start)
    if code != 0 or not os.path.exists(start):
        return full, None
    return full, start


def dump_cycle_at(wd, time):
    """The cycle of the dump at time (to 1e-12 relative) in wd's dump.dumps
    index (lines: cycle, time, file); -1 when there is none."""
    index = os.path.join(wd, "dump.dumps")
    if not os.path.exists(index):
        return -1
    for line in open(index):
        f = line.split()
        if len(f) >= 2 and abs(float(f[1]) - time) <= 1e-12 * max(abs(time), 1.0):
            return int(f[0])
    return -1


def cmd_restart(args):
    deck = variant_deck(args) if args.replace else args.deck
    full, start = full_run(args, deck)
    if start is None:
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
    check_history(os.path.join(args.workdir, "full"), wr, args.from_cycle)
    if args.history_bitwise:
        # The restart runs in a new directory: its files hold the header and
        # the rows after the restart cycle.
        for name in ["history.txt"] + sorted(os.path.basename(p) for p in glob.glob(
                os.path.join(args.workdir, "full", "probe_*.csv"))):
            a = rows_after(os.path.join(args.workdir, "full", name), args.from_cycle)
            b = rows_after(os.path.join(wr, name), args.from_cycle)
            check("%s after the restart: header and the %d rows after cycle %d byte for byte "
                  "the uninterrupted run's" % (name, len(a) - 1, args.from_cycle),
                  a == b and len(a) > 1)


def rows_after(path, cycle):
    """The header line and the rows of cycle > cycle of a history or probe
    file, as bytes ([] when there is no file)."""
    if not os.path.exists(path):
        return []
    lines = open(path, "rb").read().split(b"\n")
    return lines[:1] + [r for r in lines[1:]
                        if r and int(r.replace(b",", b" ").split()[0]) > cycle]


def check_history(wd, wr, from_cycle):
    """The history after the restart point, every column (energies, momenta,
    each contact interface's diagnostics and work, per-material columns),
    against the uninterrupted run's rows of the same cycles. The state is
    bitwise the same, but the columns are sums over the ranks' nodes or
    zones, in an order that depends on the rank count: each may differ by its
    terms' round-off, at most n eps of its quantity's scale (n <= 1e4 terms
    here: 1e4 x 1.1e-16 ~ 1e-12). A quantity that does not continue across
    the restart (a sum restarted from zero) differs by its whole value.

    A column's scale is that of its quantity: energy_error is relative
    already (scale 1); the momenta and the momentum each interface adds (zero
    by symmetry or to round-off in some directions) share the largest
    |momentum|; each interface's force components share their largest; any
    other column its own largest magnitude."""
    import numpy as np
    rows = {}
    for name, d in (("full", wd), ("restarted", wr)):
        with open(os.path.join(d, "history.txt")) as f:
            names = f.readline().split()[1:]
            rows[name] = {int(float(line.split()[0])): [float(x) for x in line.split()]
                          for line in f if line.strip()}
    after = [c for c in sorted(rows["restarted"]) if c > from_cycle and c in rows["full"]]
    worst, where = 0.0, ""
    if after:
        a = np.array([rows["full"][c] for c in after])
        b = np.array([rows["restarted"][c] for c in after])
        top = np.abs(np.array(list(rows["full"].values()))).max(axis=0)
        scale = top.copy()
        momentum = [i for i, n in enumerate(names) if n.startswith("momentum_") or "_dmom_" in n]
        scale[momentum] = top[momentum].max()
        for i, n in enumerate(names):
            if n == "energy_error":
                scale[i] = 1.0
            elif re.search(r"_force_[xyz]$", n):
                group = [j for j, m in enumerate(names) if m[:-1] == n[:-1]]
                scale[i] = top[group].max()
        rel = np.abs(a - b) / np.maximum(scale, 1e-300)
        worst = float(rel.max())
        where = names[int(np.argmax(rel.max(axis=0)))]
    check("history after the restart equals the uninterrupted run's: %d rows, largest "
          "difference %.2e of a column's scale (<= 1e-12; %s)" % (len(after), worst, where),
          len(after) > 0 and worst <= 1e-12)


def text_attr(attrs, name):
    value = attrs.get(name, b"")
    return value.decode() if isinstance(value, bytes) else str(value)


def cmd_restartdeck(args):
    import h5py
    full, start = full_run(args, args.deck)
    if start is None:
        return
    with open(args.deck) as f:
        text = f.read()
    with h5py.File(start, "r") as f:
        attrs = dict(f["run"].attrs)
    stored = text_attr(attrs, "deck")
    check("/run deck equals the deck file's text", stored == text,
          "%d vs %d characters" % (len(stored), len(text)))
    version = text_attr(attrs, "version")
    check("/run version is set", len(version) > 0, version)
    command_line = text_attr(attrs, "command")
    check("/run command names the program and the deck",
          "impact3d" in command_line and "deck.nml" in command_line, command_line)
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


def cmd_stopfile(args):
    """A STOP file in the output directory: the run writes a restart dump and
    exits with code 3 at its first check; restarted (without the file) on
    another rank count it ends bitwise identical to an uninterrupted run."""
    wd = os.path.join(args.workdir, "full")
    code, out, err = run(args, args.np, wd, args.deck)
    check("uninterrupted run exits 0", code == 0, err[-2000:])
    full = final_dump(wd)
    ws = os.path.join(args.workdir, "stopped")
    fresh(ws, args.deck)
    open(os.path.join(ws, "STOP"), "w").close()
    proc = subprocess.run(command(args, args.np), cwd=ws, env=ENV, capture_output=True,
                          text=True)
    stopped_restart_check(args, args.deck, full, ws, proc.returncode, proc.stdout, proc.stderr,
                          "stop file")


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
    """Common end of the stopfile, signal and walllimit commands: exit code 3,
    the message, the timing report, a restart dump before the final cycle;
    restarted on --restart-np ranks the run ends bitwise identical to the
    uninterrupted one, its history.txt byte for byte the same."""
    check("stopped run exits with code 3", code == 3, "got %d: %s" % (code, err[-2000:]))
    check("it says why", why in out, out[-1000:])
    check("it prints the timing report (set-up line and the closing line)",
          re.search(r"^ +set-up +[0-9.]+$", out, re.M) is not None and
          re.search(r"^impact3d: done, \d+ cycles", out, re.M) is not None, out[-1000:])
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
        c = dump_cycle(stop_dump)
        a = rows_after(os.path.join(os.path.dirname(full), "history.txt"), c)
        b = rows_after(os.path.join(wr, "history.txt"), c)
        check("history.txt after the stop and restart: header and the %d rows after cycle %d "
              "byte for byte the uninterrupted run's" % (len(a) - 1, c), a == b and len(a) > 1)
    else:
        check("restarted run ends at the same cycle", False, mine)


def timed_full_run(args, deck):
    """The uninterrupted run: (final dump or None, seconds)."""
    import time
    wd = os.path.join(args.workdir, "full")
    t0 = time.time()
    code, out, err = run(args, args.np, wd, deck)
    elapsed = time.time() - t0
    check("uninterrupted run exits 0 (%.1f s)" % elapsed, code == 0, err[-2000:])
    return (final_dump(wd) if code == 0 else None), elapsed


def cmd_signal(args):
    """A real signal: start the run, wait for its first status line (the deck
    should print them, e.g. status_every = 10), send --signal to mpirun (which
    forwards USR1 and USR2 to every rank) or, with --to rank, to the last rank's
    process only (the stop must still reach every rank); then as stopfile."""
    import signal
    import time
    deck = variant_deck(args)
    full, _ = timed_full_run(args, deck)
    if full is None:
        return
    ws = os.path.join(args.workdir, "stopped")
    fresh(ws, deck)
    signum = getattr(signal, "SIG" + args.signal)
    with open(os.path.join(ws, "stderr.txt"), "w+") as errfile:
        proc = subprocess.Popen(command(args, args.np), cwd=ws, env=ENV,
                                stdout=subprocess.PIPE, stderr=errfile, text=True)
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
    deck = variant_deck(args)
    full, elapsed = timed_full_run(args, deck)
    if full is None:
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


def register(sub, common):
    p = sub.add_parser("restart", parents=[common], help="restart ends bitwise identical")
    add_restart(p)
    add_replace(p)
    p.add_argument("--history-bitwise", action="store_true",
                   help="history.txt and probe CSVs byte for byte the uninterrupted run's")
    p.set_defaults(func=cmd_restart)
    p = sub.add_parser("restartdeck", parents=[common],
                       help="the deck in /run; changed physics refused on restart")
    add_restart(p)
    p.set_defaults(func=cmd_restartdeck)
    p = sub.add_parser("stopfile", parents=[common], help="a STOP file stops the run cleanly")
    add_restart(p, from_cycle=False)
    p.set_defaults(func=cmd_stopfile)
    p = sub.add_parser("signal", parents=[common], help="a signal stops the run cleanly")
    add_restart(p, from_cycle=False)
    add_replace(p)
    p.add_argument("--signal", default="USR1", choices=["USR1", "USR2", "TERM"])
    p.add_argument("--to", default="mpirun", choices=["mpirun", "rank"],
                   help="send to mpirun, or to the last rank's process only")
    p.add_argument("--timeout", type=float, default=900.0,
                   help="seconds before the signalled run is killed")
    p.set_defaults(func=cmd_signal)
    p = sub.add_parser("walllimit", parents=[common], help="wall_limit stops the run cleanly")
    add_restart(p, from_cycle=False)
    add_replace(p)
    p.set_defaults(func=cmd_walllimit)
