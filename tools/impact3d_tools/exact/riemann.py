#!/usr/bin/python3
"""Exact solution of the 1D Riemann problem for two ideal gases.

Source: E. F. Toro, "Riemann Solvers and Numerical Methods for Fluid
Dynamics", 3rd ed., Springer 2009, chapter 4 (the exact solver: pressure
functions eqs. 4.6-4.7, star velocity eq. 4.9, sampling section 4.5).
Toro writes it for one gamma; here each side uses its own gamma (gL on the
left of the contact, gR on the right).  Every formula that belongs to one
side (pressure function, wave speeds, star density, fan) only involves the
data and the gamma of that side, and p and u are continuous across the
contact, so the generalisation is exact: the star pressure p* solves

    f(p) = f_L(p; rhoL, pL, gL) + f_R(p; rhoR, pR, gR) + (uR - uL) = 0

with, for side K (A_K = 2/((gK+1) rhoK), B_K = (gK-1)/(gK+1) pK,
a_K = sqrt(gK pK / rhoK)):

    p > pK (shock):        f_K = (p - pK) sqrt(A_K / (p + B_K))
    p <= pK (rarefaction): f_K = 2 a_K/(gK-1) ((p/pK)^((gK-1)/(2 gK)) - 1)

and u* = (uL + uR)/2 + (f_R(p*) - f_L(p*))/2.

Usage as a module:

    pstar, ustar = solve(1.0, 0.0, 1.0, 1.4, 0.125, 0.0, 0.1, 1.4)
    rp = RiemannProblem(1.0, 0.0, 1.0, 1.4, 0.125, 0.0, 0.1, 1.4)
    rho, u, p, e = rp.sample(x, t=0.2, x0=0.5)
    rp.wave_positions(t=0.2, x0=0.5)   # shock / contact / fan head, tail

Run as a script it prints the Sod solution summary.
"""

import math

import numpy as np


def _side_function(p, rho, pk, g):
    """Toro's pressure function f_K(p) and its derivative for one side.

    Shock branch: Toro eq. 4.6 (4.21); rarefaction branch: eq. 4.7 (4.26);
    derivatives: Toro eq. 4.37.
    """
    a = math.sqrt(g * pk / rho)
    if p > pk:
        big_a = 2.0 / ((g + 1.0) * rho)
        big_b = (g - 1.0) / (g + 1.0) * pk
        root = math.sqrt(big_a / (p + big_b))
        f = (p - pk) * root
        df = root * (1.0 - 0.5 * (p - pk) / (big_b + p))
    else:
        ratio = p / pk
        f = 2.0 * a / (g - 1.0) * (ratio ** ((g - 1.0) / (2.0 * g)) - 1.0)
        df = 1.0 / (rho * a) * ratio ** (-(g + 1.0) / (2.0 * g))
    return f, df


def solve(rhoL, uL, pL, gL, rhoR, uR, pR, gR, tol=1.0e-14, max_iter=200):
    """Star-region pressure and velocity (p*, u*) of the Riemann problem.

    Safeguarded Newton iteration (Toro section 4.3.2) kept inside a bracket
    [lo, hi] with f(lo) < 0 < f(hi); a step that leaves the bracket is
    replaced by bisection.  f is monotone increasing and concave in p, so
    the root is unique.  Raises ValueError if the data create a vacuum
    (Toro eq. 4.40, pressure positivity condition, per-side gammas).
    """
    for name, value in (("rhoL", rhoL), ("pL", pL), ("rhoR", rhoR), ("pR", pR)):
        if not value > 0.0:
            raise ValueError(f"{name} must be positive, got {value}")
    for name, value in (("gL", gL), ("gR", gR)):
        if not value > 1.0:
            raise ValueError(f"{name} must be > 1, got {value}")
    aL = math.sqrt(gL * pL / rhoL)
    aR = math.sqrt(gR * pR / rhoR)
    if 2.0 * aL / (gL - 1.0) + 2.0 * aR / (gR - 1.0) <= uR - uL:
        raise ValueError("the Riemann data generate a vacuum (not handled)")

    du = uR - uL

    def total(p):
        fl, dfl = _side_function(p, rhoL, pL, gL)
        fr, dfr = _side_function(p, rhoR, pR, gR)
        return fl + fr + du, dfl + dfr

    # Bracket.  f(p -> 0) = du - 2aL/(gL-1) - 2aR/(gR-1) < 0 (no vacuum).
    lo = 1.0e-300
    hi = max(pL, pR)
    while total(hi)[0] < 0.0:
        hi *= 2.0
    # Initial guess: primitive-variable estimate (Toro eq. 4.47), clipped.
    p_pv = 0.5 * (pL + pR) - 0.125 * du * (rhoL + rhoR) * (aL + aR)
    p = min(max(p_pv, 1.0e-8 * min(pL, pR)), hi)
    for _ in range(max_iter):
        f, df = total(p)
        if f == 0.0:
            break
        if f < 0.0:
            lo = p
        else:
            hi = p
        p_new = p - f / df
        if not lo < p_new < hi:
            p_new = 0.5 * (lo + hi)
        if abs(p_new - p) <= tol * 0.5 * (p_new + p):
            p = p_new
            break
        p = p_new
    else:
        raise RuntimeError("exact Riemann solver: no convergence for p*")

    fl, _ = _side_function(p, rhoL, pL, gL)
    fr, _ = _side_function(p, rhoR, pR, gR)
    u = 0.5 * (uL + uR) + 0.5 * (fr - fl)
    return p, u


