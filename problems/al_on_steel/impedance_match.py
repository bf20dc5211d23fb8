#!/usr/bin/python3
"""Semi-analytic 1D elastic-plastic impedance match for docs/problems.md, D3.

Al 6061-T6 at 0.1 cm/us onto 304 SS at rest, uniaxial strain, with the data and
the models of the code (src/eos/eos_mie_gruneisen.f90, src/material/
material_flow_stress.f90, library sets 'al6061' and 'ss304'; read, not
imported). Units cm, g, us, Mbar; stress positive in compression.

Each side is a two-wave structure, solved with the Rankine-Hugoniot relations:

1. an elastic precursor from rest to the Hugoniot elastic limit: a shock on
   the Rayleigh line sigma = m^2 (V0 - V), e = sigma (V0 - V) / 2, with
   sigma = p_MG(rho, e) + S, S = (4/3) G ln(rho/rho0) (hypoelastic, uniaxial
   strain; G(p, T, eta) averaged between the two ends), and the limit where
   S = 2 Y(0, p, T, eta) / 3;
2. a plastic shock from that state to the final state, with
   sigma2 - sigma1 = m^2 (V1 - V2), e2 = e1 + (sigma1 + sigma2)(V1 - V2) / 2 and
   sigma2 = p_MG(rho2, e2) + 2 Y(eps_p, p2, T2, eta2) / 3, where
   eps_p = (2/3) ln(rho2/rho1) - (Y2 - Y1) / (3 G2) (radial return in uniaxial
   strain: d eps_p = (2/3) d ln rho - dY / (3 G)) and T = 300 K + e / cv.

The interface velocity u solves sigma_al(0.1 - u) = sigma_ss(u). Also printed,
for comparison, the old reference (Hugoniot stress rho0 (c0 + s1 up) up plus
2 Y0 / 3) and the same with the yield of the shocked state.

Usage: impedance_match.py [--velocity 0.1]
"""
import argparse
import math

# Mie-Grueneisen (rho0, c0, s1, gamma0, b) and Steinberg-Guinan (g0, y0, ymax,
# beta, n, A, B, tm0, a_melt, cv), as in src/material (library sets).
AL = dict(rho0=2.703, c0=0.524, s1=1.40, gamma0=1.97, b=0.48,
          g0=0.276, y0=0.0029, ymax=0.0068, beta=125.0, n=0.10, a=6.52, bt=6.16e-4,
          tm0=1220.0, a_melt=1.5, cv=0.90e-5)
SS = dict(rho0=7.90, c0=0.457, s1=1.49, gamma0=1.93, b=0.5,
          g0=0.770, y0=0.0034, ymax=0.0250, beta=43.0, n=0.35, a=2.26, bt=4.55e-4,
          tm0=2380.0, a_melt=1.43, cv=0.50e-5)


def pressure(m, rho, e):
    """Steinberg's Mie-Grueneisen pressure (compression and expansion branches)."""
    mu = rho / m["rho0"] - 1.0
    big_e = m["rho0"] * e
    if mu > 0.0:
        ref = (m["rho0"] * m["c0"] ** 2 * mu * (1.0 + (1.0 - m["gamma0"] / 2.0) * mu
                                               - m["b"] / 2.0 * mu ** 2)
               / (1.0 - (m["s1"] - 1.0) * mu) ** 2)
    else:
        ref = m["rho0"] * m["c0"] ** 2 * mu
    return ref + (m["gamma0"] + m["b"] * mu) * big_e


def softening(m, p, e, eta):
    """G/G0 = max(1 + A p eta^(-1/3) - B (T - 300), 0), zero at or above melt."""
    t = 300.0 + e / m["cv"]
    tm = (m["tm0"] * math.exp(2.0 * m["a_melt"] * (1.0 - 1.0 / eta))
          * eta ** (2.0 * (m["gamma0"] - m["a_melt"] - 1.0 / 3.0)))
    if t >= tm:
        return 0.0
    return max(1.0 + m["a"] * p / eta ** (1.0 / 3.0) - m["bt"] * (t - 300.0), 0.0)


def yield_stress(m, eps_p, p, e, eta):
    hardened = m["y0"] * (1.0 + m["beta"] * max(eps_p, 0.0)) ** m["n"]
    return min(hardened, m["ymax"]) * softening(m, p, e, eta)


def elastic_state(m, rho):
    """State on the elastic Rayleigh line from rest at density rho."""
    v0, v = 1.0 / m["rho0"], 1.0 / rho
    eta = rho / m["rho0"]
    sigma, e, p = 0.0, 0.0, 0.0
    for _ in range(200):
        e = 0.5 * sigma * (v0 - v)
        p = pressure(m, rho, e)
        g = m["g0"] * 0.5 * (1.0 + softening(m, p, e, eta))
        s = 4.0 / 3.0 * g * math.log(eta)
        sigma_new = p + s
        if abs(sigma_new - sigma) < 1e-15:
            break
        sigma = sigma_new
    return dict(rho=rho, sigma=sigma, e=e, p=p, s=s, u=math.sqrt(sigma * (v0 - v)),
                y=yield_stress(m, 0.0, p, e, eta), g=g)


