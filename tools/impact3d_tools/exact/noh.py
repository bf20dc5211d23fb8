#!/usr/bin/python3
"""Exact solution of the spherical Noh implosion problem.

Source: W. F. Noh, "Errors for calculations of strong shocks using an
artificial viscosity and an artificial heat flux", J. Comput. Phys. 72
(1987) 78-120, section 3; the formulas below are re-derived here from the
Rankine-Hugoniot jump conditions.

Set-up: ideal gas (gamma), density rho0, zero pressure and internal energy,
radial velocity -u0 everywhere at t = 0.  Geometry index j = 3 (sphere;
j = 2 cylinder, j = 1 plane also work).

Pre-shock (r > r_s): the gas coasts inward at -u0, cold; the converging
flow compresses it (continuity for u = -u0 gives rho r^(j-1) constant along
r + u0 t = const):

    rho = rho0 (1 + u0 t / r)^(j-1),  u = -u0,  p = 0,  e = 0.

The shock moves out at constant speed D and leaves the gas at rest.  In the
shock frame, with rho1 = rho0 (1 + u0/D)^(j-1) just ahead of it:

    mass:     rho1 (u0 + D) = rho2 D
    momentum: p2 = rho1 (u0 + D) u0 = rho2 D u0
    energy:   e2 = u0^2 / 2  (all kinetic energy becomes internal energy)

and p2 = (gamma - 1) rho2 e2 closes it: D = (gamma - 1) u0 / 2, so

    r_s = (gamma - 1) u0 t / 2,
    rho2 = rho0 ((gamma + 1)/(gamma - 1))^j,
    u2 = 0,  e2 = u0^2/2,  p2 = (gamma - 1) rho2 u0^2 / 2.

For gamma = 5/3, rho0 = u0 = 1, j = 3: rho2 = 64, p2 = 64/3, e2 = 1/2 and
r_s = 0.2 at t = 0.6; rho1 = 16.
"""

import numpy as np


def shock_radius(t, gamma=5.0 / 3.0, u0=1.0):
    """Shock radius r_s = (gamma - 1) u0 t / 2."""
    return 0.5 * (gamma - 1.0) * u0 * t


def post_shock_state(gamma=5.0 / 3.0, rho0=1.0, u0=1.0, geometry=3):
    """(rho2, u2, p2, e2) behind the shock."""
    rho2 = rho0 * ((gamma + 1.0) / (gamma - 1.0)) ** geometry
    e2 = 0.5 * u0 * u0
    return rho2, 0.0, (gamma - 1.0) * rho2 * e2, e2


def solution(r, t, gamma=5.0 / 3.0, rho0=1.0, u0=1.0, geometry=3):
    """rho, u (radial, negative inward), p, e at radii r (array), time t >= 0.

    A point exactly on the shock takes the post-shock state.
    """
    r = np.abs(np.asarray(r, dtype=float))
    r_s = shock_radius(t, gamma, u0)
    rho2, u2, p2, e2 = post_shock_state(gamma, rho0, u0, geometry)
    inside = r <= r_s
    with np.errstate(divide="ignore"):
        rho_pre = rho0 * (1.0 + u0 * t / np.where(r > 0.0, r, np.inf)) ** (geometry - 1)
    if t <= 0.0:
        rho_pre = np.full_like(r, rho0)
        inside = np.zeros_like(r, dtype=bool)
    rho = np.where(inside, rho2, rho_pre)
    u = np.where(inside, u2, -u0)
    p = np.where(inside, p2, 0.0)
    e = np.where(inside, e2, 0.0)
    return rho, u, p, e


def main():
    """Print the gamma = 5/3 solution data at t = 0.6."""
    rho2, _, p2, e2 = post_shock_state()
    print(f"r_s(0.6) = {shock_radius(0.6):.6f}  rho2 = {rho2:.6f}  "
          f"p2 = {p2:.6f}  e2 = {e2:.6f}")
    rho, u, p, e = solution(np.array([0.1, 0.2, 0.2 + 1e-12, 0.5]), 0.6)
    print("r = 0.1, 0.2, 0.2+, 0.5: rho =", rho)


if __name__ == "__main__":
    main()
