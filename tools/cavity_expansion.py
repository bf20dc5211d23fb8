#!/usr/bin/python3
"""Rigid-projectile penetration depth of an ogive-nose rod from the spherical
cavity-expansion model (python3 + numpy only).

Target resistance: the normal stress on the nose surface is that of a
spherical cavity expanding at the local normal velocity vn,

    sigma_n / Y = A + B (vn / c) + C (vn / c)^2,    c = sqrt(Y / rho_t),

i.e. sigma_n = A Y + B sqrt(Y rho_t) vn + C rho_t vn^2. Friction-free: the
shear stress on the nose is 0 and the shank touches nothing (the cavity has
the shank's radius a). The rod is rigid, of mass m, shank radius a, with a
tangent ogive nose of calibre-radius-head psi (ogive radius s = 2 psi a,
nose length l = a sqrt(4 psi - 1)), striking normally at V.

Nose surface, angle phi from the rod axis direction at the arc's centre
(which lies s - a off the axis on the far side): radius r = s sin(phi) -
(s - a), distance from the nose base x = s cos(phi), outward normal (sin phi,
cos phi) (radial, forward), normal velocity vn = V cos(phi), area element
2 pi r s dphi. The tip is phi0 = asin((s - a)/s), the base phi = pi/2. The
axial force on the part of the nose from the tip to phi1 is

    F = alpha G0(phi1) + beta G1(phi1) V + gamma G2(phi1) V^2,
    Gk(phi1) = 2 pi s int_phi0^phi1 cos^(k+1)(phi) (s sin(phi) - s + a) dphi,
    alpha = A Y, beta = B sqrt(Y rho_t), gamma = C rho_t,

and the Gk have closed forms (gk below). For the whole nose G0 = pi a^2
(the projected area), G1 = pi a^2 N1, G2 = pi a^2 N2 with the nose factors
N1, N2 (N2 = (8 psi - 1)/(24 psi^2) for the tangent ogive).

Depth P is the depth of the nose tip below the target face. Two phases:

* nose entry, 0 <= P < l: the part of the nose below the face is the part
  from the tip to cos(phi1) = (l - P)/s; m V dV/dP = -F(P, V). No closed
  form (beta != 0 makes it an Abel equation in V); integrated in P by RK4
  on w = V^2 (`NOSE_STEPS` = 400 steps, error O(h^4): 2e-13 relative on the
  default rod, against 4000 steps).
* tunnel, P >= l: F = pi a^2 (alpha + beta N1 V + gamma N2 V^2), so with
  a0 = alpha, a1 = beta N1, a2 = gamma N2, Delta = 4 a0 a2 - a1^2 > 0,

    P - l = m/(pi a^2) [ ln((a2 V1^2 + a1 V1 + a0)/a0) / (2 a2)
            - a1/(a2 sqrt(Delta)) (atan((2 a2 V1 + a1)/sqrt(Delta))
                                   - atan(a1/sqrt(Delta))) ],

  V1 the speed when the whole nose is in (closed form, exact for the model).

`closed_depth` is the fully closed form: the nose-entry work taken at the
striking speed, W = int_0^l F(P, V) dP = pi a^2 (alpha l0 + beta l1 V +
gamma l2 V^2) (geometric lengths lk = int_0^l Gk dP / (pi a^2)), V1^2 =
V^2 - 2 W/m, P = l + tunnel(V1). It overestimates the nose-entry loss
slightly (V falls during entry); `depth` (numerical nose entry) is the model.

With B = 0 and C = 1 the tunnel term is Forrestal's
m/(2 pi a^2 rho_t N2) ln(1 + N2 rho_t V1^2/(A Y)).

Usage: cavity_expansion.py [--velocities V ...] [--mass m] [--radius a]
       [--crh psi] [--Y Y] [--A A] [--B B] [--C C] [--rho R]
       [--profile P ... [--start P0]]
Defaults: the Piekutowski et al. (1999) rods and 6061-T6511 target (SI units).
Prints, per striking velocity, the depth of the model, the closed form and the
nose-entry speed loss; with --profile, the model's speed at the tip depths
given (the deceleration to compare a run's first microseconds with).
"""

import argparse
import math
import sys

import numpy as np

# Piekutowski, Forrestal, Poormon & Warren (1999): VAR 4340 rods, 3.0 CRH
# ogive, 7.11 mm diameter, nominal 0.021 kg; 6061-T6511 target.
DEFAULTS = dict(mass=0.021, radius=7.11e-3 / 2.0, crh=3.0, Y=276.0e6, A=5.04, B=0.983,
                C=0.940, rho=2710.0)
