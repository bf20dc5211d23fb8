"""Contact and friction against exact or physical values (docs/problems.md,
section C).

  bars --deck D --tol T --area A --duration 2L/c --stress S --v-left VL
       --v-right VR --v-interface VI --final-left FL --final-right FR
       [--momentum-tol M] [--pair NAME]
      two elastic bars meeting through a contact pair: see cmd_bars
  patch --deck D --range A B --target S --tol T
      the stress a planar wave carries through non-matching meshes is uniform
  impact --deck D --pair NAME [NAME ...] --tol T --max-pen P [--momentum-tol M --momentum-axes z]
         [--audit [--audit-after T]] [--max-audit-a A] [--max-audit-b B] [--max-work W]
      two bodies in contact: energy balance, penetration, momentum; final
      block velocities reported
  slide --deck D --v0 V --friction MU --pressure P --area A --tol T [--pair NAME]
      Coulomb friction: a block pressed on a plane by P over its contact area
      A slides from V: deceleration MU P A / m, stopping time and distance
      within T of the analytic values; friction work = the block's kinetic
      energy; energy balance to round-off
"""

import numpy as np

from impact3d_tools import dump

from checks.common import (add_replace, check, dumps as dumps_of, final_dump, read_history,
                           run_in, variant_deck)


def cmd_bars(args):
    """Two elastic bars meeting through a contact pair (docs/problems.md, section C).

    Left bar (block 1) at --v-left, right bar (block 2) at --v-right, 1D strain.
    Criteria (each within --tol): contact lasts --duration (from the pair's
    active column of the history); the interface stress (pair force / --area)
    over the middle half of the contact equals --stress; the interface nodes
    move at the impedance-matched velocity --v-interface during contact
    (within --tol of |v_left - v_right|: the velocity never reverses); after
    separation each bar's mean velocity is --final-left / --final-right."""
    wd, out = run_in(args, "bars")
    if wd is None:
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
    dumps = sorted(dumps_of(wd))
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


def cmd_patch(args):
    """Patch test (docs/problems.md, section C): after a planar wave crossed a contact
    interface between non-matching meshes, the normal stress sigma_xx of the
    zones with centroid x in --range (behind the front) is uniform across the
    section, (max - min)/|mean| <= --tol, and its mean equals --target within
    --tol (the applied pressure, transmitted through matched impedances)."""
    wd, out = run_in(args, "patch")
    if wd is None:
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


def cmd_impact(args):
    """Bodies in contact through one or more pairs (--pair NAME ...): the
    energy balance closes to --tol; for each pair, the largest penetration
    stays below --max-pen; the total momentum stays within --momentum-tol of
    its initial value (relative to its norm; give it for DLM, exact);
    reports the contact work and the final mass-weighted velocity of each
    block. With --audit: at every audit (after time --audit-after) no node
    of either surface of any pair beyond its tolerance and none unheld; with --max-audit-a /
    --max-audit-b: the deepest node of surface a / b by the audit at most
    that; with --max-work: each pair's contact work at most that fraction of
    the initial energy at every row. --replace OLD NEW edits the deck first."""
    if args.replace:
        args.deck = variant_deck(args)
    wd, out = run_in(args, "impact")
    if wd is None:
        return
    header, rows = read_history(wd)
    e0 = abs(rows[0, header.index("total_energy")])
    worst = np.abs(rows[:, header.index("energy_error")]).max()
    check("energy balance |error| %.2e <= %.1e" % (worst, args.tol), worst <= args.tol)
    for pair in args.pair:
        col = lambda name: rows[:, header.index(pair + "_" + name)]
        pen = col("pen_max").max()
        if np.isfinite(args.max_pen):
            check("%s: largest penetration %.3e <= %.3e" % (pair, pen, args.max_pen),
                  pen <= args.max_pen)
        else:
            print("%s: largest penetration %.3e (enforced pairs)" % (pair, pen))
        if args.audit:
            after = rows[:, header.index("time")] > args.audit_after
            for name in ("audit_count_a", "audit_count_b", "unheld"):
                check("%s_%s = 0 at every audit after t = %g (max %g)"
                      % (pair, name, args.audit_after, col(name)[after].max()),
                      np.all(col(name)[after] == 0))
        for side, bound in (("a", args.max_audit_a), ("b", args.max_audit_b)):
            if bound is None:
                continue
            deepest = col("audit_pen_max_" + side).max()
            check("%s: deepest node of surface %s by the audit %.3e <= %.3e"
                  % (pair, side, deepest, bound), deepest <= bound)
        if args.max_work is not None:
            work = col("work").max() / e0
            check("%s: contact work <= %.1e E0 at every row (max %.2e E0)"
                  % (pair, args.max_work, work), work <= args.max_work)
        else:
            print("%s: contact work max %.3e, final %.3e of E0"
                  % (pair, col("work").max() / e0, col("work")[-1] / e0))
    p = rows[:, [header.index("momentum_" + c) for c in args.momentum_axes]]
    drift = np.linalg.norm(p - p[0], axis=1).max() / max(np.linalg.norm(p[0]), 1e-300)
    if args.momentum_tol > 0.0:
        check("momentum drift (%s) %.2e <= %.1e" % (args.momentum_axes, drift,
                                                    args.momentum_tol),
              drift <= args.momentum_tol)
    else:
        print("momentum drift %.2e of the initial momentum" % drift)
    active = rows[:, header.index(args.pair[0] + "_active")] > 0
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
    wd, out = run_in(args, "slide")
    if wd is None:
        return
    header, rows = read_history(wd)
    t = rows[:, header.index("time")]
    dumps = sorted(dumps_of(wd))
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


