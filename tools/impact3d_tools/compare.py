#!/usr/bin/python3
"""Compare an impact3d dump with the exact solution of a verification problem.

Usage:
    python3 -m impact3d_tools.compare --problem {sod,riemann2,sedov,noh} dump.h5 [--out summary.txt]
               [--time T] [--region MIN MAX] [--block ID ...]
               [--x0 X] [--axis {x,y,z}] [--left RHO U P] [--right RHO U P]
               [--gamma-left G] [--gamma-right G]            (sod, riemann2)
               [--gamma G] [--rho0 R] [--e0 E] [--u0 U]      (sedov, noh)
               [--origin X Y Z] [--shock-threshold R] [--bin-width W]

Problems and defaults (docs/problems.md, section A):
    sod       Riemann problem along x: left (rho, u, p) = (1, 0, 1), right
              (0.125, 0, 0.1), interface x0 = 0.5, gamma 1.4 on both sides.
    riemann2  the same data with gamma_left = 1.4, gamma_right = 5/3 (the
              two-material Sod of docs/problems.md, D1).
    sedov     spherical blast, gamma 1.4, rho0 1, full-sphere energy
              E0 = 0.851072 (shock at r = 1 at t = 1), origin (0, 0, 0).
    noh       spherical implosion, gamma 5/3, rho0 1, u0 1 inward.

The exact solution is evaluated at the zone centroids (mean of the 8 node
coordinates): the centroid x (or --axis) for the Riemann problems, the
centroid radius about --origin for sedov and noh.  The time is the dump's
`time` attribute unless --time is given.

Error norms, over the zones kept by --block and --region (a window on x for
the Riemann problems, on the radius otherwise), for f in rho, p, u, e:
    L1_f     = sum V |f - f_ex| / sum V      (L1 per unit length/volume)
    L1mass_f = sum m |f - f_ex| / sum m      (mass-weighted L1)
    L1rel_f  = sum V |f - f_ex| / sum V |f_ex|
    L2_f     = sqrt(sum V (f - f_ex)^2 / sum V)
    Linf_f   = max |f - f_ex|
with V, m the zone volume and mass.  For u the pointwise error is the
length of the vector difference |v - u_ex n|, v the zone velocity (mean of
its node velocities), n the unit vector of the problem (the axis, or the
radial direction): in 1D it is |u - u_ex|, and transverse or non-radial
velocity counts as error.  Zones where the exact value is not finite (the
Sedov centre for e) are left out and counted in nzone_nonfinite.  The exact
Sedov e grows without bound towards the centre (rho -> 0 at finite p), so
whole-domain e norms for sedov are dominated by the innermost zones; use
--region (e.g. 0.3 1.2) for a meaningful e error.

Shock position (definitions, each comment at its function):
    sod/riemann2  density crosses the mid value between the exact post-shock
                  and pre-shock densities, scanning the x-profile from the
                  undisturbed end (shock_x for a right-facing shock,
                  shock_left_x for a left-facing one).
    sedov         mass-weighted mean radius of the zones denser than
                  --shock-threshold * rho0 (default 2), rescaled by the same
                  functional of the exact profile (shock_r); also the radius
                  of the densest zone (shock_r_peak).
    noh           radius where the radially binned density falls through the
                  mid value between the exact post-shock density and the
                  exact pre-shock density at the shock, scanning from outside.

The summary is `key = value` lines, printed and written to --out.
"""

import argparse
import sys

import numpy as np

from impact3d_tools import dump
from impact3d_tools.exact import noh as exact_noh
from impact3d_tools.exact import riemann as exact_riemann
from impact3d_tools.exact import sedov as exact_sedov
from impact3d_tools.measures import error_norms, noh_shock, riemann_shocks, sedov_shock

PROBLEMS = ("sod", "riemann2", "sedov", "noh")
AXES = {"x": 0, "y": 1, "z": 2}

DEFAULTS = {
    "sod": {"left": (1.0, 0.0, 1.0), "right": (0.125, 0.0, 0.1),
            "gamma_left": 1.4, "gamma_right": 1.4, "x0": 0.5},
    "riemann2": {"left": (1.0, 0.0, 1.0), "right": (0.125, 0.0, 0.1),
                 "gamma_left": 1.4, "gamma_right": 5.0 / 3.0, "x0": 0.5},
    "sedov": {"gamma": 1.4, "rho0": 1.0, "e0": 0.851072},
    "noh": {"gamma": 5.0 / 3.0, "rho0": 1.0, "u0": 1.0},
}


