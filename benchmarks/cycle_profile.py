#!/usr/bin/python3
"""Profile and speed of the cycle, before and after a change (issue 18, item 3).

Usage:
    /usr/bin/python3 benchmarks/cycle_profile.py --exe build/impact3d \\
        --baseline OLD_BINARY [--commit HASH --baseline-commit HASH] [--pairs 5]
        [--out benchmarks/cycle_profile_section.md] [--no-profile]

run_benchmarks.py calls it when given --baseline-exe, so one command
regenerates the whole report; it can also run alone (then
run_benchmarks.py --render-only puts the new section into docs/benchmarks.md).

Profile: callgrind instruction counts (valgrind, Debian package `valgrind`;
exact and independent of the machine's load) of the gamma = 1.4 Sedov octant
at 20^3 (tests/regression/decks/sedov_conv.nml.in) to t = 0.02, each binary;
the same deck with max_cycles = 1 gives the set-up's count plus one cycle's
(the smallest run the deck checks allow), so the loop's instructions per
zone-cycle are (total - that) / (zones x (cycles - 1)), the first cycle left out. The
functions with at least 0.5% of either run are listed.

Speed: the same deck at 45^3 to t = 0.01 on 1 rank, the two binaries run
in turn (A, B, A, B ...), --pairs pairs, each run after the machine is quiet
(run_benchmarks.wait_for_quiet); loop = T - D of the closing line
`done, N cycles, T s (D s of it in dumps)`, the median per binary and its ns
per zone-cycle. Runs disturbed by other processes (more than 0.25 cores
during the run) are marked.
"""

import argparse
import glob
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import run_benchmarks as rb  # noqa: E402  (the deck, run and quiet helpers)

PROFILE_N, PROFILE_T = 20, 0.02
SPEED_N, SPEED_T = 45, 0.01
MIN_SHARE = 0.005
LINE_RE = re.compile(r"^\s*([\d,]+)\s+\(\s*[\d.]+%\)\s+(.*)$")


def function_name(raw):
    """'???:__hydro_kernels_MOD_zone_work [/x/impact3d]' -> 'zone_work'."""
    name = raw.split(" [")[0]
    name = name.split(":")[-1]
    name = re.sub(r"^__\w+?_MOD_", "", name)
    name = re.sub(r"\.(constprop|isra|part)\.\d+", "", name)
    return name


def callgrind_counts(exe, deck):
    """Instruction counts per function (summed over the processes) and the total."""
    with tempfile.TemporaryDirectory(prefix="impact3d_cg_") as wd:
        with open(os.path.join(wd, "deck.nml"), "w", encoding="utf-8") as handle:
            handle.write(deck)
        proc = subprocess.run(["valgrind", "--tool=callgrind", "--trace-children=yes",
                               "--callgrind-out-file=" + os.path.join(wd, "cg.%p"), exe,
                               "deck.nml"], cwd=wd, env=rb.ENV, capture_output=True, text=True)
        # 0: t_end reached; 3: stopped at max_cycles (the set-up run)
        if proc.returncode not in (0, 3):
            sys.exit("cycle_profile.py: %s failed under valgrind (exit %d): %s"
                     % (exe, proc.returncode, proc.stdout[-500:] + proc.stderr[-500:]))
        counts, total = {}, 0
        for path in glob.glob(os.path.join(wd, "cg.*")):
            if os.path.getsize(path) == 0:
                continue
            text = subprocess.run(["callgrind_annotate", "--threshold=100", path],
                                  capture_output=True, text=True, check=True).stdout
            for line in text.splitlines():
                m = LINE_RE.match(line)
                if not m:
                    continue
                value = int(m.group(1).replace(",", ""))
                if "PROGRAM TOTALS" in m.group(2):
                    total += value
                    continue
                name = function_name(m.group(2))
                counts[name] = counts.get(name, 0) + value
        return counts, total


def profile(exe, deck_text):
    deck = rb.make_deck(deck_text, PROFILE_N, t_end=PROFILE_T)
    setup = rb.make_deck(deck_text, PROFILE_N, t_end=PROFILE_T, control="max_cycles = 1")
    counts, total = callgrind_counts(exe, deck)
    _, setup_total = callgrind_counts(exe, setup)
    run = rb.run_case(exe, deck)
    return {"counts": counts, "total": total, "setup": setup_total,
            "cycles": run.get("cycles")}


def speed(exes, pairs, deck_text):
    deck = rb.make_deck(deck_text, SPEED_N, t_end=SPEED_T)
    runs = {exe: [] for exe in exes}
    for _ in range(pairs):
        for exe in exes:
            rb.wait_for_quiet(limit=60.0)
            run = rb.run_case(exe, deck)
            if "error" in run:
                sys.exit("cycle_profile.py: %s failed: %s" % (exe, run["error"]))
            runs[exe].append(run)
    return runs


