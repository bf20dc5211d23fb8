#!/usr/bin/python3
"""tools/cavity_expansion.py against an independent integration of the same
model: the rod's equation of motion m dV/dt = -F(P, V), dP/dt = V integrated
in time by RK4, with the force F from a quadrature over the nose written here
in another parametrisation (distance from the tip, not the arc angle).

Criteria (each can fail):
* the tool's nose factors: G0 of the whole nose is the projected area pi a^2
  and N2 = (8 psi - 1)/(24 psi^2) (closed forms for a tangent ogive), to
  1e-12 relative (round-off of a few dozen operations); N1 and the force at
  three partial depths equal this file's quadrature to 1e-12;
* the tunnel closed form (whole nose in from speed V1) equals the time
  integration started with the nose in, and the tool's depth (numerical nose
  entry + closed-form tunnel) equals the time integration from the first
  contact, both to 1e-6 relative, for the given and blind velocities;
* the speed profile (`--profile`, Model.speed_at): at the nose's full depth
  the nose entry's speed to 1e-12, and half-way down the tunnel a speed
  whose closed-form tunnel ends at the model's depth, to 1e-6.
  Bound: RK4's global error is O(dt^4); the run uses dt = T/N with N = 4000
  steps over the penetration time and measures the error by Richardson (N
  against N/2: the difference times 16/15); that estimate is asserted below
  1e-8, so a 1e-6 discrepancy is a fault of the tool, not of the check.
Exit 0 when all hold, 1 with the failures listed.
"""

import math
import sys

import numpy as np

import cavity_expansion as ce

SPEEDS = [569.0, 821.0, 1147.0, 679.0, 966.0, 1237.0, 1977.0, 2570.0, 2988.0]
ROUND_OFF = 1e-12
TOLERANCE = 1e-6
RICHARDSON = 1e-8
failures = []


def check(name, value, reference, tolerance):
    error = abs(value - reference) / abs(reference)
    status = "ok" if error <= tolerance else "FAIL"
    print(f"{status:4} {name}: {value:.12e} vs {reference:.12e} (relative {error:.2e}, "
          f"bound {tolerance:g})")
    if error > tolerance:
        failures.append(name)


class Nose:
    """The same target resistance, integrated over the nose by distance from the tip."""

    def __init__(self, model):
        self.m, self.a, self.s, self.l = model.m, model.a, model.s, model.l
        Y, A, B, C, rho = (ce.DEFAULTS[k] for k in ("Y", "A", "B", "C", "rho"))
        self.sigma = lambda vn: A * Y + B * math.sqrt(Y * rho) * vn + C * rho * vn ** 2
        self.nodes, self.weights = np.polynomial.legendre.leggauss(48)

    def profile(self, xi):
        """Radius r and slope dr/dxi at distance xi from the (sharp) tip."""
        u = self.l - xi
        root = np.sqrt(self.s ** 2 - u ** 2)
        return root - (self.s - self.a), u / root

    def force(self, depth, speed):
        """Axial force of the part of the nose within depth of the tip."""
        top = min(max(depth, 0.0), self.l)
        if top <= 0.0:
            return 0.0
        xi = 0.5 * top * (self.nodes + 1.0)
        r, slope = self.profile(xi)
        n_axial = slope / np.sqrt(1.0 + slope ** 2)  # forward component of the normal
        integrand = self.sigma(speed * n_axial) * 2.0 * math.pi * r * slope
        return 0.5 * top * float(np.sum(self.weights * integrand))

    def run(self, depth, speed, steps):
        """RK4 in time from (P, V) until V = 0; the last step is cut to land on V = 0."""
        duration = 2.0 * (self.l + 0.3) / speed  # longer than any run here
        dt = duration / steps

        def rate(state):
            p, v = state
            return np.array([v, -self.force(p, v) / self.m])

        def step(state, h):
            k1 = rate(state)
            k2 = rate(state + 0.5 * h * k1)
            k3 = rate(state + 0.5 * h * k2)
            k4 = rate(state + h * k3)
            return state + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)

        def land(state, h, component, target):
            """Step length from state that brings state[component] to target (secant)."""
            h0, f0 = 0.0, state[component] - target
            h1, f1 = h, step(state, h)[component] - target
            for _ in range(60):
                if f1 == f0:
                    break
                h0, f0, h1 = h1, f1, h1 - f1 * (h1 - h0) / (f1 - f0)
                f1 = step(state, h1)[component] - target
                if abs(f1) <= 1e-15 * abs(target if target else speed):
                    break
            return h1

        state = np.array([depth, speed])
        while True:
            trial = step(state, dt)
            if trial[1] <= 0.0:
                # V crosses 0 within this step: land on V = 0.
                return step(state, land(state, dt, 1, 0.0))[0]
            if state[0] < self.l < trial[0]:
                # The nose becomes wholly embedded within this step, where the
                # force has a kink: land on P = l so that RK4 keeps its order.
                state = step(state, land(state, dt, 0, self.l))
                continue
            state = trial


