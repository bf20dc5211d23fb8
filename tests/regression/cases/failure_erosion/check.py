#!/usr/bin/python3
"""Failure, erosion and the kinetic-energy stop (docs/user-guide.md, &material
failure keys, &erosion, &control stop_block). Usage:

  check.py EXE WORKDIR --case failure|erosion|stop|spall [--mpiexec mpirun --np 1]

failure (bar_failure.nml): a bar in 1D strain stretched homogeneously (the
  initial velocity field v0 x / L, the end x = L held at v0) with linear
  hardening and failure = 'plastic_strain' at eps_f = 0.1, no erosion.
  1. Each zone fails in the cycle in which its plastic strain crosses eps_f:
     the first probe row with eps_p >= eps_f has the previous row below it,
     and from that row on the deviatoric stress is 0 (before: not) and the
     pressure >= 0 (before: tension, so the clip acts).
  2. The time: in 1D strain the equivalent deviatoric strain is 2/3 of the
     axial log strain ln(1 + v0 t / L), shared between the plastic strain and
     the elastic part sbar / (3 G), sbar = Y + H eps_p, so
       t_f = (L / v0) (exp(1.5 (eps_f + (Y + H eps_f) / (3 G))) - 1).
     The midpoint integration of the strain rate is second order in dt, so
     t_f lies within the failing cycle, widened by one step on each side.
  3. Energy balance at round-off (below).
erosion (bar_erosion.nml): the same bar, the zone at x = L of material
  'weak' (eps_f = 0.05, erode): it is eroded, its four end nodes (used by no
  other zone) leave.
  1. eroded_zones goes 0 -> 1 in one row and stays 1; eroded_zone_mass is
     the zone's mass, eroded_node_mass the four end nodes' mass (half the
     zone's), eroded_kinetic their 4 x m v0^2 / 2 (they move at the held
     v0): exact sums of equal terms, so equal to the history's printed
     precision (16 digits: 1e-15 relative).
  2. weak_internal is 0 from that row on and eroded_internal constant
     (an eroded zone takes no work).
  3. The energy balance closes at round-off with the eroded columns, and
     would not without them (the jump they book is far above the bound).
  4. Dumps: /zones/alive 0 for that zone only; /mesh/live_connectivity
     collapses it onto one node, /mesh/connectivity stays complete; the end
     nodes are frozen (same position in every later dump, velocity 0).
stop (bar_stop.nml): elastic bar onto a wall, stop_block = 'bar' at 0.5.
  1. Exit 0 with the message and a final dump; the last history row is the
     first whose kinetic energy is below half of the first row's (the same
     exact sum as the stop's).
  2. The time is L / (2 c) within 3 h / c (the width of the wave front
     spread by the artificial viscosity) plus one step.

spall (plate_spall.nml): symmetric plate impact, flyer 0.2 cm onto a 0.4 cm
  target, spall_strength 0.01 Mbar, no erosion.
  1. Zones fail, all in the target, all within 0.1 cm (a quarter of the
     target) of x = 0.4, where the two release waves meet in the acoustic
     approximation (the shocks run a few percent faster than sound at this
     speed; the spalled layer has the width of the tension above 0.01 Mbar).
  2. Every failed zone has pressure >= 0 and no deviatoric stress, and the
     spall opens: a failed zone stretched beyond 5% while every live target
     zone stays below it (elastic tension at the spall strength is 1.4%).
  3. Energy balance at round-off.

Round-off bound of the energy balance: each cycle changes each energy term by
a few roundings of its size; over N cycles the error is below
N x 8 eps x (largest of internal, kinetic, boundary work), N about 1e3 here,
so 2e-12 of the largest term.
"""

import argparse
import math
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

from impact3d_tools import history

HERE = os.path.dirname(os.path.abspath(__file__))
FAILED = []
# &material data of the decks (al6061 library: G = 0.276 Mbar; c the
# longitudinal speed sqrt(c0^2 + 4 G / (3 rho0)) of the library, cm/us).
G, Y, H = 0.276, 3.0e-3, 3.0e-2
V0, L = 2.0e-3, 1.0
C_LONG = 0.640875


def check(name, ok, detail=""):
    print(("PASS " if ok else "FAIL ") + name + ("" if ok or not detail else ": " + detail))
    if not ok:
        FAILED.append(name)


def run(a, deck, wd):
    if os.path.isdir(wd):
        shutil.rmtree(wd)
    os.makedirs(wd)
    p = subprocess.run([a.mpiexec, "-np", str(a.np), os.path.abspath(a.exe),
                        os.path.join(HERE, deck)], cwd=wd, capture_output=True, text=True)
    check("%s exits 0" % deck, p.returncode == 0, (p.stdout + p.stderr)[-1500:])
    return p


def same(column, value):
    """The history's values equal value: history.txt prints 16 significant
    digits (es23.15), a relative rounding of at most 5e-16, so 1e-15."""
    return bool(np.all(np.abs(column - value) <= 1.0e-15 * abs(value)))


