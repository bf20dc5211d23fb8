"""The run's own bookkeeping and its ways of ending.

  energy --deck D --np N --tol T
      max |relative total-energy error| in history.txt <= T
  failure --deck D --np N --expect volume|nan|dt|any
      exit code 2, the message names zone/node, position, cycle and time, and
      a final *_failed.h5 dump exists
  stability --deck D --np N
      runs to the end (exit 0) or stops through the failure path (exit 2 with
      its message and final dump); no dump holds a NaN or infinity
"""
import glob
import os
import re

import numpy as np

from impact3d_tools import dump, history

from checks.common import check, run, run_in


def cmd_energy(args):
    wd, out = run_in(args, "energy")
    if wd is None:
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
    if args.zone_block is not None and m:
        # The dt_min stop names the controlling zone's block, material,
        # compression rho/rho0 and sound speed (issue 34).
        z = re.search(r"^  zone (\d+): block '([^']*)', material '([^']*)', compression "
                      r"rho/rho0 = (\S+) \(rho = (\S+)\), sound speed (\S+) ", err, re.M)
        check("the zone line names block, material, rho/rho0 and sound speed", z is not None,
              err[-2000:])
        if z:
            check("it is the zone of the stop", z.group(1) == m.group(1),
                  f"{z.group(1)} vs {m.group(1)}")
            check(f"block '{args.zone_block}', material '{args.zone_material}'",
                  (z.group(2), z.group(3)) == (args.zone_block, args.zone_material),
                  z.group(0))
            ratio = float(z.group(4))
            check(f"rho/rho0 = {ratio} is {args.zone_compression} to 1e-4",
                  abs(ratio - args.zone_compression) <= 1e-4 * args.zone_compression,
                  z.group(0))
            check("sound speed > 0", float(z.group(6)) > 0.0, z.group(0))
    failed = glob.glob(os.path.join(wd, "*_failed.h5"))
    check("a final dump was written", len(failed) == 1, str(failed))
    if failed and m:
        d = dump.load(failed[0])
        check("final dump is at the failing cycle", int(d["attrs"]["cycle"]) == int(m.group(5)))


def cmd_stability(args):
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


def register(sub, common):
    p = sub.add_parser("energy", parents=[common], help="energy balance to --tol")
    p.add_argument("--tol", type=float, default=1e-12)
    p.set_defaults(func=cmd_energy)
    p = sub.add_parser("failure", parents=[common], help="the failure path")
    p.add_argument("--expect", choices=["volume", "nan", "dt", "any"], default="volume")
    p.add_argument("--zone-block", help="dt_min stop: the zone line's block")
    p.add_argument("--zone-material", help="dt_min stop: the zone line's material")
    p.add_argument("--zone-compression", type=float,
                   help="dt_min stop: the zone line's rho/rho0 (to 1e-4)")
    p.set_defaults(func=cmd_failure)
    p = sub.add_parser("stability", parents=[common], help="ends cleanly, no NaN in a dump")
    p.set_defaults(func=cmd_stability)
