#!/usr/bin/python3
"""Compare an impact3d dump with the exact solution of a verification problem.

Usage:
    compare.py --problem {sod,riemann2,sedov,noh} dump.h5 [--out summary.txt]
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
import math
import sys

import numpy as np


from impact3d_tools import dump  # noqa: E402
import exact_noh  # noqa: E402
import exact_riemann  # noqa: E402
import exact_sedov  # noqa: E402

PROBLEMS = ("sod", "riemann2", "sedov", "noh")
FIELDS = ("rho", "p", "u", "e")
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


def error_norms(state, exact, mask):
    """L1, L1mass, L1rel, L2, Linf of rho, p, u, e over the zones in mask."""
    rho_ex, u_ex, p_ex, e_ex = exact
    reference = {"rho": rho_ex, "p": p_ex, "u": u_ex, "e": e_ex}
    finite = np.ones_like(mask)
    for value in reference.values():
        finite &= np.isfinite(value)
    use = mask & finite
    out = {"nzone_nonfinite": int(np.count_nonzero(mask & ~finite))}
    volume, mass = state["volume"][use], state["mass"][use]
    for name in FIELDS:
        if name == "u":
            diff = np.linalg.norm(state["velocity"][use]
                                  - u_ex[use, None] * state["direction"][use], axis=1)
        else:
            diff = np.abs(state[name][use] - reference[name][use])
        if not np.any(use):
            for norm in ("L1", "L1mass", "L1rel", "L2", "Linf"):
                out[f"{norm}_{name}"] = math.nan
            continue
        scale = np.sum(volume * np.abs(reference[name][use]))
        out[f"L1_{name}"] = np.sum(volume * diff) / np.sum(volume)
        out[f"L1mass_{name}"] = np.sum(mass * diff) / np.sum(mass)
        out[f"L1rel_{name}"] = np.sum(volume * diff) / scale if scale > 0.0 else math.nan
        out[f"L2_{name}"] = math.sqrt(np.sum(volume * diff ** 2) / np.sum(volume))
        out[f"Linf_{name}"] = float(np.max(diff))
    return out


def planar_profile(x, rho, volume):
    """Volume-weighted mean density per column of zones sharing one x.

    Zones whose centroid x differ by less than 1e-6 of the x-range form one
    column (the n x 2 x 2 slabs); the result is sorted by x.
    """
    order = np.argsort(x, kind="stable")
    xs, rs, vs = x[order], rho[order], volume[order]
    tol = 1.0e-6 * max(xs[-1] - xs[0], 1.0e-300)
    starts = np.concatenate(([0], np.nonzero(np.diff(xs) > tol)[0] + 1))
    vsum = np.add.reduceat(vs, starts)
    return (np.add.reduceat(xs * vs, starts) / vsum,
            np.add.reduceat(rs * vs, starts) / vsum)


def crossing(x, values, level, from_right):
    """Position where values first reach level, scanning from one end.

    Starting at the undisturbed end (right end if from_right), find the
    first point with values >= level and interpolate linearly with its
    neighbour on the scanning side.  NaN if there is no crossing.
    """
    if from_right:
        x, values = x[::-1], values[::-1]
    above = np.nonzero(values >= level)[0]
    if above.size == 0 or above[0] == 0:
        return math.nan
    i = above[0]
    x_a, x_b, v_a, v_b = x[i - 1], x[i], values[i - 1], values[i]
    return float(x_a + (level - v_a) * (x_b - x_a) / (v_b - v_a))


def riemann_shocks(state, setup):
    """Shock positions of a Riemann problem (numerical and exact).

    Definition: the shock is where the column-averaged density profile
    crosses the mid value between the exact post-shock density and the
    undisturbed density, found by scanning from the undisturbed end of the
    domain towards the interface (the first crossing met is the shock; the
    contact and fan lie behind it).
    """
    rp = setup.riemann
    keep = state["keep"]
    x, rho = planar_profile(state["coord"][keep], state["rho"][keep],
                            state["volume"][keep])
    waves = rp.wave_positions(setup.time, setup.x0)
    out = {"contact_x_exact": waves["contact"]}
    if rp.right_is_shock:
        level = 0.5 * (rp.rho_star_right + rp.rhoR)
        found = crossing(x, rho, level, from_right=True)
        out.update({"shock_x": found, "shock_x_exact": waves["right_shock"],
                    "shock_x_error": found - waves["right_shock"]})
    if rp.left_is_shock:
        level = 0.5 * (rp.rho_star_left + rp.rhoL)
        found = crossing(x, rho, level, from_right=False)
        out.update({"shock_left_x": found, "shock_left_x_exact": waves["left_shock"],
                    "shock_left_x_error": found - waves["left_shock"]})
    return out


def sedov_dense_mean_radius_exact(setup, threshold):
    """Mass-weighted mean radius of the exact profile where rho > threshold.

    The density rises monotonically from the centre to the shock, so the
    dense region is [r_t, r_s]; r_t by bisection, the two moments by
    Gauss-Legendre quadrature.
    """
    r_s = setup.sedov.shock_radius(setup.time, setup.e0, setup.rho0)
    if threshold >= setup.rho0 * (setup.gamma + 1.0) / (setup.gamma - 1.0):
        return math.nan

    def density(r):
        return setup.sedov.solution(np.atleast_1d(r), setup.time, setup.e0,
                                    setup.rho0)[0]

    lo, hi = 0.0, r_s * (1.0 - 1.0e-14)
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if density(mid)[0] > threshold:
            hi = mid
        else:
            lo = mid
    nodes, weights = np.polynomial.legendre.leggauss(64)
    r = 0.5 * (hi + r_s) + 0.5 * (r_s - hi) * nodes
    w = 0.5 * (r_s - hi) * weights
    rho = density(r)
    return float(np.sum(w * rho * r ** 3) / np.sum(w * rho * r ** 2))


def sedov_shock(state, setup, threshold_ratio):
    """Sedov shock radius estimates.

    Definition (shock_r): the mass-weighted mean radius r_bar of the zones
    with rho > threshold_ratio * rho0 (default 2).  Every zone of the
    compressed shell contributes, so it is much less noisy than the radius
    of the single densest zone, and smearing the front over a few zones
    moves mass both ways about the shock.  The same functional of the
    exact profile is c r_s with c < 1 fixed by self-similarity, so
    shock_r = r_bar / c estimates r_s itself (equal to r_s for the exact
    profile).  shock_r_peak is the centroid radius of the densest zone.
    """
    keep = state["keep"]
    r, rho, mass = state["coord"][keep], state["rho"][keep], state["mass"][keep]
    threshold = threshold_ratio * setup.rho0
    r_s = setup.sedov.shock_radius(setup.time, setup.e0, setup.rho0)
    dense = rho > threshold
    r_bar = float(np.sum(mass[dense] * r[dense]) / np.sum(mass[dense])) if np.any(dense) \
        else math.nan
    r_bar_exact = sedov_dense_mean_radius_exact(setup, threshold)
    shock_r = r_bar * r_s / r_bar_exact
    i = int(np.argmax(rho))
    return {"shock_r": shock_r, "shock_r_exact": r_s,
            "shock_r_error_rel": shock_r / r_s - 1.0,
            "shock_r_peak": float(r[i]), "rho_peak": float(rho[i]),
            "rho_peak_exact": setup.rho0 * (setup.gamma + 1.0) / (setup.gamma - 1.0),
            "dense_mean_r": r_bar, "dense_mean_r_exact": r_bar_exact,
            "shock_threshold": threshold}


def radial_profile(r, rho, volume, width):
    """Volume-weighted mean density in radial bins of the given width."""
    index = np.floor(r / width).astype(np.int64)
    nbin = int(index.max()) + 1
    vsum = np.bincount(index, weights=volume, minlength=nbin)
    rsum = np.bincount(index, weights=rho * volume, minlength=nbin)
    filled = vsum > 0.0
    centres = (np.arange(nbin) + 0.5) * width
    return centres[filled], rsum[filled] / vsum[filled]


def noh_shock(state, setup, bin_width):
    """Noh shock radius and plateau diagnostics.

    Definition (shock_r): bin the zone densities in radius (volume-weighted
    means, bins of half the median zone size unless --bin-width), then scan
    from the outside inward for the first bin whose density reaches the
    mid value between the exact post-shock density rho2 and the exact
    pre-shock density at the shock rho1 = rho0 (1 + u0/D)^2, interpolating
    linearly.  rho_post_mean is the mass-weighted mean density of zones with
    0.25 r_s < r < 0.75 r_s (behind the front, outside the wall-heating
    core); rho_center_min is the lowest density with r < 0.25 r_s (the
    wall-heating dip).
    """
    keep = state["keep"]
    r, rho = state["coord"][keep], state["rho"][keep]
    volume, mass = state["volume"][keep], state["mass"][keep]
    r_s = exact_noh.shock_radius(setup.time, setup.gamma, setup.u0)
    rho2 = exact_noh.post_shock_state(setup.gamma, setup.rho0, setup.u0)[0]
    speed = 0.5 * (setup.gamma - 1.0) * setup.u0
    rho1 = setup.rho0 * (1.0 + setup.u0 / speed) ** 2
    if bin_width is None:
        bin_width = 0.5 * float(np.median(volume)) ** (1.0 / 3.0)
    centres, profile = radial_profile(r, rho, volume, bin_width)
    found = crossing(centres, profile, 0.5 * (rho1 + rho2), from_right=True)
    plateau = (r > 0.25 * r_s) & (r < 0.75 * r_s)
    core = r < 0.25 * r_s
    return {"shock_r": found, "shock_r_exact": r_s,
            "shock_r_error_rel": found / r_s - 1.0 if r_s > 0.0 else math.nan,
            "rho_post_mean": float(np.sum(mass[plateau] * rho[plateau]) / np.sum(mass[plateau]))
            if np.any(plateau) else math.nan,
            "rho_post_exact": rho2,
            "rho_center_min": float(np.min(rho[core])) if np.any(core) else math.nan,
            "bin_width": bin_width}


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
