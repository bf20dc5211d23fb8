#!/usr/bin/python3
"""Spherical Sedov-Taylor blast wave in a uniform ideal gas (standard case).

Point energy E0 (full sphere) released at t = 0 in gas of density rho0 at
zero pressure; ideal gas with ratio of specific heats gamma (1 < gamma < 7).
The shock is at

    r_s(t) = (E0 t^2 / (alpha rho0))^(1/5)

and behind it the flow is self-similar in lambda = r / r_s.

Sources.
  * J. R. Kamm & F. X. Timmes, "On efficient generation of numerically
    robust Sedov solutions", LA-UR-07-2849 (2007), and J. R. Kamm,
    "Evaluation of the Sedov-von Neumann-Taylor blast wave solution",
    LA-UR-00-6055 (2000): closed-form solution in the parameter V for
    j = 3 (spherical), omega = 0 (uniform density), the "standard" case.
    With j2w = j + 2 - omega = 5:
        a = j2w (g+1)/4, b = (g+1)/(g-1), c = j2w g/2,
        d = j2w (g+1) / (j2w (g+1) - 2 (2 + j (g-1))), e = (2 + j (g-1))/2,
        alpha0 = 2/j2w, alpha2 = -(g-1)/(2 (g-1) + j),
        alpha1 = j2w g/(2 + j (g-1)) (2 j (2-g)/(g j2w^2) - alpha2),
        alpha3 = j/(2 (g-1) + j), alpha4 = alpha1 j2w/(2-g),
        alpha5 = -2/(2-g),
        x1 = a V, x2 = b (c V - 1), x3 = d (1 - e V), x4 = b (1 - c V/g),
        lambda = x1^-alpha0 x2^-alpha2 x3^-alpha1,
        u/u_s   = F = x1 lambda,
        rho/rho_s = G = x2^alpha3 x3^alpha4 x4^alpha5,
        p/p_s   = H = x1^(j alpha0) x3^(alpha4 - 2 alpha1) x4^(1 + alpha5),
    for V from V0 = 2/(j2w g) (centre) to V2 = 4/(j2w (g+1)) (shock), and
    the strong-shock values u_s = 2/(g+1) D, rho_s = b rho0,
    p_s = 2/(g+1) rho0 D^2 with D = dr_s/dt = (2/5) r_s/t.
  * Energy integral (same references; derived again here):
        E0 = int_0^r_s (rho u^2/2 + p/(g-1)) 4 pi r^2 dr
    gives alpha = 32 pi / (25 (g^2 - 1)) int_0^1 (G F^2 + H) lambda^2 dlambda.
  * Independent check: the self-similar ODEs of the Euler equations
    (L. I. Sedov, "Similarity and Dimensional Methods in Mechanics", 1959,
    ch. IV), derived again here with u = D f, rho = rho0 g, p = rho0 D^2 h
    of xi = r/r_s, delta = 2/5:
        (f - xi) g' + g f' + 2 f g / xi = 0
        (f - xi) f' + h'/g = (1 - delta)/delta f
        (f - xi) (h'/h - gamma g'/g) = 2 (1 - delta)/delta
    integrated from the shock (Rankine-Hugoniot values) inward with RK4
    in ln(xi) until the centre asymptotics f = xi/gamma, h = const,
    g ~ xi^(3/(gamma-1)) hold (the inward integration is unstable closer
    in); then alpha = 4 pi delta^2 int (g f^2/2 + h/(g-1)) xi^2 dxi.

Numerics (our own; no scipy).  lambda(V) is evaluated in the variable
s = ln(cV - 1), which resolves the centre (V -> V0, where V - V0 falls below
double-precision resolution long before lambda reaches 0); lambda -> V is
inverted by vectorised bisection on s.  The energy integral uses composite
Gauss-Legendre quadrature in lambda.  The closed form is singular at
gamma = 2 (alpha4 and alpha5 diverge; the product stays finite); within
1e-4 of 2 the ODE method is used instead.  The ODE method is checked
against the closed form to 1e-7 for 1.1 <= gamma <= 2.5 and refused above
gamma = 3 (the approach to the centre gets too slow for the unstable
inward integration).  gamma -> 7 is the edge of the standard case.

Usage:
    sol = Sedov(gamma=1.4)
    sol.alpha                      # 0.851072...
    sol.shock_radius(t, E0, rho0)
    rho, u, p, e = sol.solution(r, t, E0, rho0)
"""

import math

import numpy as np

SPHERE = 3          # geometry index j (spherical)
DELTA = 2.0 / 5.0   # r_s ~ t^delta