def add_problem_arguments(parser):
    """Options shared by compare.py and plot_profiles.py."""
    parser.add_argument("--problem", required=True, choices=PROBLEMS)
    parser.add_argument("dump", help="impact3d HDF5 dump")
    parser.add_argument("--time", type=float, default=None,
                        help="problem time (default: the dump's time attribute)")
    parser.add_argument("--block", type=int, action="append", default=None,
                        help="use only zones of this block id (repeatable)")
    parser.add_argument("--region", type=float, nargs=2, metavar=("MIN", "MAX"),
                        default=None, help="window on x (Riemann) or radius "
                        "(sedov, noh) for the error norms")
    group = parser.add_argument_group("Riemann problems (sod, riemann2)")
    group.add_argument("--x0", type=float, default=None, help="interface position")
    group.add_argument("--axis", choices=sorted(AXES), default="x")
    group.add_argument("--left", type=float, nargs=3, metavar=("RHO", "U", "P"))
    group.add_argument("--right", type=float, nargs=3, metavar=("RHO", "U", "P"))
    group.add_argument("--gamma-left", type=float, default=None)
    group.add_argument("--gamma-right", type=float, default=None)
    group = parser.add_argument_group("spherical problems (sedov, noh)")
    group.add_argument("--gamma", type=float, default=None)
    group.add_argument("--rho0", type=float, default=None)
    group.add_argument("--e0", type=float, default=None,
                       help="sedov: full-sphere blast energy")
    group.add_argument("--u0", type=float, default=None, help="noh: inflow speed")
    group.add_argument("--origin", type=float, nargs=3, default=(0.0, 0.0, 0.0),
                       metavar=("X", "Y", "Z"))
    group.add_argument("--shock-threshold", type=float, default=2.0,
                       help="sedov: density ratio rho/rho0 for the shock estimator")
    group.add_argument("--bin-width", type=float, default=None,
                       help="noh: radial bin width for the profile "
                       "(default half the median zone size)")


def fill_defaults(args):
    """Replace unset problem options by the problem's defaults."""
    for key, value in DEFAULTS[args.problem].items():
        if getattr(args, key, None) is None:
            setattr(args, key, value)
    return args


class Setup:
    """The exact solution of the chosen problem and how to sample it.

    planar: True for the Riemann problems (coordinate = x along --axis).
    exact(coord) -> rho, u, p, e at time self.time.
    params: problem data for the summary.
    """

    def __init__(self, args, time):
        self.problem = args.problem
        self.time = time
        self.planar = args.problem in ("sod", "riemann2")
        if self.planar:
            (rl, ul, pl), (rr, ur, pr) = args.left, args.right
            self.riemann = exact_riemann.RiemannProblem(
                rl, ul, pl, args.gamma_left, rr, ur, pr, args.gamma_right)
            self.x0 = args.x0
            self.params = {"gamma_left": args.gamma_left, "gamma_right": args.gamma_right,
                           "x0": args.x0, "pstar": self.riemann.pstar,
                           "ustar": self.riemann.ustar}
        elif args.problem == "sedov":
            self.sedov = exact_sedov.Sedov(args.gamma)
            self.gamma, self.rho0, self.e0 = args.gamma, args.rho0, args.e0
            self.params = {"gamma": args.gamma, "rho0": args.rho0, "e0": args.e0,
                           "alpha": self.sedov.alpha}
        else:
            self.gamma, self.rho0, self.u0 = args.gamma, args.rho0, args.u0
            self.params = {"gamma": args.gamma, "rho0": args.rho0, "u0": args.u0}

    def exact(self, coord):
        """rho, u, p, e of the exact solution at coordinates coord."""
        if self.planar:
            return self.riemann.sample(coord, self.time, self.x0)
        if self.problem == "sedov":
            return self.sedov.solution(coord, self.time, self.e0, self.rho0)
        return exact_noh.solution(coord, self.time, self.gamma, self.rho0, self.u0)


