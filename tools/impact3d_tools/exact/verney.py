#!/usr/bin/python3
"""Verney shell: incompressible, rigid-perfectly-plastic collapse of a thick
spherical shell (Howell & Ball 2002; LA-14379), by the energy balance.

Derivation (written for this project; docs/theory.md has the summary). An
incompressible radial flow has u(r) = U a^2 / r^2, a the inner radius (U = da/dt)
and b^3 = a^3 + (b0^3 - a0^3). Kinetic energy (full sphere):

    K(a) = 1/2 rho int_a^b u^2 4 pi r^2 dr = 2 pi rho U^2 a^3 (1 - a/b).

The strain rates are e_rr = -2u/r, e_tt = e_pp = u/r, so the von Mises rate is
2|u|/r and the plastic dissipation is

    dW/dt = int_a^b Y 2|u|/r 4 pi r^2 dr = 8 pi Y |U| a^2 ln(b/a).

With dK/dt = -dW/dt and da/dt = U: dK/da = 8 pi Y a^2 ln(b/a), hence
K(a) = K0 - int_a^a0 8 pi Y s^2 ln(b(s)/s) ds; the shell stops where K = 0, and
t(a) = int_a^a0 ds / |U(s)|. Elasticity and compressibility are neglected.
"""
import math
import sys

import numpy as np


def verney(a0=8.0, b0=10.0, rho=1.845, y=0.0033, u0=0.06198, n=200001):
    """Return (a_stop, t_stop, a(t) as arrays a, t) for an inward U0 = u0 > 0."""
    c = b0 ** 3 - a0 ** 3
    k0 = 2.0 * math.pi * rho * u0 ** 2 * a0 ** 3 * (1.0 - a0 / b0)
    a = np.linspace(a0, 0.05 * a0, n)
    b = np.cbrt(a ** 3 + c)
    integrand = 8.0 * math.pi * y * a ** 2 * np.log(b / a)
    # Work done from a0 down to a (a decreasing): cumulative trapezoid.
    work = np.concatenate(([0.0], np.cumsum(0.5 * (integrand[1:] + integrand[:-1])
                                            * (a[:-1] - a[1:]))))
    k = k0 - work
    stop = np.where(k <= 0.0)[0]
    if stop.size == 0:
        raise ValueError("the shell does not stop before 0.05 a0")
    i = stop[0]
    # linear interpolation of the zero of K
    a_stop = a[i - 1] + (a[i] - a[i - 1]) * k[i - 1] / (k[i - 1] - k[i])
    a, b, k = a[:i], b[:i], k[:i]
    speed = np.sqrt(k / (2.0 * math.pi * rho * a ** 3 * (1.0 - a / b)))
    dt = (a[:-1] - a[1:]) * 0.5 * (1.0 / speed[:-1] + 1.0 / speed[1:])
    t = np.concatenate(([0.0], np.cumsum(dt)))
    # the last stretch to a_stop: speed ~ sqrt(a - a_stop), integral 2 (a - a_stop)/speed
    t_stop = t[-1] + 2.0 * (a[-1] - a_stop) / speed[-1]
    return a_stop, t_stop, a, t


def radius_at(times, a, t, a_stop, t_stop):
    """Inner radius at the given times (held at a_stop after t_stop)."""
    times = np.asarray(times, dtype=float)
    return np.where(times >= t_stop, a_stop, np.interp(times, t, a))


if __name__ == "__main__":
    a_stop, t_stop, a, t = verney()
    print("a_stop = %.4f cm at t = %.2f us" % (a_stop, t_stop))
    sys.exit(0)