def converged(nose, depth, speed, steps):
    """Depth from RK4 with `steps` steps, and its Richardson error estimate."""
    fine = nose.run(depth, speed, steps)
    coarse = nose.run(depth, speed, steps // 2)
    return fine, abs(fine - coarse) * 16.0 / 15.0 / abs(fine)


def main():
    model = ce.Model(**ce.DEFAULTS)
    nose = Nose(model)
    area = math.pi * model.a ** 2
    check("G0(whole nose) = pi a^2", float(model.gk(0, 0.5 * math.pi)), area, ROUND_OFF)
    psi = model.psi
    check("N2 = (8 psi - 1)/(24 psi^2)", model.N2, (8.0 * psi - 1.0) / (24.0 * psi ** 2),
          ROUND_OFF)
    # N1 by this file's quadrature: the force's linear part per unit speed.
    n1 = (nose.force(model.l, 1.0) - nose.force(model.l, 0.0)
          - (nose.force(model.l, 2.0) - 2.0 * nose.force(model.l, 1.0)
             + nose.force(model.l, 0.0)) / 2.0) / (model.beta * area)
    check("N1 (two quadratures)", model.N1, n1, 1e-9)
    for fraction in (0.1, 0.5, 0.9):
        depth = fraction * model.l
        check(f"F(P = {fraction:g} l, 1000 m/s)", float(model.force(depth, 1000.0)),
              nose.force(depth, 1000.0), ROUND_OFF)
    for v in SPEEDS:
        v1 = model.nose_entry(v)
        reference, estimate = converged(nose, model.l, v1, 4000)
        check(f"tunnel from V1 = {v1:.3f} m/s (RK4 error estimate {estimate:.1e})",
              model.l + model.tunnel(v1), reference, TOLERANCE)
        if estimate > RICHARDSON:
            failures.append(f"RK4 not converged at V1 = {v1}")
        reference, estimate = converged(nose, 0.0, v, 4000)
        check(f"depth at V = {v:g} m/s (RK4 error estimate {estimate:.1e})", model.depth(v),
              reference, TOLERANCE)
        if estimate > RICHARDSON:
            failures.append(f"RK4 not converged at V = {v}")
    # --profile (speed_at): at the nose's full depth it is the nose entry's
    # speed (the same RK4 steps: round-off over 400 steps, 1e-12); half-way
    # down the tunnel, the closed-form tunnel from its speed ends at the
    # model's depth (RK4 in P with steps l/400 against the exact tunnel: its
    # error is far below the 1e-6 bound used for the time integration above).
    for v in (569.0, 1147.0):
        check(f"speed_at(l) = nose_entry at V = {v:g} m/s", model.speed_at(v, [model.l])[0],
              model.nose_entry(v), ROUND_OFF)
        half = model.l + 0.5 * (model.depth(v) - model.l)
        u = model.speed_at(v, [half])[0]
        check(f"depth from speed_at half-way down the tunnel, V = {v:g} m/s",
              half + model.tunnel(u), model.depth(v), TOLERANCE)
    if failures:
        print("cavity_expansion: FAILED: " + "; ".join(failures))
        return 1
    print("cavity_expansion: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