class RiemannProblem:
    """A solved Riemann problem: star state, wave speeds and sampling."""

    def __init__(self, rhoL, uL, pL, gL, rhoR, uR, pR, gR):
        self.rhoL, self.uL, self.pL, self.gL = float(rhoL), float(uL), float(pL), float(gL)
        self.rhoR, self.uR, self.pR, self.gR = float(rhoR), float(uR), float(pR), float(gR)
        self.aL = math.sqrt(gL * pL / rhoL)
        self.aR = math.sqrt(gR * pR / rhoR)
        self.pstar, self.ustar = solve(rhoL, uL, pL, gL, rhoR, uR, pR, gR)
        ps, us = self.pstar, self.ustar

        # Left wave (Toro section 4.4.1 / 4.5, left side formulas).
        g = self.gL
        gm = (g - 1.0) / (g + 1.0)
        ratio = ps / self.pL
        self.left_is_shock = ps > self.pL
        if self.left_is_shock:
            # Shock density (Toro eq. 4.50) and speed (eq. 4.52).
            self.rho_star_left = self.rhoL * (ratio + gm) / (gm * ratio + 1.0)
            self.left_speeds = (self.uL - self.aL * math.sqrt(
                (g + 1.0) / (2.0 * g) * ratio + (g - 1.0) / (2.0 * g)),)
        else:
            # Isentropic star density (eq. 4.53), head and tail (4.55).
            self.rho_star_left = self.rhoL * ratio ** (1.0 / g)
            a_star = self.aL * ratio ** ((g - 1.0) / (2.0 * g))
            self.left_speeds = (self.uL - self.aL, us - a_star)

        # Right wave (Toro section 4.4.3 / 4.5, right side formulas).
        g = self.gR
        gm = (g - 1.0) / (g + 1.0)
        ratio = ps / self.pR
        self.right_is_shock = ps > self.pR
        if self.right_is_shock:
            # Shock density (eq. 4.57) and speed (eq. 4.59).
            self.rho_star_right = self.rhoR * (ratio + gm) / (gm * ratio + 1.0)
            self.right_speeds = (self.uR + self.aR * math.sqrt(
                (g + 1.0) / (2.0 * g) * ratio + (g - 1.0) / (2.0 * g)),)
        else:
            # Isentropic star density (eq. 4.60), head and tail (4.62).
            self.rho_star_right = self.rhoR * ratio ** (1.0 / g)
            a_star = self.aR * ratio ** ((g - 1.0) / (2.0 * g))
            self.right_speeds = (self.uR + self.aR, us + a_star)

    def wave_positions(self, t, x0=0.0):
        """Positions at time t of the waves, as a dict.

        Keys: 'contact'; 'left_shock' or 'left_head' and 'left_tail';
        'right_shock' or 'right_head' and 'right_tail'.
        """
        out = {"contact": x0 + self.ustar * t}
        if self.left_is_shock:
            out["left_shock"] = x0 + self.left_speeds[0] * t
        else:
            out["left_head"] = x0 + self.left_speeds[0] * t
            out["left_tail"] = x0 + self.left_speeds[1] * t
        if self.right_is_shock:
            out["right_shock"] = x0 + self.right_speeds[0] * t
        else:
            out["right_head"] = x0 + self.right_speeds[0] * t
            out["right_tail"] = x0 + self.right_speeds[1] * t
        return out

    def sample(self, x, t, x0=0.0):
        """rho, u, p, e at positions x (array) and time t >= 0.

        e = p / ((g - 1) rho) with the gamma of the side of the contact on
        which the point lies.  At t = 0 the initial discontinuity is returned
        (left state for x < x0).
        """
        x = np.asarray(x, dtype=float)
        rho = np.empty_like(x)
        u = np.empty_like(x)
        p = np.empty_like(x)
        if t <= 0.0:
            left = x < x0
            rho[:] = np.where(left, self.rhoL, self.rhoR)
            u[:] = np.where(left, self.uL, self.uR)
            p[:] = np.where(left, self.pL, self.pR)
        else:
            xi = (x - x0) / t
            left = xi <= self.ustar
            self._sample_left(xi, left, rho, u, p)
            self._sample_right(xi, ~left, rho, u, p)
        gamma = np.where(left, self.gL, self.gR)
        e = p / ((gamma - 1.0) * rho)
        return rho, u, p, e

    def _sample_left(self, xi, mask, rho, u, p):
        """Fill the points left of the contact (Toro section 4.5, Fig. 4.14)."""
        g = self.gL
        ps, us = self.pstar, self.ustar
        if self.left_is_shock:
            outside = mask & (xi < self.left_speeds[0])
            star = mask & ~outside
            fan = np.zeros_like(mask)
        else:
            head, tail = self.left_speeds
            outside = mask & (xi < head)
            star = mask & (xi > tail)
            fan = mask & ~outside & ~star
        rho[outside], u[outside], p[outside] = self.rhoL, self.uL, self.pL
        rho[star], u[star], p[star] = self.rho_star_left, us, ps
        if np.any(fan):
            # Left fan, Toro eq. 4.56.
            c = 2.0 / (g + 1.0) + (g - 1.0) / ((g + 1.0) * self.aL) * (self.uL - xi[fan])
            rho[fan] = self.rhoL * c ** (2.0 / (g - 1.0))
            u[fan] = 2.0 / (g + 1.0) * (self.aL + 0.5 * (g - 1.0) * self.uL + xi[fan])
            p[fan] = self.pL * c ** (2.0 * g / (g - 1.0))

    def _sample_right(self, xi, mask, rho, u, p):
        """Fill the points right of the contact (Toro section 4.5, Fig. 4.15)."""
        g = self.gR
        ps, us = self.pstar, self.ustar
        if self.right_is_shock:
            outside = mask & (xi > self.right_speeds[0])
            star = mask & ~outside
            fan = np.zeros_like(mask)
        else:
            head, tail = self.right_speeds
            outside = mask & (xi > head)
            star = mask & (xi < tail)
            fan = mask & ~outside & ~star
        rho[outside], u[outside], p[outside] = self.rhoR, self.uR, self.pR
        rho[star], u[star], p[star] = self.rho_star_right, us, ps
        if np.any(fan):
            # Right fan, Toro eq. 4.63.
            c = 2.0 / (g + 1.0) - (g - 1.0) / ((g + 1.0) * self.aR) * (self.uR - xi[fan])
            rho[fan] = self.rhoR * c ** (2.0 / (g - 1.0))
            u[fan] = 2.0 / (g + 1.0) * (-self.aR + 0.5 * (g - 1.0) * self.uR + xi[fan])
            p[fan] = self.pR * c ** (2.0 * g / (g - 1.0))


def sample(x, t, x0, rhoL, uL, pL, gL, rhoR, uR, pR, gR):
    """Convenience wrapper: rho, u, p, e of the given problem at (x, t)."""
    return RiemannProblem(rhoL, uL, pL, gL, rhoR, uR, pR, gR).sample(x, t, x0)


def main():
    """Print the Sod problem star state and wave positions at t = 0.2."""
    rp = RiemannProblem(1.0, 0.0, 1.0, 1.4, 0.125, 0.0, 0.1, 1.4)
    print(f"p* = {rp.pstar:.6f}  u* = {rp.ustar:.6f}")
    print(f"rho*L = {rp.rho_star_left:.6f}  rho*R = {rp.rho_star_right:.6f}")
    for key, value in rp.wave_positions(0.2, 0.5).items():
        print(f"{key} = {value:.6f}")


if __name__ == "__main__":
    main()