def register(sub, common):
    p = sub.add_parser("bars", parents=[common], help="two bars meeting through contact")
    p.add_argument("--pair", default="mid", help="contact pair name")
    p.add_argument("--tol", type=float, default=1e-12)
    p.add_argument("--area", type=float, default=1.0, help="bar cross-section")
    p.add_argument("--duration", type=float, default=0.0, help="contact time (0: not checked)")
    p.add_argument("--stress", type=float, required=True, help="interface stress")
    p.add_argument("--v-left", type=float, default=0.0)
    p.add_argument("--v-right", type=float, default=0.0)
    p.add_argument("--v-interface", type=float, default=0.0)
    p.add_argument("--final-left", type=float)
    p.add_argument("--final-right", type=float)
    p.add_argument("--momentum-tol", type=float, default=0.0)
    p.set_defaults(func=cmd_bars)
    p = sub.add_parser("patch", parents=[common], help="patch test on non-matching meshes")
    p.add_argument("--range", type=float, nargs=2, required=True, help="window on x")
    p.add_argument("--target", type=float, required=True, help="transmitted sigma_xx")
    p.add_argument("--tol", type=float, default=1e-12)
    p.set_defaults(func=cmd_patch)
    p = sub.add_parser("impact", parents=[common], help="two bodies impacting through contact")
    p.add_argument("--pair", nargs="+", default=["mid"], help="contact pair name(s)")
    p.add_argument("--tol", type=float, default=1e-12, help="energy balance")
    p.add_argument("--max-pen", type=float, default=float("inf"))
    p.add_argument("--audit", action="store_true",
                   help="no node beyond its tolerance and none unheld at any audit")
    p.add_argument("--audit-after", type=float, default=-1.0,
                   help="with --audit: only the audits after this time (the end of "
                        "an impact's transient)")
    p.add_argument("--max-audit-a", type=float, default=None,
                   help="bound on the audit's deepest node of surface a")
    p.add_argument("--max-audit-b", type=float, default=None,
                   help="bound on the audit's deepest node of surface b")
    p.add_argument("--max-work", type=float, default=None,
                   help="bound on the interface's contact work / initial energy")
    p.add_argument("--momentum-tol", type=float, default=0.0)
    add_replace(p)
    p.add_argument("--momentum-axes", default="xyz",
                   help="the momentum components no boundary acts on (a symmetry "
                        "plane's reaction changes the component along its normal)")
    p.set_defaults(func=cmd_impact)
    p = sub.add_parser("slide", parents=[common], help="Coulomb friction: a sliding block")
    p.add_argument("--v0", type=float, required=True, help="the block's initial speed along x")
    p.add_argument("--friction", type=float, required=True, help="the Coulomb coefficient")
    p.add_argument("--pressure", type=float, required=True, help="the applied pressure")
    p.add_argument("--area", type=float, default=1.0, help="the block's contact area")
    p.add_argument("--tol", type=float, default=1e-12)
    p.add_argument("--pair", default="mid", help="contact pair name (none: the wall)")
    p.set_defaults(func=cmd_slide)