class Sedov:
    """Self-similar Sedov-Taylor solution for one gamma (spherical, omega=0)."""

    def __init__(self, gamma=1.4, method="auto", panels=256):
        """Set up the solution; method is 'closed', 'ode' or 'auto'."""
        g = float(gamma)
        if not 1.0 < g < 7.0:
            raise ValueError(f"gamma must be in (1, 7) for the standard case, got {g}")
        self.gamma = g
        if method == "auto":
            method = "ode" if abs(g - 2.0) < 1.0e-4 else "closed"
        if method not in ("closed", "ode"):
            raise ValueError(f"method must be 'closed', 'ode' or 'auto', got {method}")
        if method == "ode" and g > 3.0:
            raise ValueError("the ODE method is only reliable for gamma <= 3")
        self.method = method
        self._panels = panels
        if method == "closed":
            self._setup_closed()
        else:
            self._setup_ode()
        self.alpha = self._alpha()

    # ----------------------------------------------------------------- closed
    def _setup_closed(self):
        """Constants of the Kamm-Timmes closed form (j = 3, omega = 0)."""
        g = self.gamma
        j = float(SPHERE)
        j2w = j + 2.0
        self.a = 0.25 * j2w * (g + 1.0)
        self.b = (g + 1.0) / (g - 1.0)
        self.c = 0.5 * j2w * g
        self.d = j2w * (g + 1.0) / (j2w * (g + 1.0) - 2.0 * (2.0 + j * (g - 1.0)))
        self.e = 0.5 * (2.0 + j * (g - 1.0))
        self.alpha0 = 2.0 / j2w
        self.alpha2 = -(g - 1.0) / (2.0 * (g - 1.0) + j)
        self.alpha1 = (j2w * g / (2.0 + j * (g - 1.0))
                       * (2.0 * j * (2.0 - g) / (g * j2w ** 2) - self.alpha2))
        self.alpha3 = j / (2.0 * (g - 1.0) + j)
        self.alpha4 = self.alpha1 * j2w / (2.0 - g)
        self.alpha5 = -2.0 / (2.0 - g)
        self.v0 = 2.0 / (j2w * g)
        self.v2 = 4.0 / (j2w * (g + 1.0))
        # s = ln(cV - 1) at the shock.
        self.s2 = math.log(self.c * self.v2 - 1.0)

    def _logs(self, s):
        """ln x1, ln x2, ln x3, ln x4 as functions of s = ln(cV - 1)."""
        v = (1.0 + np.exp(s)) / self.c
        ln_x1 = np.log(self.a * v)
        ln_x2 = math.log(self.b) + s
        ln_x3 = np.log(self.d * (1.0 - self.e * v))
        ln_x4 = np.log(self.b * (1.0 - self.c * v / self.gamma))
        return ln_x1, ln_x2, ln_x3, ln_x4

    def _ln_lambda(self, s):
        ln_x1, ln_x2, ln_x3, _ = self._logs(s)
        return -self.alpha0 * ln_x1 - self.alpha2 * ln_x2 - self.alpha1 * ln_x3

    def _s_of_lambda(self, lam):
        """Invert lambda(s) by bisection (lam in (0, 1], array)."""
        target = np.log(lam)
        hi = np.full_like(target, self.s2)
        # Near the centre ln(lambda) ~ -alpha2 (ln b + s) + const, so this
        # lower bound is close; it is then pushed down until it brackets.
        ln_x1, _, ln_x3, _ = self._logs(np.array(-700.0))
        const = -self.alpha0 * ln_x1 - self.alpha1 * ln_x3
        lo = (target - const) / (-self.alpha2) - math.log(self.b) - 10.0
        lo = np.minimum(lo, self.s2 - 1.0)
        for _ in range(200):
            bad = self._ln_lambda(lo) > target
            if not np.any(bad):
                break
            lo = np.where(bad, 2.0 * lo - self.s2, lo)
        for _ in range(110):
            mid = 0.5 * (lo + hi)
            below = self._ln_lambda(mid) < target
            lo = np.where(below, mid, lo)
            hi = np.where(below, hi, mid)
        return 0.5 * (lo + hi)

    def _profile_closed(self, lam):
        """F, G, H (normalised to the post-shock values) at lam in [0, 1]."""
        lam = np.asarray(lam, dtype=float)
        out_f = np.zeros_like(lam)
        out_g = np.zeros_like(lam)
        out_h = np.zeros_like(lam)
        inside = lam > 0.0
        s = self._s_of_lambda(lam[inside])
        ln_x1, ln_x2, ln_x3, ln_x4 = self._logs(s)
        out_f[inside] = np.exp(ln_x1) * lam[inside]
        out_g[inside] = np.exp(self.alpha3 * ln_x2 + self.alpha4 * ln_x3
                               + self.alpha5 * ln_x4)
        out_h[inside] = np.exp(SPHERE * self.alpha0 * ln_x1
                               + (self.alpha4 - 2.0 * self.alpha1) * ln_x3
                               + (1.0 + self.alpha5) * ln_x4)
        if np.any(~inside):
            # Centre: V = V0 exactly (s -> -inf): F = G = 0, H finite.
            v = self.v0
            ln_x1 = math.log(self.a * v)
            ln_x3 = math.log(self.d * (1.0 - self.e * v))
            ln_x4 = math.log(self.b * (1.0 - self.c * v / self.gamma))
            out_h[~inside] = math.exp(SPHERE * self.alpha0 * ln_x1
                                      + (self.alpha4 - 2.0 * self.alpha1) * ln_x3
                                      + (1.0 + self.alpha5) * ln_x4)
        return out_f, out_g, out_h

    # -------------------------------------------------------------------- ode
    def _ode_rhs(self, s, y):
        """d/ds of (f, ln g, ln h), s = ln(xi); see the module docstring."""
        g = self.gamma
        xi = math.exp(s)
        f, ln_g, ln_h = y
        h_over_g = math.exp(ln_h - ln_g)
        w = f - xi
        k = (1.0 - DELTA) / DELTA
        # Solve the 3x3 linear system for A = (ln g)', B = f', C = (ln h)'.
        a_prime = ((k * f + 2.0 * w * f / xi - 2.0 * k * h_over_g / w)
                   / (g * h_over_g - w * w))
        b_prime = -2.0 * f / xi - w * a_prime
        c_prime = g * a_prime + 2.0 * k / w
        return np.array([xi * b_prime, xi * a_prime, xi * c_prime])

    def _setup_ode(self, s_end=-12.0, steps_per_unit=2000, centre_tol=1.0e-9):
        """Integrate the similarity ODEs from the shock (s = 0) inward.

        The centre is a singular point that repels neighbouring solutions
        when integrating inward (a Jacobian eigenvalue -2 in s: errors grow
        like xi^-2 while f ~ xi).  So the integration stops as soon as the
        flow has reached its centre asymptotics, |gamma f/xi - 1| <
        centre_tol (f/xi -> 1/gamma, approached like a high power of xi),
        and _profile_ode continues with the exact centre power laws.
        """
        g = self.gamma
        ds = -1.0 / steps_per_unit
        y = np.array([2.0 / (g + 1.0), math.log((g + 1.0) / (g - 1.0)),
                      math.log(2.0 / (g + 1.0))])
        s = 0.0
        s_list, values, slopes = [s], [y], [self._ode_rhs(s, y)]
        while s > s_end:
            k1 = slopes[-1]
            k2 = self._ode_rhs(s + 0.5 * ds, y + 0.5 * ds * k1)
            k3 = self._ode_rhs(s + 0.5 * ds, y + 0.5 * ds * k2)
            k4 = self._ode_rhs(s + ds, y + ds * k3)
            y = y + ds / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
            s = s + ds
            s_list.append(s)
            values.append(y)
            slopes.append(self._ode_rhs(s, y))
            if abs(g * y[0] / math.exp(s) - 1.0) < centre_tol:
                break
        # Stored increasing in s for interpolation; entry 0 is the cut-off.
        self._ode_s = np.array(s_list[::-1])
        self._ode_y = np.array(values[::-1])
        self._ode_dy = np.array(slopes[::-1])

    def _profile_ode(self, lam):
        """F, G, H from the ODE table (cubic Hermite in s = ln lambda)."""
        g = self.gamma
        lam = np.asarray(lam, dtype=float)
        s = np.log(np.maximum(lam, 1.0e-300))
        s_tab, y_tab, dy_tab = self._ode_s, self._ode_y, self._ode_dy
        s_c = np.clip(s, s_tab[0], s_tab[-1])
        i = np.clip(np.searchsorted(s_tab, s_c) - 1, 0, len(s_tab) - 2)
        h = s_tab[i + 1] - s_tab[i]
        tau = (s_c - s_tab[i]) / h
        h00 = (1.0 + 2.0 * tau) * (1.0 - tau) ** 2
        h10 = tau * (1.0 - tau) ** 2
        h01 = tau * tau * (3.0 - 2.0 * tau)
        h11 = tau * tau * (tau - 1.0)
        y = (h00[:, None] * y_tab[i] + h10[:, None] * h[:, None] * dy_tab[i]
             + h01[:, None] * y_tab[i + 1] + h11[:, None] * h[:, None] * dy_tab[i + 1])
        # Below the table, the centre power laws (also in the closed form):
        # f = xi/gamma, h = const, g ~ xi^(3/(gamma-1)).
        below = s < s_tab[0]
        ds = s - s_tab[0]
        f = np.where(below, np.exp(s) / g, y[:, 0])
        ln_g = np.where(below, y_tab[0, 1] + 3.0 / (g - 1.0) * ds, y[:, 1])
        ln_h = np.where(below, y_tab[0, 2], y[:, 2])
        big_f = f * (g + 1.0) / 2.0
        big_g = np.exp(ln_g) * (g - 1.0) / (g + 1.0)
        big_h = np.exp(ln_h) * (g + 1.0) / 2.0
        big_f = np.where(lam > 0.0, big_f, 0.0)
        big_g = np.where(lam > 0.0, big_g, 0.0)
        return big_f, big_g, big_h

    # ---------------------------------------------------------------- public
    def profile(self, lam):
        """Normalised F = u/u_s, G = rho/rho_s, H = p/p_s at lam = r/r_s <= 1."""
        if self.method == "closed":
            return self._profile_closed(lam)
        return self._profile_ode(lam)

    def _alpha(self):
        """Energy constant from composite Gauss-Legendre quadrature in lambda."""
        nodes, weights = np.polynomial.legendre.leggauss(16)
        edges = np.linspace(0.0, 1.0, self._panels + 1)
        half = 0.5 * np.diff(edges)
        mid = 0.5 * (edges[1:] + edges[:-1])
        lam = (mid[:, None] + half[:, None] * nodes[None, :]).ravel()
        wts = (half[:, None] * weights[None, :]).ravel()
        big_f, big_g, big_h = self.profile(lam)
        integral = np.sum(wts * (big_g * big_f ** 2 + big_h) * lam ** 2)
        g = self.gamma
        return 32.0 * math.pi / (25.0 * (g * g - 1.0)) * integral

    def shock_radius(self, t, E0=0.851072, rho0=1.0):
        """r_s = (E0 t^2 / (alpha rho0))^(1/5)."""
        return (E0 * t * t / (self.alpha * rho0)) ** 0.2

    def solution(self, r, t, E0=0.851072, rho0=1.0):
        """rho, u (radial), p, e at radii r (array) and time t > 0.

        Outside the shock the gas is at rest, cold: rho0, 0, 0, 0.  At the
        centre rho -> 0 and e = p/((g-1) rho) -> infinity (inf at r = 0).
        """
        if not t > 0.0:
            raise ValueError("the Sedov solution needs t > 0")
        g = self.gamma
        r = np.abs(np.asarray(r, dtype=float))
        r_s = self.shock_radius(t, E0, rho0)
        speed = DELTA * r_s / t
        lam = r / r_s
        inside = lam <= 1.0
        rho = np.full_like(r, rho0)
        u = np.zeros_like(r)
        p = np.zeros_like(r)
        if np.any(inside):
            big_f, big_g, big_h = self.profile(lam[inside])
            rho[inside] = rho0 * (g + 1.0) / (g - 1.0) * big_g
            u[inside] = 2.0 / (g + 1.0) * speed * big_f
            p[inside] = 2.0 / (g + 1.0) * rho0 * speed ** 2 * big_h
        with np.errstate(divide="ignore", invalid="ignore"):
            e = np.where(rho > 0.0, p / ((g - 1.0) * np.where(rho > 0.0, rho, 1.0)), np.inf)
        e = np.where(p > 0.0, e, 0.0)
        return rho, u, p, e


def alpha(gamma=1.4):
    """Energy constant alpha(gamma) of the spherical standard case."""
    return Sedov(gamma).alpha


def solution(r, t, E0=0.851072, rho0=1.0, gamma=1.4):
    """rho, u, p, e at radii r, time t (convenience wrapper)."""
    return Sedov(gamma).solution(r, t, E0, rho0)


def main():
    """Print alpha for a few gammas by both methods and the gamma=1.4 check."""
    for g in (1.2, 1.4, 5.0 / 3.0, 3.0):
        closed = Sedov(g, method="closed").alpha
        ode = Sedov(g, method="ode").alpha
        print(f"gamma = {g:.6f}  alpha(closed) = {closed:.9f}  alpha(ode) = {ode:.9f}")
    sol = Sedov(1.4)
    print(f"gamma = 1.4, E0 = 0.851072, rho0 = 1: r_s(t=1) = {sol.shock_radius(1.0):.7f}")


if __name__ == "__main__":
    main()