GIVEN = [(569.0, 58.0), (821.0, 102.0), (1147.0, 190.0)]
BLIND = [679.0, 966.0, 1237.0, 1977.0, 2570.0, 2988.0]
NOSE_STEPS = 400


class Model:
    """The cavity-expansion model of one rod and target (SI units)."""

    def __init__(self, mass, radius, crh, Y, A, B, C, rho):
        self.m = mass
        self.a = radius
        self.psi = crh
        self.s = 2.0 * crh * radius
        self.l = radius * math.sqrt(4.0 * crh - 1.0)
        self.phi0 = math.asin((self.s - radius) / self.s)
        self.alpha = A * Y
        self.beta = B * math.sqrt(Y * rho)
        self.gamma = C * rho
        area = math.pi * radius ** 2
        self.N1 = self.gk(1, 0.5 * math.pi) / area
        self.N2 = self.gk(2, 0.5 * math.pi) / area
        self.a0 = self.alpha
        self.a1 = self.beta * self.N1
        self.a2 = self.gamma * self.N2
        self.delta = 4.0 * self.a0 * self.a2 - self.a1 ** 2
        if self.delta <= 0.0:
            raise ValueError("4 a0 a2 <= a1^2: the tunnel closed form here needs a "
                             "positive discriminant")
        # Nose-entry lengths lk = int_0^l Gk(phi1(P)) dP / (pi a^2), by
        # Gauss-Legendre in P (the integrand is smooth).
        nodes, weights = np.polynomial.legendre.leggauss(64)
        p = 0.5 * self.l * (nodes + 1.0)
        self.lk = [0.5 * self.l * float(np.sum(weights * self.gk(k, self.phi_of_depth(p))))
                   / area for k in range(3)]

    def phi_of_depth(self, depth):
        """Angle phi1 bounding the part of the nose below the face at tip depth P."""
        x = np.clip(self.l - np.asarray(depth, dtype=float), 0.0, self.l)
        return np.arccos(x / self.s)

    def gk(self, k, phi1):
        """Gk(phi1) = 2 pi s int_phi0^phi1 cos^(k+1) (s sin - s + a) dphi, closed form."""
        s, a, p0 = self.s, self.a, self.phi0
        phi1 = np.asarray(phi1, dtype=float)

        def cos_power(n, phi):
            """int cos^n(phi) dphi for n = 1, 2, 3."""
            if n == 1:
                return np.sin(phi)
            if n == 2:
                return 0.5 * phi + 0.25 * np.sin(2.0 * phi)
            return np.sin(phi) - np.sin(phi) ** 3 / 3.0

        sin_part = -(np.cos(phi1) ** (k + 2) - math.cos(p0) ** (k + 2)) / (k + 2)
        cos_part = cos_power(k + 1, phi1) - cos_power(k + 1, p0)
        return 2.0 * math.pi * s * (s * sin_part - (s - a) * cos_part)

    def force(self, depth, speed):
        """Axial resisting force at tip depth P (>= 0) and speed V (>= 0)."""
        phi1 = self.phi_of_depth(depth)
        return (self.alpha * self.gk(0, phi1) + self.beta * self.gk(1, phi1) * speed
                + self.gamma * self.gk(2, phi1) * speed ** 2)

    def tunnel(self, speed):
        """Depth travelled with the whole nose in, from speed V1 to rest (closed form)."""
        a0, a1, a2, root = self.a0, self.a1, self.a2, math.sqrt(self.delta)
        log_term = math.log((a2 * speed ** 2 + a1 * speed + a0) / a0) / (2.0 * a2)
        atan_term = a1 / (a2 * root) * (math.atan((2.0 * a2 * speed + a1) / root)
                                        - math.atan(a1 / root))
        return self.m / (math.pi * self.a ** 2) * (log_term - atan_term)

    def nose_entry(self, speed, steps=NOSE_STEPS):
        """Speed when the whole nose is in (RK4 in P on w = V^2); 0 if it stops before."""
        h = self.l / steps
        w = speed ** 2

        def rate(p, w):
            return -2.0 / self.m * float(self.force(p, math.sqrt(max(w, 0.0))))

        for i in range(steps):
            p = i * h
            k1 = rate(p, w)
            k2 = rate(p + 0.5 * h, w + 0.5 * h * k1)
            k3 = rate(p + 0.5 * h, w + 0.5 * h * k2)
            k4 = rate(p + h, w + h * k3)
            w += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
            if w <= 0.0:
                return 0.0
        return math.sqrt(w)

    def speed_at(self, speed, depths, start=0.0, flat=0.0, steps_per_nose=NOSE_STEPS):
        """Speed of the rod when its (sharp) tip is at each depth of `depths` (increasing,
        >= start), striking at `speed` with the tip at depth `start` (RK4 in P on w = V^2,
        steps of at most l / steps_per_nose); 0 once it has stopped. A nose cut by a flat
        of radius `flat` at the sharp tip's depth `start` (the cut part never touches):
        the flat carries the normal stress at vn = V on its area pi flat^2."""
        h_max = self.l / steps_per_nose
        w, p, out = speed ** 2, start, []
        flat_area = math.pi * flat ** 2

        def rate(p, w):
            v = math.sqrt(max(w, 0.0))
            cut = self.force(start, v) if flat > 0.0 else 0.0
            on_flat = flat_area * (self.alpha + self.beta * v + self.gamma * v * v)
            return -2.0 / self.m * float(self.force(p, v) - cut + on_flat)

        for target in depths:
            while p < target and w > 0.0:
                h = min(h_max, target - p)
                k1 = rate(p, w)
                k2 = rate(p + 0.5 * h, w + 0.5 * h * k1)
                k3 = rate(p + 0.5 * h, w + 0.5 * h * k2)
                k4 = rate(p + h, w + h * k3)
                w += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
                p += h
            out.append(math.sqrt(max(w, 0.0)))
        return out

    def depth(self, speed):
        """Depth of the tip below the face when the rod stops (nose entry + tunnel)."""
        v1 = self.nose_entry(speed)
        if v1 == 0.0:
            raise ValueError(f"V = {speed}: the rod stops before its nose is in")
        return self.l + self.tunnel(v1)

    def closed_depth(self, speed):
        """Closed form: the nose-entry work at the striking speed, then the tunnel."""
        work = math.pi * self.a ** 2 * (self.alpha * self.lk[0] + self.beta * self.lk[1] * speed
                                        + self.gamma * self.lk[2] * speed ** 2)
        v1_squared = speed ** 2 - 2.0 * work / self.m
        if v1_squared <= 0.0:
            raise ValueError(f"V = {speed}: the rod stops before its nose is in")
        return self.l + self.tunnel(math.sqrt(v1_squared))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--velocities", type=float, nargs="+",
                        help="striking velocities (m/s); default: the given and blind shots")
    for key, value in DEFAULTS.items():
        parser.add_argument(f"--{key}", type=float, default=value, help=f"default {value:g}")
    parser.add_argument("--profile", type=float, nargs="+", metavar="P",
                        help="tip depths (m): print the model's speed there for each velocity "
                        "instead of the depths")
    parser.add_argument("--start", type=float, default=0.0,
                        help="with --profile: depth of the sharp tip at impact (m); a rod whose "
                        "tip is cut by a flat of axial length f strikes with the sharp tip at "
                        "f, default 0")
    parser.add_argument("--flat", type=float, default=0.0,
                        help="with --profile: radius (m) of that flat, which carries the normal "
                        "stress at the rod's speed (0: no flat, default)")
    args = parser.parse_args(argv)
    model = Model(**{key: getattr(args, key) for key in DEFAULTS})
    if args.profile:
        depths = sorted(args.profile)
        for v in args.velocities or [v for v, _ in GIVEN] + BLIND:
            speeds = model.speed_at(v, depths, start=args.start, flat=args.flat)
            for p, u in zip(depths, speeds):
                print(f"V0 {v:8.1f}  tip depth {p * 1e3:9.3f} mm  speed {u:10.4f} m/s  "
                      f"loss {v - u:9.4f} m/s")
        return 0
    print(f"ogive CRH {model.psi:g}: a = {model.a * 1e3:.4f} mm, s = {model.s * 1e3:.4f} mm, "
          f"nose l = {model.l * 1e3:.4f} mm, m = {model.m:g} kg")
    print(f"N1 = {model.N1:.6f}, N2 = {model.N2:.6f} "
          f"((8 psi - 1)/(24 psi^2) = {(8 * model.psi - 1) / (24 * model.psi ** 2):.6f}); "
          f"a0 = {model.a0:.6e} Pa, a1 = {model.a1:.6e} Pa s/m, a2 = {model.a2:.6e} kg/m^3")
    measured = dict(GIVEN)
    speeds = args.velocities or [v for v, _ in GIVEN] + BLIND
    print(f"{'V (m/s)':>8} {'P model (mm)':>13} {'P closed (mm)':>14} {'V1 (m/s)':>9} "
          f"{'measured (mm)':>14}")
    for v in speeds:
        p = model.depth(v)
        print(f"{v:8.0f} {p * 1e3:13.2f} {model.closed_depth(v) * 1e3:14.2f} "
              f"{model.nose_entry(v):9.1f} "
              f"{measured[v] if v in measured else '':>14}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