def zone_state(data, args):
    """Numerical zone state, coordinate and problem direction.

    Returns a dict: coord (x or radius), direction (nzone x 3 unit vectors),
    rho, p, e, velocity (nzone x 3), u (velocity along direction), volume,
    mass, keep (zones selected by --block).
    """
    centroids = dump.zone_centroids(data)
    nzone = centroids.shape[0]
    if args.problem in ("sod", "riemann2"):
        axis = AXES[args.axis]
        coord = centroids[:, axis]
        direction = np.zeros((nzone, 3))
        direction[:, axis] = 1.0
    else:
        offset = centroids - np.asarray(args.origin, dtype=float)
        coord = np.linalg.norm(offset, axis=1)
        direction = offset / np.where(coord > 0.0, coord, 1.0)[:, None]
    velocity = dump.zone_velocity(data)
    keep = np.ones(nzone, dtype=bool)
    if args.block:
        keep = np.isin(data["block"], args.block)
    return {"coord": coord, "direction": direction, "rho": data["density"],
            "p": data["pressure"], "e": data["specific_internal_energy"],
            "velocity": velocity, "u": np.sum(velocity * direction, axis=1),
            "volume": data["volume"], "mass": data["mass"], "keep": keep}


def summarize(args):
    """Compute the summary dict for parsed arguments."""
    fill_defaults(args)
    data = dump.load(args.dump)
    time = args.time if args.time is not None else dump.problem_time(data)
    setup = Setup(args, time)
    state = zone_state(data, args)
    mask = state["keep"].copy()
    if args.region is not None:
        lo, hi = args.region
        mask &= (state["coord"] >= lo) & (state["coord"] <= hi)
    summary = {"problem": args.problem, "dump": args.dump, "time": time,
               "cycle": data["attrs"].get("cycle", -1),
               "nzone": int(state["coord"].size), "nzone_used": int(np.count_nonzero(mask))}
    if args.region is not None:
        summary["region_min"], summary["region_max"] = args.region
    summary.update(setup.params)
    exact = setup.exact(state["coord"])
    summary.update(error_norms(state, exact, mask))
    if setup.planar:
        summary.update(riemann_shocks(state, setup))
    elif args.problem == "sedov":
        summary.update(sedov_shock(state, setup, args.shock_threshold))
    else:
        summary.update(noh_shock(state, setup, args.bin_width))
    return summary


def format_summary(summary):
    """`key = value` lines; floats in %.6e."""
    lines = []
    for key, value in summary.items():
        if isinstance(value, (float, np.floating)):
            text = f"{float(value):.6e}"
        else:
            text = str(value)
        lines.append(f"{key} = {text}")
    return "\n".join(lines) + "\n"


def read_summary(path):
    """Read a `key = value` summary back into a dict (floats where possible)."""
    out = {}
    with open(path, encoding="utf-8") as handle:
        for line in handle:
            if "=" not in line or line.lstrip().startswith("#"):
                continue
            key, value = (part.strip() for part in line.split("=", 1))
            try:
                out[key] = float(value)
            except ValueError:
                out[key] = value
    return out


def summary_values(argv):
    """Run main(argv) in this process and read its printed summary back, as
    the `key = value` lines a caller of the command would (floats in %.6e):
    (exit code, {key: float}, error text)."""
    import contextlib
    import io
    import traceback
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(argv)
        except SystemExit as stop:
            code = stop.code if isinstance(stop.code, int) else 1
        except Exception:  # a failing comparison is reported, not raised
            traceback.print_exc()
            code = 1
    values = {}
    for line in out.getvalue().splitlines():
        if "=" in line:
            k, v = line.split("=", 1)
            try:
                values[k.strip()] = float(v)
            except ValueError:
                pass
    return code, values, err.getvalue()


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_problem_arguments(parser)
    parser.add_argument("--out", default=None, help="write the summary here too")
    args = parser.parse_args(argv)
    try:
        summary = summarize(args)
    except (OSError, ValueError, KeyError) as error:
        print(f"compare.py: {args.dump}: {error}", file=sys.stderr)
        return 1
    text = format_summary(summary)
    sys.stdout.write(text)
    if args.out:
        with open(args.out, "w", encoding="utf-8") as handle:
            handle.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
