#!/usr/bin/python3
"""Self-test of the exact solutions and the dump/compare/plot tools.

Plain asserts, no framework: every test_* function runs, failures are
listed, the last line is `N passed, M failed`, and the exit status is
non-zero if anything failed.  Run: PYTHONPATH=tools /usr/bin/python3
tests/regression/cases/exact_solutions/check.py

Reference values:
  * Riemann: Toro, "Riemann Solvers and Numerical Methods for Fluid
    Dynamics", 3rd ed., Table 4.3 (p*, u* of tests 1-5; test 1 is Sod).
  * Sedov: alpha(1.4) = 0.851072 (Kamm & Timmes LA-UR-07-2849), strong
    shock compression (g+1)/(g-1); energy and mass integrals.
  * Noh: Noh, J. Comput. Phys. 72 (1987): rho2 = 64, r_s = 0.2 at t = 0.6.
"""

import contextlib
import io
import math
import os
import sys
import tempfile
import traceback

import h5py
import numpy as np

from impact3d_tools import compare, dump
from impact3d_tools import profiles as plot_profiles
from impact3d_tools.exact import noh as exact_noh
from impact3d_tools.exact import riemann as exact_riemann
from impact3d_tools.exact import sedov as exact_sedov

SOD = (1.0, 0.0, 1.0, 1.4, 0.125, 0.0, 0.1, 1.4)


def gauss_integral(func, a, b, panels=400, order=16):
    """Composite Gauss-Legendre quadrature of a vectorised func on [a, b]."""
    nodes, weights = np.polynomial.legendre.leggauss(order)
    edges = np.linspace(a, b, panels + 1)
    half = 0.5 * np.diff(edges)
    mid = 0.5 * (edges[1:] + edges[:-1])
    x = (mid[:, None] + half[:, None] * nodes[None, :]).ravel()
    w = (half[:, None] * weights[None, :]).ravel()
    return float(np.sum(w * func(x)))


# ------------------------------------------------------------------ Riemann
def test_sod_star_state():
    pstar, ustar = exact_riemann.solve(*SOD)
    assert abs(pstar - 0.30313) < 1e-4, pstar
    assert abs(ustar - 0.92745) < 1e-4, ustar
    rp = exact_riemann.RiemannProblem(*SOD)
    assert abs(rp.rho_star_left - 0.42632) < 1e-4, rp.rho_star_left
    assert abs(rp.rho_star_right - 0.26557) < 1e-4, rp.rho_star_right


def test_toro_table_4_3():
    cases = [  # (rhoL, uL, pL, rhoR, uR, pR), p*, u*   (Toro Table 4.3)
        ((1.0, -2.0, 0.4, 1.0, 2.0, 0.4), 0.00189, 0.0),
        ((1.0, 0.0, 1000.0, 1.0, 0.0, 0.01), 460.894, 19.5975),
        ((1.0, 0.0, 0.01, 1.0, 0.0, 100.0), 46.0950, -6.19633),
        ((5.99924, 19.5975, 460.894, 5.99242, -6.19633, 46.0950), 1691.64, 8.68975),
    ]
    for (rl, ul, pl, rr, ur, pr), p_ref, u_ref in cases:
        pstar, ustar = exact_riemann.solve(rl, ul, pl, 1.4, rr, ur, pr, 1.4)
        assert abs(pstar - p_ref) <= max(1e-5 * p_ref, 6e-6), (pstar, p_ref)
        assert abs(ustar - u_ref) <= max(1e-5 * abs(u_ref), 1e-6), (ustar, u_ref)


def test_sod_profile_regions():
    rp = exact_riemann.RiemannProblem(*SOD)
    waves = rp.wave_positions(0.2, 0.5)
    x = np.array([0.1, waves["left_head"] + 1e-9, 0.6, waves["contact"] - 1e-9,
                  waves["contact"] + 1e-9, waves["right_shock"] - 1e-9, 0.95])
    rho, u, p, e = rp.sample(x, 0.2, 0.5)
    assert rho[0] == 1.0 and p[0] == 1.0 and u[0] == 0.0
    assert abs(rho[1] - 1.0) < 1e-7 and abs(u[1]) < 1e-7
    assert abs(p[3] - rp.pstar) < 1e-12 and abs(rho[3] - rp.rho_star_left) < 1e-12
    assert abs(rho[4] - rp.rho_star_right) < 1e-12 and abs(rho[5] - rp.rho_star_right) < 1e-12
    assert rho[6] == 0.125 and p[6] == 0.1
    assert np.allclose(e, p / (0.4 * rho))
    # Fan tail joins the star state continuously.
    rho_t, u_t, p_t, _ = rp.sample(np.array([waves["left_tail"] - 1e-10]), 0.2, 0.5)
    assert abs(p_t[0] - rp.pstar) < 1e-8 and abs(u_t[0] - rp.ustar) < 1e-8


