"""Verification against exact solutions (docs/verification.md), through
impact3d_tools.compare (its summary's `key = value` values).

  compare --deck D --np N --problem P --max KEY=VALUE ... --min KEY=VALUE ...
      run, compare the final dump with the exact solution and check the
      summary values
  convergence --deck TEMPLATE --sizes 100 200 400 --problem P --key L1_rho
              --min-rate R [--max-at SIZE=VALUE]
      run the template ({n} = zones, {h} = 1/n) at each size; observed rates
      log(e(n)/e(m))/log(m/n) >= R
  interface --deck D --np N --zones-tol 2 [--max KEY=VALUE] [compare args]
      two-block Riemann problem: the material interface and the shock within
      2 local zone widths of exact
  window --deck D --np N --axis x --range A B --target 4 --tol 0.05
      zone densities with centroid in [A, B] all within tol (relative) of target
  versus --deck D --reference R --np N --problem P --closer KEY ... --higher KEY ...
      run both decks; the deck's |KEY| below the reference's (--closer) or
      its KEY above the reference's (--higher): a claim that one option
      beats another on the same problem and mesh, with no bound taken from
      a measurement
"""
import os

import numpy as np

from impact3d_tools import dump

from checks.common import (add_bounds, add_problem, check, check_bounds, compare_values,
                           final_dump, run, run_in, run_pair)


def cmd_compare(args):
    wd, out = run_in(args, "compare")
    if wd is None:
        return
    rc, values, err = compare_values(final_dump(wd), args.problem,
                                     args.compare_args + ["--out", os.path.join(wd, "summary.txt")])
    check("compare.py runs", rc == 0, err[-2000:])
    check_bounds(values, args)


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
    wd, out = run_in(args, "window", "run exits 0 (no tangling)")
    if wd is None:
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
    wd, out = run_in(args, "interface")
    if wd is None:
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
    check_bounds(values, args)


def cmd_versus(args):
    ref_dir = os.path.join(args.workdir, "reference")
    run_dir = os.path.join(args.workdir, "run")
    ok, _ = run_pair(args, ref_dir, run_dir)
    if not ok:
        return
    rc_r, ref, err_r = compare_values(final_dump(ref_dir), args.problem, args.compare_args)
    rc, got, err = compare_values(final_dump(run_dir), args.problem, args.compare_args)
    check("compare.py runs on both", rc == 0 and rc_r == 0, (err + err_r)[-2000:])
    check_bounds(got, args, reference=ref)
    nan = float("nan")
    for k in args.closer or []:
        a, b = got.get(k, nan), ref.get(k, nan)
        check("|%s| = %.4e < the reference's %.4e" % (k, abs(a), abs(b)), abs(a) < abs(b))
    for k in args.higher or []:
        a, b = got.get(k, nan), ref.get(k, nan)
        check("%s = %.4e > the reference's %.4e" % (k, a, b), a > b)


def register(sub, common):
    p = sub.add_parser("compare", parents=[common], help="summary values against exact")
    add_problem(p)
    add_bounds(p)
    p.set_defaults(func=cmd_compare)
    p = sub.add_parser("convergence", parents=[common], help="observed convergence rate")
    add_problem(p)
    p.add_argument("--sizes", type=int, nargs="+", default=[100, 200, 400])
    p.add_argument("--key", default="L1_rho")
    p.add_argument("--min-rate", type=float, default=0.8)
    p.add_argument("--max-at", action="append", metavar="SIZE=VALUE")
    p.set_defaults(func=cmd_convergence)
    p = sub.add_parser("interface", parents=[common], help="two-material Riemann problem")
    add_problem(p)
    p.add_argument("--zones-tol", type=float, default=2.0)
    p.add_argument("--max", action="append", metavar="KEY=VALUE")
    p.set_defaults(func=cmd_interface)
    p = sub.add_parser("window", parents=[common], help="density in a window against a target")
    p.add_argument("--axis", default="x")
    p.add_argument("--range", type=float, nargs=2, required=True)
    p.add_argument("--target", type=float, required=True)
    p.add_argument("--tol", type=float, default=1e-12)
    p.set_defaults(func=cmd_window)
    p = sub.add_parser("versus", parents=[common], help="one option beats another")
    add_problem(p)
    add_bounds(p)
    p.add_argument("--reference", required=True, help="the deck to beat")
    p.add_argument("--closer", action="append", metavar="KEY",
                   help="the deck's |KEY| is below the reference's")
    p.add_argument("--higher", action="append", metavar="KEY",
                   help="the deck's KEY is above the reference's")
    p.set_defaults(func=cmd_versus)
