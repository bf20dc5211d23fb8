#!/usr/bin/python3
"""No whole-mesh array at set-up: the zones' share of the largest rank's
peak memory does not grow with the total number of zones.

Usage: check.py EXE WORKDIR [--mpiexec mpirun]

The weak-scaling Sedov deck (tools/impact3d_tools/weak.py: a box stacked
along z, K^3 zones per rank, about four cycles, a dump every two cycles and
the final one) runs at K = 40 and K = 8 on 1 and on 4 ranks. The zones'
share at N ranks is S(N) = peak(K = 40) - peak(K = 8) of the largest rank
(VmHWM over the whole run, set-up and dumps included; the difference cancels
the executable, the libraries and Open MPI's own buffers, which do not
depend on the zones).

Criterion (from the issue's acceptance, not from a measurement):
  S(4) <= 1.25 S(1). Each rank of the 4-rank run owns 40^3 zones as the
  1-rank run does; what it holds more is its ghost layer (a part with two
  neighbours in this column has at most 2 x 40^2 ghost zones, 5% of 40^3),
  the partition's imbalance (PT-Scotch is asked for 3%), and its halo and
  migration buffers. 25% bounds those with room. A rank holding arrays over
  the whole mesh (4 x 40^3 zones) fails it: the code before the distributed
  set-up had rank 0 at about 250 B per zone of the whole problem, which alone
  adds 0.75 x 64,000 x 250 B = 12 MB on top of a share of about 50 MB.
"""

import argparse
import os
import sys

from impact3d_tools.weak import run_stack

BOUND = 1.25


def main():
    p = argparse.ArgumentParser()
    p.add_argument("exe")
    p.add_argument("workdir")
    p.add_argument("--mpiexec", default="mpirun")
    args = p.parse_args()
    peak = {}
    for n in (1, 4):
        for k in (8, 40):
            code, rep, out = run_stack(os.path.abspath(args.exe), k, n,
                                       os.path.join(args.workdir, f"k{k}_np{n}"), args.mpiexec)
            if code != 0 or "rss_largest" not in rep:
                print(out[-3000:])
                print(f"FAIL run K={k} N={n}: exit {code}")
                return 1
            peak[(k, n)] = rep["rss_largest"]
            print(f"K={k:2d} N={n}: largest rank peak {rep['rss_largest']:.1f} MB "
                  f"(rank 0 {rep['rss_rank0']:.1f}, median {rep['rss_median']:.1f})")
    share = {n: peak[(40, n)] - peak[(8, n)] for n in (1, 4)}
    ratio = share[4] / share[1]
    ok = ratio <= BOUND
    print(f"{'PASS' if ok else 'FAIL'} zones' share: S(1) = {share[1]:.1f} MB, "
          f"S(4) = {share[4]:.1f} MB, S(4)/S(1) = {ratio:.3f} (bound {BOUND})")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
