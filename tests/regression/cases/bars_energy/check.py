#!/usr/bin/python3
"""Contact energy of the equal and dissimilar elastic bars, bounded by
physics rather than by the bookkeeping (contact work is computed from the
contact forces, so the energy balance closes by construction).

Usage: check.py EXE WORKDIR --case equal|dissimilar --method dam|dlm
       [--mpiexec mpirun --np 1]

1. Elastic contact does no net work after the impact: from the end of the
   impact cycle on, through the whole contact and the release, the contact
   work changes by at most 1e-6 of the initial energy.
2. The impact cycle's loss is the inelastic stop of the two interface nodes
   (half-zone masses m_a, m_b): derived here for the predictor-corrector
   step and the contact in both stages.
     Predictor: the contact gives both interface nodes the common velocity
       V_h = (m_a v_a + m_b v_b) / (m_a + m_b) (no stress yet).
     Corrector: the first zone of each bar has closed by dt/2 times the jump
       d_i = |v_i - V_h| against its next node, so the interface node feels
       f_i = A (rho_i c_i^2 (dt/2) d_i / h_i + C1 rho_i c_i d_i + C2 rho_i d_i^2)
       toward the other bar (elastic 1D-strain stress, c_i the longitudinal
       speed, plus the linear and quadratic artificial viscosity, defaults
       C1 = 0.5, C2 = 2/3), and the contact makes both move at
       V = (m_a v_a + m_b v_b + dt (f_a + f_b)) / (m_a + m_b);
     the contact work of the cycle is sum_i F_i (v_i + V) dt / 2 with
       F_i = m_i (V - v_i) / dt - f_i.
   For equal bars this is -(m v0^2) (1 + CFL^2 + 2 CFL (C1 + C2 v0/c)) per
   pair of nodes: 1.7516 / (2 N) of E0 at CFL 0.5 and N zones per bar.
   Tolerance: the estimate is linear in the strain; the Mie-Grueneisen
   stiffening and the change of c with it are of relative size v0 / c
   (1.6e-3 for Al at 1e-3 cm/us), the tolerance.
3. The loss halves when h halves (m, dt and h all scale with h at fixed
   CFL): the loss at 2N zones is half the loss at N, within the same v0 / c.
"""

import argparse
import os
import shutil
import subprocess
import sys

import numpy as np

from impact3d_tools import history

HERE = os.path.dirname(os.path.abspath(__file__))
DECKS = os.path.join(HERE, "..", "..", "decks")
AREA = 1.0e-4  # 0.01 x 0.01 cm, from the decks
# Densities (g/cm^3) and longitudinal speeds c = sqrt(c0^2 + 4G/(3 rho0))
# (cm/us) of the library materials, as the decks' comments give them.
AL = (2.703, 0.640875)
SS = (7.90, 0.582071)
C1, C2 = 0.5, 2.0 / 3.0  # &hydro defaults: q_linear, q_quadratic
FAILED = []


def check(name, ok, detail=""):
    print(("PASS " if ok else "FAIL ") + name + ("" if ok or not detail else ": " + detail))
    if not ok:
        FAILED.append(name)


def estimate(a, b, dt):
    """Contact work of the impact cycle; a, b = (rho, c, h, v)."""
    (ra, ca, ha, va), (rb, cb, hb, vb) = a, b
    ma, mb = ra * AREA * ha / 2, rb * AREA * hb / 2
    vh = (ma * va + mb * vb) / (ma + mb)

    def force(rho, c, h, d):
        return AREA * (rho * c * c * (dt / 2) * d / h + C1 * rho * c * d + C2 * rho * d * d)

    fa, fb = force(ra, ca, ha, abs(va - vh)), -force(rb, cb, hb, abs(vh - vb))
    v = (ma * va + mb * vb + dt * (fa + fb)) / (ma + mb)
    work = 0.0
    for m, vi, f in ((ma, va, fa), (mb, vb, fb)):
        work += (m * (v - vi) / dt - f) * (vi + v) / 2 * dt
    return work


def run(a, deck_text, wd):
    if os.path.isdir(wd):
        shutil.rmtree(wd)
    os.makedirs(wd)
    with open(os.path.join(wd, "deck.nml"), "w") as f:
        f.write(deck_text)
    p = subprocess.run([a.mpiexec, "-np", str(a.np), os.path.abspath(a.exe), "deck.nml"],
                       cwd=wd, capture_output=True, text=True)
    if p.returncode != 0:
        check("run in %s exits 0" % wd, False, (p.stdout + p.stderr)[-1500:])
        return None
    return history.columns(wd)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("workdir")
    ap.add_argument("--case", required=True, choices=["equal", "dissimilar"])
    ap.add_argument("--method", required=True, choices=["dam", "dlm"])
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--np", type=int, default=1)
    a = ap.parse_args()
    with open(os.path.join(DECKS, "bars_%s_%s.nml" % (a.case, a.method))) as f:
        deck = f.read()
    if a.case == "equal":
        v0, nb = 1.0e-3, 200
        left, right = AL, AL
        vb = -v0
    else:
        v0, nb = 1.0e-3, 170
        left, right = AL, SS
        vb = 0.0
    tol = v0 / min(left[1], right[1])
    losses = []
    for scale in (1, 2):
        text = deck.replace("nx = 200", "nx = %d" % (200 * scale)).replace(
            "nx = 170", "nx = %d" % (170 * scale))
        if scale == 2:
            # Only the impact cycle matters at 2N.
            text = text.replace("t_end = 4.0", "t_end = 0.01")
        h = run(a, text, os.path.join(a.workdir, "n%d" % scale))
        if h is None:
            return finish()
        e0 = h["total_energy"][0]
        w = h["contact_work"]
        assert h["cycle"][0] == 0 and h["cycle"][1] == 1
        dt = h["dt"][1]
        est = estimate((left[0], left[1], 1.0 / (200 * scale), v0),
                       (right[0], right[1], 1.0 / (nb * scale), vb), dt)
        rel = abs(w[1] / est - 1.0)
        check("N x %d: impact-cycle loss %.6e E0 = the nodal estimate %.6e E0 (|ratio - 1| "
              "%.1e <= v0/c = %.1e)" % (scale, -w[1] / e0, -est / e0, rel, tol), rel <= tol)
        losses.append(w[1] / e0)
        if scale == 1:
            drift = np.max(np.abs(w[1:] - w[1])) / abs(e0)
            check("after the impact cycle the contact work changes by %.1e E0 <= 1e-6 "
                  "(to t = %.2f, through contact and release)" % (drift, h["time"][-1]),
                  drift <= 1e-6)
    ratio = losses[1] / losses[0]
    check("the loss halves when h halves: ratio %.6f = 0.5 within v0/c" % ratio,
          abs(ratio / 0.5 - 1.0) <= tol)
    return finish()


def finish():
    print("%d failed" % len(FAILED))
    return 1 if FAILED else 0


if __name__ == "__main__":
    sys.exit(main())
