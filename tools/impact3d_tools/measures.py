"""Measures of a numerical solution against an exact one, for
impact3d_tools.compare (whose docstring defines them): error norms, the
planar and radial density profiles, and the shock positions of the Riemann,
Sedov and Noh problems."""
import math

import numpy as np

from impact3d_tools.exact import noh as exact_noh

FIELDS = ("rho", "p", "u", "e")


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