def hel_state(m):
    """Elastic precursor state at the Hugoniot elastic limit (bisection on rho)."""
    lo, hi = m["rho0"], 1.2 * m["rho0"]
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        st = elastic_state(m, mid)
        if st["s"] < 2.0 * st["y"] / 3.0:
            lo = mid
        else:
            hi = mid
    return elastic_state(m, lo)


def plastic_state(m, hel, rho2):
    """State behind the plastic shock from the HEL state, at density rho2."""
    v1, v2 = 1.0 / hel["rho"], 1.0 / rho2
    eta2 = rho2 / m["rho0"]
    sigma2, y2, e2, p2 = hel["sigma"], hel["y"], hel["e"], hel["p"]
    for _ in range(500):
        e2 = hel["e"] + 0.5 * (hel["sigma"] + sigma2) * (v1 - v2)
        p2 = pressure(m, rho2, e2)
        g2 = m["g0"] * softening(m, p2, e2, eta2)
        eps_p = 2.0 / 3.0 * math.log(rho2 / hel["rho"]) - (y2 - hel["y"]) / (3.0 * max(g2, 1e-6))
        y2 = yield_stress(m, eps_p, p2, e2, eta2)
        sigma_new = p2 + 2.0 * y2 / 3.0
        if abs(sigma_new - sigma2) < 1e-15:
            break
        sigma2 = sigma_new
    du = math.sqrt(max(sigma2 - hel["sigma"], 0.0) * (v1 - v2))
    return dict(rho=rho2, sigma=sigma2, e=e2, p=p2, y=y2, eps_p=eps_p,
                t=300.0 + e2 / m["cv"], u=hel["u"] + du)


def state_at_velocity(m, up):
    """Shocked state with particle velocity jump up (two waves, or elastic only)."""
    hel = hel_state(m)
    if up <= hel["u"]:
        lo, hi = m["rho0"], hel["rho"]
        for _ in range(100):
            mid = 0.5 * (lo + hi)
            if elastic_state(m, mid)["u"] < up:
                lo = mid
            else:
                hi = mid
        return elastic_state(m, lo), hel
    lo, hi = hel["rho"], 1.4 * m["rho0"]
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if plastic_state(m, hel, mid)["u"] < up:
            lo = mid
        else:
            hi = mid
    return plastic_state(m, hel, lo), hel


def match(stress, v):
    """Interface velocity u with stress(al, v - u) = stress(ss, u), by bisection."""
    lo, hi = 0.0, v
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if stress(AL, v - mid) > stress(SS, mid):
            lo = mid
        else:
            hi = mid
    return lo, stress(SS, lo)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--velocity", type=float, default=0.1, help="Al impact speed (cm/us)")
    a = ap.parse_args()
    v = a.velocity

    def hugoniot_y0(m, up):
        return m["rho0"] * (m["c0"] + m["s1"] * up) * up + 2.0 * m["y0"] / 3.0

    u_old, s_old = match(hugoniot_y0, v)
    print("old reference, Hugoniot stress + 2 Y0/3: u = %.5f cm/us, sigma_zz = %.5f Mbar"
          % (u_old, s_old))
    u, sigma = match(lambda m, up: state_at_velocity(m, up)[0]["sigma"], v)
    for name, m, up in (("al", AL, v - u), ("ss", SS, u)):
        st, hel = state_at_velocity(m, up)
        us_plastic = (hel["u"] + (st["rho"] * (st["u"] - hel["u"]))
                      / (st["rho"] - hel["rho"]))
        print("%s: HEL %.5f Mbar (u %.5f, Y %.5f); shocked: up %.5f, rho %.4f, p %.5f, "
              "Y %.5f, eps_p %.4f, T %.0f K, sigma_zz %.5f; plastic shock %.4f cm/us"
              % (name, hel["sigma"], hel["u"], hel["y"], up, st["rho"], st["p"], st["y"],
                 st["eps_p"], st["t"], st["sigma"], us_plastic))
    print("two-wave elastic-plastic match, SG yield of the shocked state: "
          "u = %.5f cm/us, sigma_zz = %.5f Mbar" % (u, sigma))

    def hugoniot_y(m, up):
        st = state_at_velocity(m, up)[0]
        return m["rho0"] * (m["c0"] + m["s1"] * up) * up + 2.0 * st["y"] / 3.0

    u_h, s_h = match(hugoniot_y, v)
    print("for comparison, Hugoniot stress + 2 Y/3 with that Y: u = %.5f, sigma_zz = %.5f"
          % (u_h, s_h))


if __name__ == "__main__":
    main()
