"""A run against a reference run of the same physics (docs/problems.md,
sections C and D).

  mirror --deck D --reference WALL --axis z --tol T [--sym-tol S --all-dumps
         --energy-tol E --momentum-tol M --momentum-axes z --pair NAME]
      a body and its mirror image through contact against the body on the
      rigid wall: see cmd_mirror
  relative --deck D --reference R --problem P --key K --tol T [--max KEY=V]
           [--min KEY=V] [--pair NAME] [--energy-tol E]
           [--booked-pair NAME --momentum-tol M]
           [--radial-penetration INNER OUTER RADIUS MAX]
      the contact run's K within (1 + T) of the reference's; optionally the
      energy balance, the momentum the pair books and the penetration across
      a curved interface
"""
import os

import numpy as np

from impact3d_tools import dump, radial

from checks.common import (add_bounds, add_problem, add_reference, check, check_bounds,
                           compare_values, dumps as dumps_of, final_dump, read_history,
                           report_contact_energy, run_pair)


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
    wd_ref = os.path.join(args.workdir, "wall")
    wd = os.path.join(args.workdir, "mirror")
    ok, out = run_pair(args, wd_ref, wd, "wall", "mirror")
    if not ok:
        return
    sym_tol = args.tol if args.sym_tol is None else args.sym_tol
    if args.all_dumps:
        names = sorted(set(os.path.basename(f) for f in dumps_of(wd_ref))
                       & set(os.path.basename(f) for f in dumps_of(wd)))
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
    moved = np.abs(x0 - dump.load(dumps_of(wd_ref)[0])["coordinates"]).max() / size
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


def cmd_relative(args):
    """A contact run against its single-mesh reference (docs/problems.md, section D): the
    --key of compare.py (--problem) for --deck is at most (1 + --tol) times
    the reference's (--reference); --max / --min bound other keys of the
    contact run; with --pair, the interface is in contact on every cycle and
    never releases; with --energy-tol, max |energy_error| (the balance that
    books the contact work) is at most that; with --booked-pair and
    --momentum-tol, the momentum that pair's forces added over the run (sum of
    its dmom columns) is at most that fraction of the largest |momentum|."""
    wd_ref = os.path.join(args.workdir, "reference")
    wd = os.path.join(args.workdir, "contact")
    ok, out = run_pair(args, wd_ref, wd, "reference", "contact")
    if not ok:
        return
    rc, ref, err = compare_values(final_dump(wd_ref), args.problem, args.compare_args)
    rc2, got, err2 = compare_values(final_dump(wd), args.problem, args.compare_args)
    check("compare.py runs", rc == 0 and rc2 == 0, (err + err2)[-2000:])
    a, b = got.get(args.key, float("nan")), ref.get(args.key, float("nan"))
    check("%s = %.4e vs reference %.4e: ratio %.4f <= %.3f" % (args.key, a, b, a / b,
          1 + args.tol), a <= (1 + args.tol) * b)
    check_bounds(got, args, "contact run: ", ref)
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


def register(sub, common):
    p = sub.add_parser("mirror", parents=[common], help="mirror test against the rigid wall")
    add_reference(p, "the body on the rigid wall")
    p.add_argument("--axis", default="x", help="normal of the mirror plane")
    p.add_argument("--tol", type=float, default=1e-12)
    p.add_argument("--sym-tol", type=float, default=None,
                   help="tolerance of the image's symmetry (default: --tol)")
    p.add_argument("--all-dumps", action="store_true",
                   help="compare every dump of the two runs, not only the final one")
    p.add_argument("--energy-tol", type=float, default=0.0,
                   help="largest |energy_error| of both runs (0: not checked)")
    p.add_argument("--momentum-tol", type=float, default=0.0)
    p.add_argument("--momentum-axes", default="xyz")
    p.add_argument("--pair", default="mid", help="contact pair reported")
    p.set_defaults(func=cmd_mirror)
    p = sub.add_parser("relative", parents=[common], help="contact run against a single mesh")
    add_reference(p, "the single-mesh deck")
    add_problem(p)
    add_bounds(p)
    p.add_argument("--key", default="L1_rho")
    p.add_argument("--tol", type=float, default=1e-12)
    p.add_argument("--pair", default="mid",
                   help="pair in contact on every cycle (none: not checked)")
    p.add_argument("--energy-tol", type=float, default=0.0,
                   help="largest |energy_error| of the contact run (0: not checked)")
    p.add_argument("--booked-pair", default=None,
                   help="with --momentum-tol, check the momentum this contact pair books "
                        "(sum of its dmom columns) against the largest |momentum|")
    p.add_argument("--momentum-tol", type=float, default=0.0)
    p.add_argument("--radial-penetration", nargs=4, metavar=("INNER", "OUTER", "RADIUS", "MAX"),
                   help="in every dump, no node of block INNER on the sphere RADIUS (at "
                        "t = 0) lies more than MAX radially beyond the faceted surface of "
                        "block OUTER (impact3d_tools.radial)")
    p.set_defaults(func=cmd_relative)