def test_two_gamma_consistency():
    gl, gr = 1.4, 5.0 / 3.0
    rl, ul, pl, rr, ur, pr = 1.0, 0.0, 1.0, 0.125, 0.0, 0.1
    rp = exact_riemann.RiemannProblem(rl, ul, pl, gl, rr, ur, pr, gr)
    t, x0 = 0.2, 0.5
    waves = rp.wave_positions(t, x0)
    xc = waves["contact"]
    rho, u, p, e = rp.sample(np.array([xc - 1e-9, xc + 1e-9]), t, x0)
    # p and u continuous across the contact, density and e jump.
    assert abs(p[0] - p[1]) < 1e-12 and abs(u[0] - u[1]) < 1e-12
    assert abs(rho[0] - rho[1]) > 1e-3
    assert abs(e[0] - p[0] / ((gl - 1) * rho[0])) < 1e-12
    assert abs(e[1] - p[1] / ((gr - 1) * rho[1])) < 1e-12
    # Right shock: Rankine-Hugoniot with gamma_right.
    s = (waves["right_shock"] - x0) / t
    rs, us, ps = rp.rho_star_right, rp.ustar, rp.pstar
    mass_a, mass_b = rr * (ur - s), rs * (us - s)
    assert abs(mass_a - mass_b) < 1e-12 * abs(mass_a)
    mom_a = rr * ur * (ur - s) + pr
    mom_b = rs * us * (us - s) + ps
    assert abs(mom_a - mom_b) < 1e-12
    energy = lambda r, v, q: (0.5 * r * v * v + q / (gr - 1)) * (v - s) + q * v  # noqa: E731
    assert abs(energy(rr, ur, pr) - energy(rs, us, ps)) < 1e-12
    # Left rarefaction: isentropic, Riemann invariant uL + 2 aL/(gL-1).
    rsl = rp.rho_star_left
    assert abs(pl / rl ** gl - ps / rsl ** gl) < 1e-12
    a_l, a_s = math.sqrt(gl * pl / rl), math.sqrt(gl * ps / rsl)
    assert abs(ul + 2 * a_l / (gl - 1) - (us + 2 * a_s / (gl - 1))) < 1e-12
    # Mirror symmetry: swapping the sides flips u* and keeps p*.
    p2, u2 = exact_riemann.solve(rr, -ur, pr, gr, rl, -ul, pl, gl)
    assert abs(p2 - ps) < 1e-13 and abs(u2 + us) < 1e-13
    # Equal gammas reduce to the one-gamma solver.
    pa, ua = exact_riemann.solve(rl, ul, pl, gl, rr, ur, pr, gl)
    assert abs(pa - 0.30313) < 1e-4 and abs(ua - 0.92745) < 1e-4


def test_riemann_mass_conservation():
    rp = exact_riemann.RiemannProblem(1.0, 0.0, 1.0, 1.4, 0.125, 0.0, 0.1, 5.0 / 3.0)
    x = np.linspace(0.0, 1.0, 400001)
    rho = rp.sample(x, 0.2, 0.5)[0]
    mass = np.sum(0.5 * (rho[1:] + rho[:-1]) * np.diff(x))
    assert abs(mass - (0.5 * 1.0 + 0.5 * 0.125)) < 1e-5, mass


# -------------------------------------------------------------------- Sedov
def test_sedov_shock_radius():
    sol = exact_sedov.Sedov(1.4)
    assert abs(sol.alpha - 0.851072) < 1e-6, sol.alpha
    assert abs(sol.shock_radius(1.0, 0.851072, 1.0) - 1.0) < 1e-4
    # Scaling r_s ~ (E t^2 / rho0)^(1/5).
    r = sol.shock_radius(0.5, 2.0, 3.0)
    assert abs(r - (2.0 * 0.25 / (sol.alpha * 3.0)) ** 0.2) < 1e-14