def render(prof, runs, labels, exes, args):
    zones_p = PROFILE_N ** 3
    zones_s = SPEED_N ** 3
    lines = ["## Cost of a cycle, latest change: profile and speed, %s -> %s"
             % (labels[0], labels[1]), "",
             "Written by `benchmarks/cycle_profile.py` (%s), %s; machine: %s, load "
             "average %.2f at the start." % (
                 " ".join(["--baseline", os.path.basename(args.baseline), "--exe",
                           os.path.basename(args.exe)]),
                 rb.datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z"),
                 rb.machine_info(exes[1]).get("cpu", "?"), os.getloadavg()[0]), ""]
    if prof:
        lines += ["**Profile** (callgrind instructions, gamma = 1.4 Sedov 20^3 to t = %g; "
                  "the same deck with max_cycles = 1 gives the set-up and the first "
                  "cycle):" % PROFILE_T, "",
                  "| function | %s (1e9 instr.) | %s (1e9 instr.) |" % tuple(labels),
                  "|---|---|---|"]
        names = set()
        for p in prof:
            for name, value in p["counts"].items():
                if value >= MIN_SHARE * p["total"]:
                    names.add(name)
        order = sorted(names, key=lambda n: -max(p["counts"].get(n, 0) for p in prof))
        for name in order:
            cells = ["%.3f" % (p["counts"].get(name, 0) / 1e9) if name in p["counts"] else "-"
                     for p in prof]
            lines.append("| %s | %s | %s |" % (name, cells[0], cells[1]))
        lines.append("| whole run | %.3f | %.3f |" % tuple(p["total"] / 1e9 for p in prof))
        lines.append("| set-up and first cycle (max_cycles = 1) | %.3f | %.3f |"
                     % tuple(p["setup"] / 1e9 for p in prof))
        per = [(p["total"] - p["setup"]) / (zones_p * (p["cycles"] - 1)) for p in prof]
        lines.append("| loop, instructions per zone-cycle (cycles) | %.0f (%d) | %.0f (%d) |"
                     % (per[0], prof[0]["cycles"], per[1], prof[1]["cycles"]))
        lines += ["", "Loop instructions per zone-cycle: %.0f -> %.0f (%+.1f%%)."
                  % (per[0], per[1], 100.0 * (per[1] / per[0] - 1.0)), ""]
    lines += ["**Speed** (gamma = 1.4 Sedov octant %d^3 to t = %g, 1 rank, the binaries "
              "in turn, %d pairs; loop = T - D of the closing line; * = disturbed run, "
              "other processes used more than %.2f cores):" % (SPEED_N, SPEED_T, args.pairs,
                                                                  rb.DISTURBED), "",
              "| binary | cycles | loop s (runs in order) | median s | ns/zone-cycle |",
              "|---|---|---|---|---|"]
    ns = []
    for label, exe in zip(labels, exes):
        r = runs[exe]
        loops = [x["loop"] for x in r]
        med = statistics.median(loops)
        cycles = r[0]["cycles"]
        ns.append(med / (zones_s * cycles) * 1e9)
        cells = ", ".join("%.3f%s" % (x["loop"], "*" if x["other_load"] > rb.DISTURBED else "")
                          for x in r)
        lines.append("| %s | %d | %s | %.3f | %.0f |" % (label, cycles, cells, med, ns[-1]))
    lines += ["", "Median ns per zone-cycle: %.0f -> %.0f (%+.1f%%); issue 18's target "
              "for the predictor-corrector: 450." % (ns[0], ns[1], 100.0 * (ns[1] / ns[0] - 1.0)),
              ""]
    return "\n".join(lines) + "\n"


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exe", default=os.path.join(rb.ROOT, "build", "impact3d"))
    p.add_argument("--baseline", required=True, help="the binary before the change")
    p.add_argument("--commit", default=None, help="commit of --exe (default: HEAD)")
    p.add_argument("--baseline-commit", default=None, help="commit of --baseline")
    p.add_argument("--pairs", type=int, default=5)
    p.add_argument("--no-profile", action="store_true", help="speed only (no valgrind)")
    p.add_argument("--out", default=os.path.join(HERE, "cycle_profile_section.md"))
    args = p.parse_args()
    run(args)


def run(args):
    exes = [os.path.abspath(args.baseline), os.path.abspath(args.exe)]
    for exe in exes:
        if not os.access(exe, os.X_OK):
            sys.exit("cycle_profile.py: %s is not an executable" % exe)
    labels = ["before, %s" % (args.baseline_commit or os.path.basename(exes[0])),
              "after, %s" % (args.commit or rb.git_commit())]
    deck_text = rb.template("sedov_conv.nml.in")
    prof = None
    if not args.no_profile:
        if not shutil.which("valgrind"):
            sys.exit("cycle_profile.py: valgrind not found (apt-get install valgrind), "
                     "or pass --no-profile")
        rb.log("cycle profile: callgrind of both binaries (about 30 s each)")
        prof = [profile(exe, deck_text) for exe in exes]
    rb.log("cycle speed: %d interleaved pairs at %d^3" % (args.pairs, SPEED_N))
    runs = speed(exes, args.pairs, deck_text)
    text = render(prof, runs, labels, exes, args)
    with open(args.out, "w", encoding="utf-8") as handle:
        handle.write(text)
    rb.log("wrote %s" % args.out)
    return text


if __name__ == "__main__":
    main()
