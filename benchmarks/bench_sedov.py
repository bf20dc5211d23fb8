#!/usr/bin/python3
"""Time the Sedov octant at several sizes on 1 and 2 ranks (Release build).

Usage: bench_sedov.py [--exe build/impact3d] [--sizes 30 60] [--ranks 1 2]
                      [--t-end 0.3] [--out results.txt]
Reports, per run: zones, ranks, cycles, wall seconds of the time loop without
dumps, ns per zone-cycle (wall x ranks / (zones x cycles): the aggregate cost
of one zone-cycle on this many cores), zone-cycles per second, and peak
resident memory (1-rank runs, measured without mpirun) per zone.
"""
import argparse
import os
import re
import resource
import subprocess
import tempfile

DECK = """&control title = 'Sedov benchmark {n}^3', t_end = {t_end} /
&mesh x = 0.0, 1.2, nx = {n}, y = 0.0, 1.2, ny = {n}, z = 0.0, 1.2, nz = {n} /
&material name = 'gas', eos = 'ideal_gas', gamma = 1.4 /
&block name = 'octant', material = 'gas' /
&region density = 1.0, energy = 1.0e-10, deposit_energy = 0.106384, deposit_point = 0, 0, 0 /
&boundary set = 'xmin', type = 'symmetry' /
&boundary set = 'ymin', type = 'symmetry' /
&boundary set = 'zmin', type = 'symmetry' /
&output status_every = 100000 /
"""
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")


def run(exe, n, ranks, t_end):
    with tempfile.TemporaryDirectory() as wd:
        with open(os.path.join(wd, "deck.nml"), "w") as f:
            f.write(DECK.format(n=n, t_end=t_end))
        cmd = [exe, "deck.nml"] if ranks == 1 else ["mpirun", "-np", str(ranks), exe, "deck.nml"]
        before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
        out = subprocess.run(cmd, cwd=wd, env=ENV, capture_output=True, text=True, check=True)
        rss = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
        m = re.search(r"done, (\d+) cycles,\s+(\S+) s \(\s*(\S+) s of it in dumps\)", out.stdout)
        cycles, wall, dumps = int(m.group(1)), float(m.group(2)), float(m.group(3))
        return cycles, wall - dumps, rss if rss > before else None


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exe", default=os.path.join(os.path.dirname(__file__), "..", "build",
                                                  "impact3d"))
    p.add_argument("--sizes", type=int, nargs="+", default=[30, 60])
    p.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    p.add_argument("--t-end", type=float, default=0.3)
    p.add_argument("--out")
    args = p.parse_args()
    exe = os.path.abspath(args.exe)
    lines = ["| zones | ranks | cycles | loop s | ns/zone-cycle | zone-cycles/s | peak RSS MB |",
             "|---|---|---|---|---|---|---|"]
    for n in args.sizes:
        for r in args.ranks:
            cycles, wall, rss = run(exe, n, r, args.t_end)
            zones = n ** 3
            ns = wall * r / (zones * cycles) * 1e9
            rate = zones * cycles / wall
            mem = "%.1f" % (rss / 1024.0) if (rss and r == 1) else "-"
            lines.append("| %d^3 | %d | %d | %.2f | %.0f | %.3g | %s |"
                         % (n, r, cycles, wall, ns, rate, mem))
            print(lines[-1], flush=True)
    text = "\n".join(lines) + "\n"
    if args.out:
        with open(args.out, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