def test_sedov_post_shock_state():
    for gamma in (1.4, 5.0 / 3.0):
        sol = exact_sedov.Sedov(gamma)
        r_s = sol.shock_radius(1.0, 0.851072, 1.0)
        rho, u, p, _ = sol.solution(np.array([r_s * (1 - 1e-12), r_s * (1 + 1e-12)]),
                                    1.0, 0.851072, 1.0)
        speed = 0.4 * r_s
        assert abs(rho[0] - (gamma + 1) / (gamma - 1)) < 1e-6 * rho[0], rho
        assert abs(u[0] - 2 / (gamma + 1) * speed) < 1e-8
        assert abs(p[0] - 2 / (gamma + 1) * speed ** 2) < 1e-8
        assert rho[1] == 1.0 and u[1] == 0.0 and p[1] == 0.0
    rho = exact_sedov.Sedov(1.4).solution(np.array([1.0 - 1e-9]), 1.0, 0.851072, 1.0)[0]
    assert abs(rho[0] - 6.0) < 1e-4, rho


def test_sedov_closed_form_matches_ode():
    for gamma in (1.2, 1.4, 5.0 / 3.0, 2.5):
        closed = exact_sedov.Sedov(gamma, method="closed")
        ode = exact_sedov.Sedov(gamma, method="ode")
        assert abs(closed.alpha / ode.alpha - 1.0) < 1e-7, (gamma, closed.alpha, ode.alpha)
        lam = np.linspace(0.02, 1.0, 200)
        for a, b in zip(closed.profile(lam), ode.profile(lam)):
            assert np.max(np.abs(a - b) / np.abs(a)) < 1e-6, gamma
    # The ODE fallback at gamma = 2 lies between its neighbours.
    near = [exact_sedov.Sedov(g).alpha for g in (1.999, 2.0, 2.001)]
    assert near[0] > near[1] > near[2]
    assert abs(near[1] - 0.5 * (near[0] + near[2])) < 1e-6


def test_sedov_energy_integral():
    for gamma, e0, rho0, t in ((1.4, 0.851072, 1.0, 1.0), (1.4, 0.851072, 1.0, 0.3),
                               (5.0 / 3.0, 1.0, 2.0, 0.7)):
        sol = exact_sedov.Sedov(gamma)
        r_s = sol.shock_radius(t, e0, rho0)

        def density(r):
            rho, u, p, _ = sol.solution(r, t, e0, rho0)
            return (0.5 * rho * u * u + p / (gamma - 1.0)) * 4.0 * math.pi * r * r

        energy = gauss_integral(density, 0.0, r_s)
        assert abs(energy / e0 - 1.0) < 1e-4, (gamma, energy, e0)
        assert abs(energy / e0 - 1.0) < 1e-8, (gamma, energy, e0)


def test_sedov_mass_integral():
    sol = exact_sedov.Sedov(1.4)
    r_s = sol.shock_radius(1.0)
    mass = gauss_integral(lambda r: sol.solution(r, 1.0)[0] * 4 * math.pi * r * r, 0.0, r_s)
    assert abs(mass / (4.0 / 3.0 * math.pi * r_s ** 3) - 1.0) < 1e-8, mass


# ---------------------------------------------------------------------- Noh
def test_noh():
    assert abs(exact_noh.shock_radius(0.6) - 0.2) < 1e-14
    rho2, u2, p2, e2 = exact_noh.post_shock_state()
    assert abs(rho2 - 64.0) < 1e-12 and u2 == 0.0
    assert abs(p2 - 64.0 / 3.0) < 1e-12 and abs(e2 - 0.5) < 1e-15
    rho, u, p, e = exact_noh.solution(np.array([0.1, 0.3, 1.2]), 0.6)
    assert rho[0] == 64.0 and u[0] == 0.0 and e[0] == 0.5
    assert abs(rho[1] - 9.0) < 1e-12 and u[1] == -1.0 and p[1] == 0.0
    assert abs(rho[2] - 2.25) < 1e-12
    # Mass inside R (beyond the shock) = initial mass inside R + u0 t.
    big_r = 0.7
    mass = (gauss_integral(lambda r: exact_noh.solution(r, 0.6)[0] * 4 * math.pi * r * r,
                           0.0, 0.2)
            + gauss_integral(lambda r: exact_noh.solution(r, 0.6)[0] * 4 * math.pi * r * r,
                             0.2, big_r))
    assert abs(mass / (4.0 / 3.0 * math.pi * (big_r + 0.6) ** 3) - 1.0) < 1e-10
    # Planar case: rho2 = rho0 (g+1)/(g-1), pre-shock unchanged.
    rho, _, _, _ = exact_noh.solution(np.array([0.1, 0.5]), 0.6, geometry=1)
    assert abs(rho[0] - 4.0) < 1e-12 and rho[1] == 1.0