def balance(h, what):
    err = h["energy_error"]
    e0 = h["total_energy"][0]
    scale = max(np.abs(h["internal_energy"]).max(), np.abs(h["kinetic_energy"]).max(),
                np.abs(h["boundary_work"]).max())
    bound = 2.0e-12 * scale
    worst = np.abs(err).max() * e0
    check("%s: energy balance at round-off (|error| %.2e <= %.2e)" % (what, worst, bound),
          worst <= bound)
    return bound, e0


def case_failure(a):
    wd = os.path.join(a.workdir, "failure")
    if run(a, "bar_failure.nml", wd).returncode != 0:
        return
    eps_f = 0.1
    t_pred = L / V0 * (math.exp(1.5 * (eps_f + (Y + H * eps_f) / (3 * G))) - 1.0)
    for k in range(1, 11):
        t = history.read_table(os.path.join(wd, "probe_z%d.csv" % k))
        eps = t["plastic_strain"]
        s = np.column_stack([t["deviatoric_stress_" + c] for c in
                             ("xx", "yy", "zz", "xy", "yz", "zx")])
        p = t["pressure"]
        time = t[t.time_name()]
        hit = np.nonzero(eps >= eps_f)[0]
        if not len(hit):
            check("zone %d fails" % k, False, "plastic strain reaches %.4f" % eps.max())
            continue
        i = hit[0]
        check("zone %d: fails in the cycle its plastic strain crosses %.2f" % (k, eps_f),
              eps[i - 1] < eps_f <= eps[i] and np.any(s[i - 1] != 0.0)
              and np.all(s[i:] == 0.0),
              "eps %r, stress before %r" % (eps[i - 1:i + 1], s[i - 1]))
        check("zone %d: no tension once failed (p %.3e before, min %.3e after)"
              % (k, p[i - 1], p[i:].min()), p[i - 1] < 0.0 and p[i:].min() >= 0.0)
        dt = time[i] - time[i - 1]
        check("zone %d: fails at t = %.4f, derived %.4f (window [%.4f, %.4f])"
              % (k, time[i], t_pred, time[i - 1] - dt, time[i] + dt),
              time[i - 1] - dt <= t_pred <= time[i] + dt)
    h = history.read(wd)
    balance(h, "failure")
    check("failure without erosion: no eroded columns", "eroded_zones" not in h)
    last = sorted(f for f in os.listdir(wd) if f.startswith("dump_") and f.endswith(".h5"))[-1]
    with h5py.File(os.path.join(wd, last), "r") as f:
        check("final dump: damage 1 in every zone, no /zones/alive",
              np.all(f["zones/damage"][()] == 1.0) and "alive" not in f["zones"])


def case_erosion(a):
    wd = os.path.join(a.workdir, "erosion")
    if run(a, "bar_erosion.nml", wd).returncode != 0:
        return
    h = history.read(wd)
    n = h["eroded_zones"]
    first = np.nonzero(n > 0)[0]
    if not len(first):
        check("the weak zone is eroded", False)
        return
    i = first[0]
    check("eroded_zones 0 -> 1 at cycle %d and stays 1" % h["cycle"][i],
          np.all(n[:i] == 0) and np.all(n[i:] == 1))
    with h5py.File(os.path.join(wd, "dump_000000.h5"), "r") as f:
        zmass = f["zones/mass"][()]
        nmass = f["nodes/mass"][()]
        x0 = f["mesh/coordinates"][()]
        conn0 = f["mesh/connectivity"][()]
    end = np.nonzero(x0[:, 0] == L)[0]
    m_nodes = 0.0
    ke = 0.0
    for j in end:
        m_nodes += nmass[j]
        ke += 0.5 * nmass[j] * (V0 * V0)
    check("eroded_zone_mass = the zone's mass (%.6e)" % zmass[9],
          same(h["eroded_zone_mass"][i:], zmass[9]))
    check("eroded_node_mass = the 4 end nodes' mass (%.6e, half the zone's)" % m_nodes,
          len(end) == 4 and same(h["eroded_node_mass"][i:], m_nodes)
          and m_nodes == 0.5 * zmass[9])
    check("eroded_kinetic = 4 m v0^2 / 2 of the end nodes (%.6e)" % ke,
          same(h["eroded_kinetic"][i:], ke))
    ei = h["eroded_internal"]
    check("weak_internal 0 after, eroded_internal constant and positive",
          np.all(h["weak_internal"][i:] == 0.0) and h["weak_internal"][i - 1] > 0.0
          and np.all(ei[i:] == ei[i]) and ei[i] > 0.0 and np.all(ei[:i] == 0.0))
    bound, e0 = balance(h, "erosion")
    moved = ei[i] + h["eroded_kinetic"][i]
    check("the eroded columns matter: without them the balance would jump by %.2e > %.2e"
          % (moved, bound), moved > 100 * bound)
    dumps = sorted(f for f in os.listdir(wd) if f.startswith("dump_") and f.endswith(".h5"))
    after = [d for d in dumps if int(d[5:11]) >= h["cycle"][i]]
    positions = []
    for d in after:
        with h5py.File(os.path.join(wd, d), "r") as f:
            alive = f["zones/alive"][()]
            live = f["mesh/live_connectivity"][()]
            conn = f["mesh/connectivity"][()]
            x = f["mesh/coordinates"][()]
            v = f["nodes/velocity"][()]
        check("%s: alive 0 for the eroded zone only; live_connectivity collapses it; "
              "connectivity complete" % d,
              np.all(alive[:9] == 1.0) and alive[9] == 0.0 and np.all(live[9] == live[9][0])
              and np.array_equal(live[:9], conn0[:9]) and np.array_equal(conn, conn0))
        check("%s: the end nodes are at rest" % d, np.all(v[end] == 0.0))
        positions.append(x[end])
    check("the end nodes keep their last position in every later dump (%d dumps)"
          % len(positions), len(positions) > 1 and all(np.array_equal(positions[0], q)
                                                       for q in positions))


