"""Solid mechanics against exact or analytic values.

  wavefront --deck D --target C --target-velocity UP --origin X0 --tol T
      a planar front (|u| = UP/2) moves at C within T
  rebound --deck D --target 2L/c --tol T
      bar on a rigid wall: momentum reversed within T, contact (momentum
      changing) lasts 2L/c within T
  twowave --deck D --target C_L --hel HEL --c0 C0 --s1 S --rho0 R
          --target-velocity UP --origin X0
      elastic precursor and plastic wave of a piston-driven elastic-plastic wave
  shell_stop --deck D --origin R0 [--target R | --reference SINGLE] --tol T
      imploding shell: where the inner surface stops
  shape --deck D --reference R --tol T
      Taylor rod: final length and foot diameter of D within T (relative) of R's
"""
import os

import numpy as np

from impact3d_tools import dump
from impact3d_tools.exact import verney
from impact3d_tools.shapes import inner_radius_history, rod_shape

from checks.common import (add_reference, check, final_dump, read_history,
                           report_contact_energy, run, run_in, run_pair)


def cmd_wavefront(args):
    """Speed of a planar front: where the x velocity crosses half the piston speed."""
    wd, out = run_in(args, "wavefront")
    if wd is None:
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
    wd, out = run_in(args, "rebound")
    if wd is None:
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


def cmd_twowave(args):
    """Elastic-plastic piston problem: elastic precursor and plastic wave.

    --target is the longitudinal speed c_L, --hel the 1D-strain Hugoniot
    elastic limit (stress), --c0 and --s1 the Hugoniot fit, --rho0 the density,
    --target-velocity the piston speed; the run starts at t = 0 with the piston
    at --origin."""
    wd, out = run_in(args, "twowave")
    if wd is None:
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
    target = args.target
    if args.reference:
        wd_ref = os.path.join(args.workdir, "reference")
        code, out, err = run(args, args.np, wd_ref, args.reference)
        check("reference run exits 0", code == 0, err[-2000:])
        if code != 0:
            return
        target = min(inner_radius_history(wd_ref, args.origin), key=lambda h: h[1])[1]
        print("  reference (single shell) stops at r = %.4f" % target)
    wd, out = run_in(args, "shell")
    if wd is None:
        return
    history = inner_radius_history(wd, args.origin)
    t_stop, r_stop = min(history, key=lambda h: h[1])
    print("  inner radius history: " + ", ".join("%.0f:%.3f" % h for h in history))
    check("inner surface stops at r = %.4f (t = %.1f) vs %.4f within %.2f"
          % (r_stop, t_stop, target, args.tol), abs(r_stop - target) <= args.tol)
    a_stop, t_end, a, t = verney.verney()
    times = np.array([h[0] for h in history])
    radii = np.array([h[1] for h in history])
    exact = verney.radius_at(times, a, t, a_stop, t_end)
    worst = float(np.max(np.abs(radii / exact - 1.0)))
    check("inner radius history within 2%% of the rigid-plastic energy balance (worst %.2f%%)"
          % (100 * worst), worst <= 0.02)
    if args.reference:
        report_contact_energy(wd)


def cmd_shape(args):
    """Taylor rods: the final length L and foot diameter D of --deck are within
    --tol (relative) of those of --reference."""
    wd_ref = os.path.join(args.workdir, "reference")
    wd = os.path.join(args.workdir, "run")
    ok, out = run_pair(args, wd_ref, wd)
    if not ok:
        return
    lr, dr = rod_shape(final_dump(wd_ref))
    l, d = rod_shape(final_dump(wd))
    check("final length %.4f vs reference %.4f: %+.2f%% within %.1f%%"
          % (l, lr, 100 * (l / lr - 1), 100 * args.tol), abs(l / lr - 1) <= args.tol)
    check("foot diameter %.4f vs reference %.4f: %+.2f%% within %.1f%%"
          % (d, dr, 100 * (d / dr - 1), 100 * args.tol), abs(d / dr - 1) <= args.tol)
    report_contact_energy(wd)
    print(out.strip().splitlines()[-2] if out.strip() else "")


def register(sub, common):
    p = sub.add_parser("wavefront", parents=[common], help="speed of a planar front")
    p.add_argument("--target", type=float, required=True, help="expected front speed")
    p.add_argument("--target-velocity", type=float, default=0.0, help="piston speed")
    p.add_argument("--origin", type=float, default=0.0, help="front position at t = 0")
    p.add_argument("--tol", type=float, default=1e-12)
    p.set_defaults(func=cmd_wavefront)
    p = sub.add_parser("rebound", parents=[common], help="bar rebounding from a rigid wall")
    p.add_argument("--target", type=float, required=True, help="contact time 2L/c")
    p.add_argument("--tol", type=float, default=1e-12)
    p.set_defaults(func=cmd_rebound)
    p = sub.add_parser("twowave", parents=[common], help="elastic precursor and plastic wave")
    p.add_argument("--target", type=float, required=True, help="longitudinal speed c_L")
    p.add_argument("--target-velocity", type=float, default=0.0, help="piston speed")
    p.add_argument("--origin", type=float, default=0.0, help="piston position at t = 0")
    for name in ("--hel", "--c0", "--s1", "--rho0"):
        p.add_argument(name, type=float, required=True)
    p.set_defaults(func=cmd_twowave)
    p = sub.add_parser("shell_stop", parents=[common], help="where an imploding shell stops")
    p.add_argument("--origin", type=float, default=0.0, help="initial inner radius")
    p.add_argument("--target", type=float, help="stopping radius (without --reference)")
    add_reference(p, "single-shell deck whose stopping radius is the target", required=False)
    p.add_argument("--tol", type=float, default=1e-12)
    p.set_defaults(func=cmd_shell_stop)
    p = sub.add_parser("shape", parents=[common], help="Taylor rod shape against a reference")
    add_reference(p)
    p.add_argument("--tol", type=float, default=1e-12)
    p.set_defaults(func=cmd_shape)