# -------------------------------------------------------- dump and compare
def box_mesh(counts, lower, upper):
    """Structured hex mesh: coordinates (nnode x 3), connectivity (nzone x 8)."""
    nx, ny, nz = counts
    axes = [np.linspace(lo, hi, n + 1) for lo, hi, n in zip(lower, upper, counts)]
    gx, gy, gz = np.meshgrid(*axes, indexing="ij")
    coords = np.column_stack([gx.ravel(), gy.ravel(), gz.ravel()])
    node = np.arange(coords.shape[0]).reshape(nx + 1, ny + 1, nz + 1)
    i, j, k = np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz), indexing="ij")
    i, j, k = i.ravel(), j.ravel(), k.ravel()
    conn = np.column_stack([node[i, j, k], node[i + 1, j, k], node[i + 1, j + 1, k],
                            node[i, j + 1, k], node[i, j, k + 1], node[i + 1, j, k + 1],
                            node[i + 1, j + 1, k + 1], node[i, j + 1, k + 1]])
    volume = np.prod([(hi - lo) / n for lo, hi, n in zip(lower, upper, counts)])
    return coords, conn, volume


def write_exact_dump(path, counts, lower, upper, time, zone_exact, node_velocity):
    """A synthetic dump holding the exact solution at zone centroids."""
    coords, conn, volume = box_mesh(counts, lower, upper)
    centroids = coords[conn].mean(axis=1)
    rho, u, p, e = zone_exact(centroids)
    nzone = conn.shape[0]
    zones = {"density": rho, "specific_internal_energy": e, "pressure": p,
             "viscosity": np.zeros(nzone), "sound_speed": np.zeros(nzone),
             "volume": np.full(nzone, volume), "mass": rho * volume}
    dump.write(path, coords, conn, zones, node_velocity=node_velocity(coords),
               attrs={"time": time, "cycle": 123, "title": "synthetic",
                      "units": "dimensionless"})