def case_stop(a):
    wd = os.path.join(a.workdir, "stop")
    p = run(a, "bar_stop.nml", wd)
    if p.returncode != 0:
        return
    check("stop message names the block", "kinetic energy of block 'bar'" in p.stdout,
          p.stdout[-800:])
    h = history.read(wd)
    k = h["kinetic_energy"]
    check("the run ends at the first row below half the initial kinetic energy",
          k[-1] < 0.5 * k[0] and np.all(k[:-1] >= 0.5 * k[0]))
    t = h["time"][-1]
    dt = h["dt"][-1]
    t_star = L / (2 * C_LONG)
    tol = 3 * 0.01 / C_LONG + dt
    check("stop time %.4f = L / (2 c) = %.4f within %.4f" % (t, t_star, tol),
          abs(t - t_star) <= tol and t < 10.0)
    final = os.path.join(wd, "dump_%06d.h5" % h["cycle"][-1])
    ok = os.path.exists(final)
    if ok:
        with h5py.File(final, "r") as f:
            ok = f["run"].attrs["reason"].decode() == "final" if isinstance(
                f["run"].attrs["reason"], bytes) else str(f["run"].attrs["reason"]) == "final"
    check("a final dump at the last cycle (reason 'final')", ok)


def case_spall(a):
    wd = os.path.join(a.workdir, "spall")
    if run(a, "plate_spall.nml", wd).returncode != 0:
        return
    last = sorted(f for f in os.listdir(wd) if f.startswith("dump_") and f.endswith(".h5"))[-1]
    with h5py.File(os.path.join(wd, last), "r") as f:
        d = f["zones/damage"][()]
        p = f["zones/pressure"][()]
        s = f["zones/deviatoric_stress"][()].reshape(-1, 6)
        block = f["mesh/block"][()]
        conn = f["mesh/connectivity"][()].reshape(-1, 8)
        v = f["zones/volume"][()]
    with h5py.File(os.path.join(wd, "dump_000000.h5"), "r") as f:
        x0 = f["mesh/coordinates"][()][:, 0]
        v0 = f["zones/volume"][()]
    failed = d >= 1.0
    centre = x0[conn].mean(axis=1)
    check("zones spall (%d), all in the target, within 0.1 of x = 0.4 (%.3f .. %.3f)"
          % (failed.sum(), centre[failed].min() if failed.any() else 0,
             centre[failed].max() if failed.any() else 0),
          failed.any() and np.all(block[failed] == 2)
          and np.all(np.abs(centre[failed] - 0.4) <= 0.1))
    check("failed zones: p >= 0 and no deviatoric stress",
          np.all(p[failed] >= 0.0) and np.all(s[failed] == 0.0))
    # A live zone in tension at the spall strength stretches by p/K, about
    # 1.4% (K = rho0 c0^2 = 0.74 Mbar); the failed zones, free of tension,
    # open far beyond that: the spall gap.
    check("the failed zones opened: V/V0 %.3f .. %.3f, above 1.05 (live target zones <= %.4f)"
          % ((v / v0)[failed].min() if failed.any() else 0,
             (v / v0)[failed].max() if failed.any() else 0,
             (v / v0)[~failed & (block == 2)].max()),
          failed.any() and (v / v0)[failed].max() > 1.05
          and (v / v0)[~failed & (block == 2)].max() < 1.05)
    balance(history.read(wd), "spall")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("workdir")
    ap.add_argument("--case", required=True, choices=["failure", "erosion", "stop", "spall"])
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--np", type=int, default=1)
    a = ap.parse_args()
    {"failure": case_failure, "erosion": case_erosion, "stop": case_stop,
     "spall": case_spall}[a.case](a)
    print("%d check(s) failed" % len(FAILED) if FAILED else "all checks passed")
    return 1 if FAILED else 0


if __name__ == "__main__":
    sys.exit(main())