def run_compare(argv):
    """Run compare.py's main with --out and read the summary back."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "summary.txt")
        with contextlib.redirect_stdout(io.StringIO()):
            status = compare.main(argv + ["--out", out])
        assert status == 0, status
        return compare.read_summary(out)


def test_dump_roundtrip():
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "d.h5")
        coords, conn, volume = box_mesh((3, 2, 1), (0, 0, 0), (3, 2, 1))
        n = conn.shape[0]
        dump.write(path, coords, conn, {"density": np.ones(n), "volume": np.full(n, volume),
                                        "pressure": np.zeros(n),
                                        "specific_internal_energy": np.zeros(n)},
                   node_velocity=coords * 2.0,
                   attrs={"time": np.array([0.25]), "title": np.bytes_(b"abc   ")})
        data = dump.load(path)
        assert data["attrs"]["time"] == 0.25 and data["attrs"]["title"] == "abc"
        assert dump.problem_time(data) == 0.25
        assert np.allclose(data["mass"], volume)  # filled from density * volume
        cent = dump.zone_centroids(data)
        assert np.allclose(cent[0], [0.5, 0.5, 0.5]) and np.allclose(cent[-1], [2.5, 1.5, 0.5])
        assert np.allclose(dump.zone_velocity(data), 2.0 * cent)
        assert np.allclose(dump.radius(cent[:1], (0.5, 0.5, 0.0)), [0.5])


def test_compare_sod():
    rp = exact_riemann.RiemannProblem(*SOD)
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "sod.h5")

        def node_velocity(c):
            v = np.zeros_like(c)
            v[:, 0] = rp.sample(c[:, 0], 0.2, 0.5)[1]
            return v

        write_exact_dump(path, (200, 2, 2), (0, 0, 0), (1, 0.01, 0.01), 0.2,
                         lambda c: rp.sample(c[:, 0], 0.2, 0.5), node_velocity)
        s = run_compare(["--problem", "sod", path])
        assert s["time"] == 0.2 and s["nzone"] == 800 and s["cycle"] == 123
        for f in ("rho", "p", "e"):
            assert s[f"L1_{f}"] == 0.0 and s[f"Linf_{f}"] == 0.0, f
        assert s["L1_u"] < 5e-3, s["L1_u"]
        assert abs(s["shock_x"] - s["shock_x_exact"]) < 1.0 / 200, s["shock_x"]
        assert abs(s["pstar"] - 0.30313) < 1e-4
        # A perturbed density gives the expected L1 and Linf.
        data = dump.load(path)
        rho = data["density"] + 0.01
        with h5py.File(path, "r+") as handle:
            handle["zones/density"][...] = rho
        s = run_compare(["--problem", "sod", path, "--region", "0.0", "0.5"])
        assert abs(s["L1_rho"] - 0.01) < 1e-12 and abs(s["Linf_rho"] - 0.01) < 1e-12
        assert abs(s["L1mass_rho"] - 0.01) < 1e-12 and s["nzone_used"] == 400
        with contextlib.redirect_stderr(io.StringIO()):
            assert compare.main(["--problem", "sod", os.path.join(tmp, "missing.h5")]) == 1


def test_compare_riemann2():
    rp = exact_riemann.RiemannProblem(1.0, 0.0, 1.0, 1.4, 0.125, 0.0, 0.1, 5.0 / 3.0)
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "r2.h5")
        write_exact_dump(path, (100, 1, 1), (0, 0, 0), (1, 0.01, 0.01), 0.2,
                         lambda c: rp.sample(c[:, 0], 0.2, 0.5),
                         lambda c: np.zeros_like(c))
        s = run_compare(["--problem", "riemann2", path])
        assert s["L1_e"] == 0.0 and abs(s["gamma_right"] - 5.0 / 3.0) < 1e-6
        assert abs(s["shock_x"] - s["shock_x_exact"]) < 1.0 / 100


def test_compare_sedov_and_plot():
    sol = exact_sedov.Sedov(1.4)
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "sedov.h5")

        def node_velocity(c):
            r = np.linalg.norm(c, axis=1)
            u = sol.solution(r, 1.0)[1]
            return c * (u / np.where(r > 0, r, 1.0))[:, None]

        write_exact_dump(path, (24, 24, 24), (0, 0, 0), (1.2, 1.2, 1.2), 1.0,
                         lambda c: sol.solution(np.linalg.norm(c, axis=1), 1.0),
                         node_velocity)
        s = run_compare(["--problem", "sedov", path])
        assert abs(s["alpha"] - 0.851072) < 1e-6
        assert s["L1_rho"] == 0.0 and s["L1_p"] == 0.0
        assert s["L1_u"] < 0.02, s["L1_u"]
        assert abs(s["shock_r"] - 1.0) < 0.05, s["shock_r"]
        assert abs(s["shock_r_exact"] - 1.0) < 1e-4
        assert s["rho_peak_exact"] == 6.0 and 1.0 < s["rho_peak"] <= 6.0
        png = os.path.join(tmp, "sedov.png")
        with contextlib.redirect_stdout(io.StringIO()):
            assert plot_profiles.main(["--problem", "sedov", path, "-o", png]) == 0
        assert os.path.getsize(png) > 10000


def test_compare_noh():
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "noh.h5")

        def node_velocity(c):
            r = np.linalg.norm(c, axis=1)
            u = exact_noh.solution(r, 0.6)[1]
            return c * (u / np.where(r > 0, r, 1.0))[:, None]

        write_exact_dump(path, (40, 40, 40), (0, 0, 0), (1, 1, 1), 0.6,
                         lambda c: exact_noh.solution(np.linalg.norm(c, axis=1), 0.6),
                         node_velocity)
        s = run_compare(["--problem", "noh", path, "--region", "0.05", "0.3"])
        assert s["L1_rho"] == 0.0 and s["L1_e"] == 0.0
        assert abs(s["shock_r"] - 0.2) < 0.025, s["shock_r"]
        assert s["rho_post_mean"] == 64.0 and s["rho_post_exact"] == 64.0
        png = os.path.join(tmp, "noh.png")
        with contextlib.redirect_stdout(io.StringIO()):
            assert plot_profiles.main(["--problem", "noh", path, "-o", png]) == 0


def main():
    tests = [(name, obj) for name, obj in globals().items()
             if name.startswith("test_") and callable(obj)]
    passed, failed = 0, []
    for name, test in tests:
        try:
            test()
        except Exception:  # report every failure, keep going
            failed.append(name)
            print(f"FAIL {name}")
            traceback.print_exc()
        else:
            passed += 1
            print(f"ok   {name}")
    print(f"{passed} passed, {len(failed)} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
