#!/usr/bin/python3
"""Run the contact verification problems and regenerate their plots and summary.

Usage:
    /usr/bin/python3 tools/verify_contact.py [--exe build/impact3d] [--np 2] [--full]
                                             [--workdir /tmp/impact3d_verify_contact]
                                             [--reuse] [--docs docs]

One command for the contact problems of docs/problems.md, section D.  Each run gets
its own directory under --workdir (deck.nml, run.log, dumps, history.txt,
run.json) and is started as `mpirun -np NP EXE deck.nml` through
impact3d_tools.runs.run_case (same environment, same --reuse rule: a directory that
already holds a successful run of the identical deck, executable and rank
count is not run again).

Default (quick, about 5 minutes on 2 ranks):
    Sod        conforming reference, non-matching meshes joined by DLM and DAM
               (tests/regression/cases/sod_nonmatching/sod_*.nml, pair 'mid')
    Sedov      octant split at x = 0.6, left block 18^3 and 30^3: single mesh,
               DLM, DAM (problems/sedov_contact, pair 'x06'; the single-mesh
               references are problems/sedov/sedov.nml with nx = ny = nz = n)
    Sedov      curved split at r = 0.5 (a ball octant and the box minus the ball,
    curved     meshed apart), coarse and medium: DLM, DAM (pair 'r05'; reference
               the single-mesh 30^3 run)
    Verney     shell split at r = 9 cm: single shell, DLM, DAM (pair 'r9')
--full adds (each Taylor or tube run takes minutes):
    Sedov 45^3; the curved split's fine mesh; Al block on steel (DLM, DAM; problems/al_on_steel/analyse.py);
    Taylor anvil cases 1 and 2, coarse: rigid wall, stiff anvil DLM/DAM, steel
    anvil DLM/DAM (pair 'foot'); crossed tubes, same and stiff, DLM/DAM ('cross').

For every run it records, from history.txt and run.log: the problem's criterion
values, the largest penetration (max of NAME_pen_max), the contact work over the
initial total energy E0, max |energy_error|, the momentum booked by contact
(norm of the summed NAME_dmom columns over the largest |momentum| of the run),
cycles, wall time, and the contact share (search and enforcement seconds over
the run's seconds, and the printed share of the loop).  Writes
docs/img/contact_*.png and docs/verification-contact.md.

--only KEY [KEY ...] runs only those sections (keys: sod, sedov, sedov_curved,
verney, al, taylor, tubes) and puts them in place of the same sections of the
existing docs/verification-contact.md, leaving the rest of it as it was.

Exit status: 0 if every run finished (exit 0), 1 otherwise.  Whether the
numbers meet the criteria is reported (PASS / FAIL), not enforced.
"""

import argparse
import datetime
import glob
import math
import os
import re
import subprocess
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

TOOLS = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(TOOLS)

from impact3d_tools import compare, dump, measures, radial, runs, shapes  # noqa: E402
from impact3d_tools.exact import verney as exact_verney  # noqa: E402

DPI = 110
METHODS = ("dlm", "dam")
SEDOV_QUICK = (18, 30)
SEDOV_FULL = (18, 30, 45)
TAYLOR_CASES = (1, 2)
TUBE_VARIANTS = ("same", "stiff")
TUBE_TITLES = {"same": "same material", "stiff": "struck tube (a) 10x stiffer"}

SOD_DECKS = {"conforming": "tests/regression/cases/sod_nonmatching/sod_conforming.nml",
             "dlm": "tests/regression/cases/sod_nonmatching/sod_contact_dlm.nml",
             "dam": "tests/regression/cases/sod_nonmatching/sod_contact_dam.nml"}
SEDOV_CONTACT = "problems/sedov_contact/sedov_contact_{method}_{n}.nml"
SEDOV_CURVED = "problems/sedov_contact/sedov_curved_{method}_{mesh}.nml"
SEDOV_CURVED_QUICK = ("a", "b")
SEDOV_CURVED_FULL = ("a", "b", "c")
SEDOV_CURVED_NAMES = {"a": "coarse", "b": "medium", "c": "fine"}
SEDOV_CURVED_RADIUS = 0.5
VERNEY_DECKS = {"single": "problems/verney/verney.nml",
                "dlm": "problems/verney_contact/verney_contact_dlm.nml",
                "dam": "problems/verney_contact/verney_contact_dam.nml"}
TAYLOR_RIGID = "problems/taylor/taylor_case{case}_coarse.nml"
TAYLOR_CONTACT = "problems/taylor_contact/taylor_case{case}_{anvil}_{method}_coarse.nml"
AL_DECK = "problems/al_on_steel/al_on_steel_{method}_fine.nml"
AL_ANALYSE = os.path.join(ROOT, "problems", "al_on_steel", "analyse.py")
TUBE_DECK = "problems/tubes/tubes_{variant}_{method}.nml"

PAIRS = {"sod": "mid", "sedov": "x06", "sedov_curved": "r05", "verney": "r9", "taylor": "foot",
         "al": "interface", "tubes": "cross"}

# Bounds of the criteria (reported against, not enforced).
SOD_L1_RATIO = 1.10
SEDOV_L1_RATIO = 1.10
SEDOV_SHOCK_REL = 0.02          # at 30^3
VERNEY_INNER_R0 = 8.0           # cm, the inner surface at t = 0
VERNEY_STOP_TOL = 0.1           # cm, against the single shell
TAYLOR_TOL = 0.02
AL_TOL = 0.03
TUBE_PEN_MAX = 0.01             # cm, 5 % of the 0.2 cm wall
TUBE_V0 = -0.002                # cm/us, initial z velocity of tube b
TUBE_B_BLOCK = 2
MOMENTUM_ROUNDOFF = 1.0e-12     # DLM: contact books no momentum

# "contact T s search and RCB, T s enforcement, T s migration (P% of the loop; ...)"
# (older binaries: "contact T s search, T s enforcement (P% of the loop"); the
# search column includes the RCB and the migration of the contact nodes.
CONTACT_LINE = re.compile(r"impact3d: contact\s+([0-9.]+) s search(?: and RCB)?,\s+([0-9.]+) s "
                          r"enforcement(?:,\s+([0-9.]+) s migration)?\s*\(\s*([0-9.]+)% of the loop")
DONE_LINE = re.compile(r"impact3d: done, (\d+) cycles,\s+([0-9.]+) s")
AL_TARGET_LINE = re.compile(r"axial stress ([-0-9.eE+]+) Mbar")
AL_MEAN_LINE = re.compile(r"(\d+) dumps in .*: mean ([-0-9.eE+]+) Mbar \(min ([-0-9.eE+]+), "
                          r"max ([-0-9.eE+]+)\), error ([-+0-9.]+)%")


# --------------------------------------------------------------------------- decks

def deck_text(relpath):
    return runs.read(os.path.join(ROOT, relpath))


def deck_setup(relpath):
    """The leading '!' comment of a deck as one line, criteria sentences removed."""
    lines = []
    for line in deck_text(relpath).splitlines():
        if not line.startswith("!"):
            break
        lines.append(line.lstrip("!").strip())
    text = " ".join(lines)
    return re.split(r"\s*Criteri(?:on|a):", text)[0].strip()


# --------------------------------------------------------------------------- runs

def parse_timing(log_path):
    """Contact search / enforcement seconds, the printed share of the loop, the
    run's seconds and cycles from the end of a run's stdout."""
    out = {}
    with open(log_path, encoding="utf-8", errors="replace") as handle:
        text = handle.read()
    match = CONTACT_LINE.search(text)
    if match:
        out.update(search=float(match.group(1)) + float(match.group(3) or 0.0),
                   enforcement=float(match.group(2)), loop_pct=float(match.group(4)))
    match = DONE_LINE.search(text)
    if match:
        out.update(cycles=int(match.group(1)), total=float(match.group(2)))
    return out


def initial_energy(hist):
    """E0 of the run, recovered from the first history row through the
    definition energy_error = (IE + KE - W_boundary - W_contact - E0) / |E0|."""
    total = hist["total_energy"][0] - hist["boundary_work"][0] - hist["contact_work"][0]
    return float(total / (1.0 + hist["energy_error"][0]))


def contact_stats(hist, pair):
    """Penetration, contact work, momentum and activity of one contact pair."""
    e0 = initial_energy(hist)
    booked = np.array([hist[f"{pair}_dmom_{c}"].sum() for c in "xyz"])
    momentum = np.sqrt(hist["momentum_x"] ** 2 + hist["momentum_y"] ** 2
                       + hist["momentum_z"] ** 2)
    scale = float(momentum.max())
    return {"pen_max": float(hist[f"{pair}_pen_max"].max()),
            "work_rel": float(hist["contact_work"][-1] / e0),
            "momentum_error": float(np.linalg.norm(booked) / scale) if scale > 0 else math.nan,
            "active_cycles": int(np.count_nonzero(hist[f"{pair}_active"] > 0)),
            "released": int(hist[f"{pair}_released"].sum())}


def run_stats(hist, pair):
    stats = {"e0": initial_energy(hist), "rows": int(hist["cycle"].size),
             "cycles": int(hist["cycle"][-1]),
             "energy_error_max": float(np.abs(hist["energy_error"]).max())}
    if pair:
        stats.update(contact_stats(hist, pair))
    return stats


def run(name, deck, opts, label, pair=None, method=None):
    """Run one deck (runs.run_case) and collect its history and timing."""
    return measure(name, runs.run_case(name, deck, opts), label, pair, method)


def measure(name, rec, label, pair=None, method=None):
    """The entry of one finished run: its run_case record (rc, workdir, dump,
    wall), history.txt, statistics and the timing from run.log."""
    entry = {"name": name, "label": label, "pair": pair, "method": method, "rec": rec,
             "ok": rec["rc"] == 0 and bool(rec.get("dump"))}
    if entry["ok"]:
        entry["hist"] = runs.history(rec["workdir"])
        entry["stats"] = run_stats(entry["hist"], pair)
        entry["timing"] = parse_timing(os.path.join(rec["workdir"], "run.log"))
    return entry


# --------------------------------------------------------------------------- measures

def stopping_radius(workdir):
    """(time, radius) of the smallest mean radius of the initial r = 8 nodes, and
    the whole history as arrays."""
    history = shapes.inner_radius_history(workdir, VERNEY_INNER_R0)
    times = np.array([h[0] for h in history])
    radii = np.array([h[1] for h in history])
    i = int(np.argmin(radii))
    return float(times[i]), float(radii[i]), times, radii


def block_velocity_z(path, block):
    """Mass-weighted mean z velocity of the nodes of one block (1-based id)."""
    data = dump.load(path)
    nodes = np.unique(data["connectivity"][data["block"] == block].ravel())
    mass = data["node_mass"][nodes]
    return float(np.sum(mass * data["node_velocity"][nodes, 2]) / np.sum(mass))


def al_axial_stress(workdir):
    """problems/al_on_steel/analyse.py on a run directory: axial stress next to
    the interface (mean, min, max over its window), its impedance-match value and
    the relative error."""
    path = os.pathsep.join([TOOLS] + [p for p in [os.environ.get("PYTHONPATH")] if p])
    proc = subprocess.run([sys.executable, AL_ANALYSE, workdir], capture_output=True,
                          text=True, env=dict(os.environ, PYTHONPATH=path))
    target = AL_TARGET_LINE.search(proc.stdout)
    mean = AL_MEAN_LINE.search(proc.stdout)
    if proc.returncode != 0 or not target or not mean:
        return None
    return {"target": float(target.group(1)), "ndump": int(mean.group(1)),
            "mean": float(mean.group(2)), "min": float(mean.group(3)),
            "max": float(mean.group(4)), "error": float(mean.group(5)) / 100.0}


def relative(a, b):
    return a / b - 1.0 if b else math.nan


# --------------------------------------------------------------------------- plots

def save(figure, path):
    figure.tight_layout()
    figure.savefig(path, dpi=DPI)
    plt.close(figure)
    print(f"  wrote {os.path.relpath(path, ROOT)}", flush=True)


STYLE = {None: ("tab:green", "o"), "dlm": ("tab:blue", "s"), "dam": ("tab:orange", "^")}
MEAN_LINES = {None: "-", "dlm": "--", "dam": ":"}


def exact_setup(problem, path):
    """compare.Setup for the dump's time and the problem's default data."""
    args = compare.fill_defaults(runs.compare_args(problem, path))
    return compare.Setup(args, dump.problem_time(dump.load(path))), args


def plot_sod(entries, path):
    """Column-averaged density against x for each run, the exact solution, and a
    zoom on the contact and the shock."""
    done = [e for e in entries if e["ok"]]
    if not done:
        return False
    setup, _ = exact_setup("sod", done[0]["rec"]["dump"])
    figure, axes = plt.subplots(1, 2, figsize=(12, 4.6))
    x_line = np.linspace(0.0, 1.0, 4001)
    for axis, window in zip(axes, ((0.0, 1.0), (0.55, 0.92))):
        axis.plot(x_line, setup.exact(x_line)[0], "-", color="0.3", lw=1.0, label="exact")
        for e in done:
            data = dump.load(e["rec"]["dump"])
            x, rho = measures.planar_profile(dump.zone_centroids(data)[:, 0], data["density"],
                                            data["volume"])
            color, marker = STYLE[e["method"]]
            axis.plot(x, rho, marker=marker, ms=3.5, lw=0.8, color=color, mfc="none",
                      label=e["label"])
        axis.axvline(0.5, color="0.6", ls=":", lw=0.8)
        axis.set_xlim(*window)
        axis.set_xlabel("x (zone centroid; mean over the zones of one column)")
        axis.set_ylabel("density")
        axis.grid(alpha=0.3)
    axes[1].set_ylim(0.1, 0.45)
    axes[0].legend(fontsize=8)
    axes[0].set_title("whole tube (dotted: initial interface, x = 0.5)", fontsize=9)
    axes[1].set_title("contact discontinuity and shock", fontsize=9)
    figure.suptitle(f"Sod, non-matching meshes joined by contact, t = {setup.time:.3g}")
    save(figure, path)
    return True


SEDOV_FIELDS = (("rho", "density", "density", "linear"),
                ("p", "pressure", "pressure", "linear"),
                ("e", "specific_internal_energy", "specific internal energy", "log"))
SEDOV_BIN = 0.02


def plot_sedov_profiles(entries, n, path, title=None):
    """rho, p, e against the centroid radius for single, DLM and DAM at n^3:
    every zone as a dot, the volume-weighted mean in radial bins as a line."""
    done = [e for e in entries if e["ok"]]
    if not done:
        return False
    setup, _ = exact_setup("sedov", done[0]["rec"]["dump"])
    r_line = np.linspace(1e-3, 1.3, 3000)
    exact = dict(zip(("rho", "u", "p", "e"), setup.exact(r_line)))
    figure, axes = plt.subplots(1, 3, figsize=(15, 4.8))
    for axis, (key, name, label, scale) in zip(axes, SEDOV_FIELDS):
        highest = 0.0
        for e in done:
            data = dump.load(e["rec"]["dump"])
            r = np.linalg.norm(dump.zone_centroids(data), axis=1)
            value = data[name]
            color, _ = STYLE[e["method"]]
            axis.plot(r, value, ".", ms=1.0, alpha=0.3, color=color, rasterized=True)
            centres, mean = measures.radial_profile(r, value, data["volume"], SEDOV_BIN)
            axis.plot(centres, mean, MEAN_LINES[e["method"]], lw=1.6, color=color,
                      label=e["label"])
            highest = max(highest, float(value[r < 1.3].max()))
        axis.plot(r_line, exact[key], "-", color="k", lw=1.0, label="exact")
        axis.set_xlim(0.0, 1.3)
        if scale == "log":
            axis.set_yscale("log")
            axis.set_ylim(1e-2, 2.0 * highest)
        else:
            axis.set_ylim(0.0, 1.1 * max(highest, float(np.nanmax(exact[key]))))
        axis.set_xlabel("radius (zone centroid)")
        axis.set_ylabel(label)
        axis.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    if title is None:
        title = f"Sedov octant split at x = 0.6, left block {n}^3"
    figure.suptitle(f"{title}, t = {setup.time:.3g}: "
                    f"zones (dots) and means in radial bins of {SEDOV_BIN} (lines)")
    save(figure, path)
    return True


def energy_drift(hist):
    """(IE + KE - W_boundary) / E0 - 1: the energy balance without the contact
    work, i.e. including what contact dissipates."""
    e0 = initial_energy(hist)
    return (hist["total_energy"] - hist["boundary_work"]) / e0 - 1.0


def plot_sedov_energy(entries, path, title="Sedov"):
    done = [e for e in entries if e["ok"]]
    if not done:
        return False
    figure, axis = plt.subplots(figsize=(8, 4.8))
    colors = {18: "tab:green", 30: "tab:blue", 45: "tab:red", "a": "tab:green",
              "b": "tab:blue", "c": "tab:red"}
    lines = {None: ":", "dlm": "-", "dam": "--"}
    for e in done:
        drift = energy_drift(e["hist"])
        axis.semilogy(e["hist"]["time"], np.maximum(np.abs(drift), 1e-18),
                      lines[e["method"]], color=colors.get(e["n"], "k"), lw=1.0,
                      label=f"{e['label']} (end {drift[-1]:+.1e})")
    axis.set_xlabel("time")
    axis.set_ylabel("|(IE + KE - W_boundary) / E0 - 1|")
    axis.set_ylim(1e-18, 1e-1)
    axis.grid(alpha=0.3, which="both")
    axis.legend(fontsize=7, ncol=2)
    axis.set_title(f"{title}: total energy error, contact dissipation included "
                   "(negative = lost)", fontsize=10)
    save(figure, path)
    return True


def plot_verney(entries, path):
    """Inner radius against time: the whole collapse and a zoom on the stop."""
    done = [e for e in entries if e["ok"]]
    if not done:
        return False
    a_stop, t_stop, a, t = exact_verney.verney()
    t_max = max(float(e["verney"]["times"].max()) for e in done)
    t_line = np.linspace(0.0, t_max, 600)
    r_line = exact_verney.radius_at(t_line, a, t, a_stop, t_stop)
    figure, axes = plt.subplots(1, 2, figsize=(12, 4.6))
    for axis in axes:
        axis.plot(t_line, r_line, "-", color="0.3",
                  label=f"rigid-plastic energy balance (stops at {a_stop:.3f} cm)")
        for e in done:
            color, marker = STYLE[e["method"]]
            axis.plot(e["verney"]["times"], e["verney"]["radii"], marker=marker, ms=4,
                      lw=0.8, color=color, mfc="none",
                      label=f"{e['label']} (smallest {e['verney']['r_stop']:.3f} cm)")
        axis.set_xlabel("time (us)")
        axis.set_ylabel("inner radius (cm)")
        axis.grid(alpha=0.3)
    axes[1].set_xlim(70.0, t_max + 2.0)
    axes[1].set_ylim(a_stop - 0.2, a_stop + 0.5)
    axes[0].legend(fontsize=8)
    axes[0].set_title("mean radius of the nodes at r = 8 cm at t = 0", fontsize=9)
    axes[1].set_title("the stop (t > 70 us)", fontsize=9)
    figure.suptitle("Verney shell split at r = 9 cm by contact")
    save(figure, path)
    return True


def rod_profile(path, initial_path):
    """Final (x, z) of the rod's outer surface in the y = 0 plane: of the rod's
    (block of zone 0) nodes on y = 0 at t = 0, the outermost of each initial z
    layer, in order of the initial z; and its initial (x, z)."""
    d0, d1 = dump.load(initial_path), dump.load(path)
    x0 = d0["coordinates"]
    rod = np.zeros(x0.shape[0], dtype=bool)
    rod[np.unique(d0["connectivity"][d0["block"] == d0["block"][0]].ravel())] = True
    section = np.nonzero(rod & (np.abs(x0[:, 1]) < 1e-12))[0]
    layers = {}
    for node in section:
        key = round(float(x0[node, 2]), 9)
        if key not in layers or x0[node, 0] > x0[layers[key], 0]:
            layers[key] = node
    outer = np.array([layers[k] for k in sorted(layers)])
    return d1["coordinates"][outer][:, [0, 2]], x0[outer][:, [0, 2]]


TAYLOR_STYLE = {"rigid": ("k", 3.0), "stiff": ("tab:green", 1.2), "steel": ("tab:red", 1.2)}
TAYLOR_LINES = {None: "-", "dlm": "-", "dam": "--"}
TAYLOR_FOOT = 1.0               # cm, height of the zoom on the foot


def plot_taylor(cases, path):
    """Final outer profiles of the rods in the y = 0 plane, one row per case:
    the whole rod (left, true aspect) and the foot (right)."""
    figure, axes = plt.subplots(len(cases), 2, figsize=(11, 6.0 * len(cases)), squeeze=False,
                                gridspec_kw={"width_ratios": [1.0, 2.4]})
    for (whole, foot), (case, entries) in zip(axes, sorted(cases.items())):
        initial = None
        for e in entries:
            if not e["ok"]:
                continue
            final, initial = rod_profile(e["rec"]["dump"],
                                         runs.first_dump(e["rec"]["workdir"]))
            color, width = TAYLOR_STYLE[e["anvil"]]
            for axis in (whole, foot):
                axis.plot(final[:, 0], final[:, 1], TAYLOR_LINES[e["method"]], lw=width,
                          color=color, label=e["label"].split(", ", 1)[-1])
        for axis in (whole, foot):
            if initial is not None:
                axis.plot(initial[:, 0], initial[:, 1], ":", color="0.5", lw=1.0,
                          label="initial")
            axis.set_xlabel("x (cm), section y = 0")
            axis.set_ylabel("z (cm)")
            axis.grid(alpha=0.3)
        if initial is not None:
            foot.legend(fontsize=8)
        whole.set_xlim(0.0, 2.0)
        whole.set_aspect("equal")
        foot.set_ylim(-0.05, TAYLOR_FOOT)
        whole.set_title(f"Taylor case {case}, coarse", fontsize=10)
        foot.set_title(f"case {case}: final outer profile of the foot (z < {TAYLOR_FOOT:g} cm)",
                       fontsize=10)
    save(figure, path)
    return True


def plot_tubes(variants, path):
    """Kinetic, internal energy and dissipated contact work against time."""
    figure, axes = plt.subplots(1, len(variants), figsize=(6.5 * len(variants), 4.6),
                                squeeze=False)
    lines = {"dlm": "-", "dam": "--"}
    for axis, (variant, entries) in zip(axes[0], sorted(variants.items())):
        for e in entries:
            if not e["ok"]:
                continue
            h, e0 = e["hist"], e["stats"]["e0"]
            style = lines[e["method"]]
            method = e["method"].upper()
            axis.plot(h["time"], h["kinetic_energy"] / e0, style, color="tab:blue",
                      label=f"kinetic, {method}")
            axis.plot(h["time"], h["internal_energy"] / e0, style, color="tab:red",
                      label=f"internal, {method}")
            axis.plot(h["time"], -h["contact_work"] / e0, style, color="tab:gray",
                      label=f"- contact work (dissipated), {method}")
        axis.set_xlabel("time (us)")
        axis.set_ylabel("energy / E0")
        axis.grid(alpha=0.3)
        if axis.get_legend_handles_labels()[0]:
            axis.legend(fontsize=7)
        axis.set_title(f"Crossed tubes, {TUBE_TITLES[variant]}", fontsize=10)
    save(figure, path)
    return True


# --------------------------------------------------------------------------- problems

def section(key, title, setup, criterion, rows, images=(), notes=()):
    return {"key": key, "title": title, "setup": setup, "criterion": criterion,
            "rows": rows, "images": list(images), "notes": list(notes)}


def not_run(key, title):
    return {"key": key, "title": title, "not_run": True}


def row(entry, criterion="", ok=None):
    """A table row: ok True / False, or None for a reference (no bound)."""
    return {"entry": entry, "criterion": criterion, "ok": ok}


def do_sod(opts, img):
    entries = []
    for key, deck in SOD_DECKS.items():
        method = None if key == "conforming" else key
        label = "conforming" if method is None else method.upper()
        entries.append(run(f"sod_{key}", deck_text(deck), opts, label,
                           PAIRS["sod"] if method else None, method))
    rows, reference = [], None
    for e in entries:
        if not e["ok"]:
            rows.append(row(e))
            continue
        l1 = runs.summarize("sod", e["rec"]["dump"])["L1_rho"]
        if e["method"] is None:
            reference = l1
            rows.append(row(e, f"L1(rho) = {l1:.3e}"))
            continue
        s = e["stats"]
        ratio = l1 / reference if reference else math.nan
        always = s["active_cycles"] == s["rows"] and s["released"] == 0
        rows.append(row(e, f"L1(rho) = {l1:.3e}, ratio {ratio:.3f}; active on "
                           f"{s['active_cycles']} of {s['rows']} cycles, "
                           f"{s['released']} released", ratio <= SOD_L1_RATIO and always))
    images = []
    if plot_sod(entries, os.path.join(img, "contact_sod_density.png")):
        images.append(("Sod density profiles", "img/contact_sod_density.png"))
    return section("sod", "Sod shock tube, non-matching meshes",
                   [(SOD_DECKS["conforming"], deck_setup(SOD_DECKS["conforming"])),
                    (SOD_DECKS["dlm"], deck_setup(SOD_DECKS["dlm"]))],
                   f"L1(rho) of the contact run (tools/compare.py, whole tube) at most "
                   f"{SOD_L1_RATIO:.2f} times the conforming run's; the interface is in "
                   "contact on every cycle and never releases a node.", rows, images)


def sedov_entries(opts, n):
    entries = [run(f"sedov_single_{n}", runs.sedov_deck(n), opts, f"single {n}^3")]
    for method in METHODS:
        deck = deck_text(SEDOV_CONTACT.format(method=method, n=n))
        entries.append(run(f"sedov_{method}_{n}", deck, opts, f"{method.upper()} {n}^3",
                           PAIRS["sedov"], method))
    for e in entries:
        e["n"] = n
    return entries


def sedov_rows(entries, n):
    rows, reference = [], None
    for e in entries:
        if not e["ok"]:
            rows.append(row(e))
            continue
        s = runs.summarize("sedov", e["rec"]["dump"])
        text = (f"L1(rho) = {s['L1_rho']:.3e}, shock r error "
                f"{100 * s['shock_r_error_rel']:+.2f} %")
        if e["method"] is None:
            reference = s["L1_rho"]
            rows.append(row(e, text))
            continue
        ratio = s["L1_rho"] / reference if reference else math.nan
        ok = ratio <= SEDOV_L1_RATIO
        if n == 30:
            ok = ok and abs(s["shock_r_error_rel"]) <= SEDOV_SHOCK_REL
        rows.append(row(e, f"{text}; L1 ratio {ratio:.3f}", ok))
    return rows


def do_sedov(opts, img, sizes):
    rows, everything, images = [], [], []
    for n in sizes:
        entries = sedov_entries(opts, n)
        everything.extend(entries)
        rows.extend(sedov_rows(entries, n))
        if n == 30 and plot_sedov_profiles(entries, n,
                                           os.path.join(img, "contact_sedov_profiles.png")):
            images.append(("Sedov profiles, split at 30^3", "img/contact_sedov_profiles.png"))
    if plot_sedov_energy(everything, os.path.join(img, "contact_sedov_energy.png")):
        images.append(("Sedov energy error", "img/contact_sedov_energy.png"))
    notes = [] if 45 in sizes else ["Sedov 45^3 not run; use --full."]
    return section("sedov", "Sedov blast wave split by a contact plane",
                   [("problems/sedov/sedov.nml", deck_setup("problems/sedov/sedov.nml")),
                    (SEDOV_CONTACT.format(method="dlm", n=30),
                     deck_setup(SEDOV_CONTACT.format(method="dlm", n=30)))],
                   f"L1(rho) (tools/compare.py, whole octant) of the contact run at most "
                   f"{SEDOV_L1_RATIO:.2f} times the single mesh's at the same resolution; "
                   f"shock radius within {100 * SEDOV_SHOCK_REL:.0f} % of exact at 30^3.",
                   rows, images, notes)


def curved_overshoot(workdir):
    """Largest radial penetration of a node of the ball's surface (block 1)
    beyond the outer region's faceted surface (block 2) over the run's dumps,
    with its time and the node's direction (tools/radial_gap.py: it sees
    nodes the contact no longer holds)."""
    rows = radial.history(workdir, 1, 2, SEDOV_CURVED_RADIUS)
    time, worst, direction = max(rows, key=lambda r: r[1])
    return worst, time, direction


def do_sedov_curved(opts, img, meshes):
    reference = run("sedov_single_30", runs.sedov_deck(30), opts, "single 30^3")
    reference["n"] = 30
    rows, everything = [], []
    l1_reference = None
    if reference["ok"]:
        s = runs.summarize("sedov", reference["rec"]["dump"])
        l1_reference = s["L1_rho"]
        rows.append(row(reference, f"L1(rho) = {s['L1_rho']:.3e}, shock r error "
                                   f"{100 * s['shock_r_error_rel']:+.2f} %"))
    else:
        rows.append(row(reference))
    by_mesh = {}
    for mesh in meshes:
        for method in METHODS:
            deck = deck_text(SEDOV_CURVED.format(method=method, mesh=mesh))
            e = run(f"sedov_curved_{method}_{mesh}", deck, opts,
                    f"{method.upper()} {SEDOV_CURVED_NAMES[mesh]} ({mesh})",
                    PAIRS["sedov_curved"], method)
            e["n"] = mesh
            everything.append(e)
            by_mesh.setdefault(mesh, []).append(e)
            if not e["ok"]:
                rows.append(row(e))
                continue
            s = runs.summarize("sedov", e["rec"]["dump"])
            ratio = s["L1_rho"] / l1_reference if l1_reference else math.nan
            beyond, when, direction = curved_overshoot(e["rec"]["workdir"])
            ok = ratio <= 1.0 and abs(s["shock_r_error_rel"]) <= SEDOV_SHOCK_REL
            rows.append(row(e, f"L1(rho) = {s['L1_rho']:.3e}, ratio {ratio:.3f}; shock r "
                               f"error {100 * s['shock_r_error_rel']:+.2f} %; ball surface "
                               f"beyond the outer surface by up to {beyond:.2e} (t = "
                               f"{when:.2f}, direction {direction[0]:.2f}, "
                               f"{direction[1]:.2f}, {direction[2]:.2f})",
                            ok))
    images = []
    if "b" in by_mesh and plot_sedov_profiles(
            [reference] + by_mesh["b"], 30,
            os.path.join(img, "contact_sedov_curved_profiles.png"),
            title="Sedov octant split at r = 0.5 (ball / box minus ball), medium mesh"):
        images.append(("Sedov curved split profiles, medium mesh",
                       "img/contact_sedov_curved_profiles.png"))
    if plot_sedov_energy(everything, os.path.join(img, "contact_sedov_curved_energy.png"),
                         title="Sedov, curved split"):
        images.append(("Sedov curved split energy error",
                       "img/contact_sedov_curved_energy.png"))
    notes = [] if "c" in meshes else ["Fine mesh (c) not run; use --full."]
    notes.append("Penetration: the largest radial distance of a ball surface node beyond the "
                 "gas's faceted surface over the dumps (tools/radial_gap.py); the faceting "
                 "alone (two polyhedra on one sphere) gives the sagitta of the gas's faces, "
                 "about 1e-3. The long tests assert it <= 4e-3 on the medium mesh.")
    return section("sedov_curved", "Sedov blast wave split along a curved contact surface",
                   [(SEDOV_CURVED.format(method="dlm", mesh="b"),
                     deck_setup(SEDOV_CURVED.format(method="dlm", mesh="b")))],
                   "L1(rho) (tools/compare.py, whole octant) of the contact run at most the "
                   "single-mesh 30^3 run's; shock radius within "
                   f"{100 * SEDOV_SHOCK_REL:.0f} % of exact.", rows, images, notes)


def do_verney(opts, img):
    entries = []
    for key, deck in VERNEY_DECKS.items():
        method = None if key == "single" else key
        label = "single shell" if method is None else method.upper()
        entries.append(run(f"verney_{key}", deck_text(deck), opts, label,
                           PAIRS["verney"] if method else None, method))
    a_stop = exact_verney.verney()[0]
    rows, reference = [], None
    for e in entries:
        if not e["ok"]:
            rows.append(row(e))
            continue
        t_stop, r_stop, times, radii = stopping_radius(e["rec"]["workdir"])
        e["verney"] = {"r_stop": r_stop, "t_stop": t_stop, "times": times, "radii": radii}
        text = f"stops at r = {r_stop:.4f} cm (t = {t_stop:.0f} us)"
        if e["method"] is None:
            reference = r_stop
            rows.append(row(e, f"{text}; energy balance {a_stop:.4f} cm"))
            continue
        diff = r_stop - reference if reference is not None else math.nan
        rows.append(row(e, f"{text}; {diff:+.4f} cm from the single shell",
                        abs(diff) <= VERNEY_STOP_TOL))
    images = []
    if plot_verney(entries, os.path.join(img, "contact_verney_radius.png")):
        images.append(("Verney inner radius", "img/contact_verney_radius.png"))
    return section("verney", "Verney shell split by a contact sphere",
                   [(VERNEY_DECKS["single"], deck_setup(VERNEY_DECKS["single"])),
                    (VERNEY_DECKS["dlm"], deck_setup(VERNEY_DECKS["dlm"]))],
                   f"stopping radius (smallest mean radius, over the dumps every 5 us, of "
                   f"the nodes at r = {VERNEY_INNER_R0:g} cm at t = 0) within "
                   f"{VERNEY_STOP_TOL} cm of the single-shell run's.", rows, images)


def do_al_on_steel(opts, img):
    rows = []
    for method in METHODS:
        e = run(f"al_on_steel_{method}", deck_text(AL_DECK.format(method=method)), opts,
                method.upper(), PAIRS["al"], method)
        stress = al_axial_stress(e["rec"]["workdir"]) if e["ok"] else None
        if stress is None:
            rows.append(row(e, "analyse.py failed" if e["ok"] else "", False))
            continue
        rows.append(row(e, f"sigma_zz = {stress['mean']:.4f} Mbar ({stress['min']:.3f} to "
                           f"{stress['max']:.3f}, {stress['ndump']} dumps) vs "
                           f"{stress['target']:.4f}: {100 * stress['error']:+.2f} %",
                        abs(stress["error"]) <= AL_TOL))
    deck = AL_DECK.format(method="dlm")
    return section("al", "Aluminium block on a steel block", [(deck, deck_setup(deck))],
                   "axial stress sigma_zz on the axis next to the interface, averaged over "
                   "0.3-1.2 us (problems/al_on_steel/analyse.py), within "
                   f"{100 * AL_TOL:.0f} % of the 1D elastic-plastic impedance match from the "
                   "same data (two-wave Rankine-Hugoniot match with the Steinberg-Guinan yield "
                   "of the shocked state, problems/al_on_steel/impedance_match.py; the 1D "
                   "column al_on_steel_column.nml gives the same). Fine mesh, to 1.5 us; the "
                   "coarse decks and the other meshes: problems/al_on_steel/README.md.", rows)


def taylor_entries(opts, case):
    entries = [run(f"taylor{case}_rigid", deck_text(TAYLOR_RIGID.format(case=case)), opts,
                   f"case {case}, rigid wall")]
    entries[0]["anvil"] = "rigid"
    for anvil in ("stiff", "steel"):
        for method in METHODS:
            deck = deck_text(TAYLOR_CONTACT.format(case=case, anvil=anvil, method=method))
            e = run(f"taylor{case}_{anvil}_{method}", deck, opts,
                    f"case {case}, {anvil} anvil, {method.upper()}", PAIRS["taylor"], method)
            e["anvil"] = anvil
            entries.append(e)
    return entries


def shape_text(shape, reference, name):
    length, diameter = shape
    if reference is None:
        return f"L = {length:.4f}, D = {diameter:.4f} cm"
    return (f"L = {length:.4f} ({100 * relative(length, reference[0]):+.2f} %), "
            f"D = {diameter:.4f} cm ({100 * relative(diameter, reference[1]):+.2f} %) vs {name}")


def within(shape, reference, tol):
    return (reference is not None and abs(relative(shape[0], reference[0])) <= tol
            and abs(relative(shape[1], reference[1])) <= tol)


def taylor_rows(entries):
    shapes = {(e["anvil"], e["method"]): shapes.rod_shape(e["rec"]["dump"])
              for e in entries if e["ok"]}
    rigid, steel_dlm = shapes.get(("rigid", None)), shapes.get(("steel", "dlm"))
    rows = []
    for e in entries:
        key = (e["anvil"], e["method"])
        if key not in shapes:
            rows.append(row(e))
        elif e["anvil"] == "rigid":
            rows.append(row(e, shape_text(shapes[key], None, "")))
        elif e["anvil"] == "stiff":
            rows.append(row(e, shape_text(shapes[key], rigid, "rigid"),
                            within(shapes[key], rigid, TAYLOR_TOL)))
        elif e["method"] == "dlm":
            rows.append(row(e, shape_text(shapes[key], rigid, "rigid")))
        else:
            rows.append(row(e, shape_text(shapes[key], steel_dlm, "steel DLM"),
                            within(shapes[key], steel_dlm, TAYLOR_TOL)))
    return rows


def do_taylor(opts, img):
    rows, cases, images = [], {}, []
    for case in TAYLOR_CASES:
        cases[case] = taylor_entries(opts, case)
        rows.extend(taylor_rows(cases[case]))
    if plot_taylor(cases, os.path.join(img, "contact_taylor_sections.png")):
        images.append(("Taylor final sections", "img/contact_taylor_sections.png"))
    decks = [TAYLOR_RIGID.format(case=1),
             TAYLOR_CONTACT.format(case=1, anvil="stiff", method="dlm"),
             TAYLOR_CONTACT.format(case=1, anvil="steel", method="dlm")]
    return section("taylor", "Taylor anvil on a deformable anvil",
                   [(d, deck_setup(d)) for d in decks],
                   "final length L and foot diameter D (tools/impact3d_tools/shapes.py "
                   f"rod_shape, final dump): stiff-anvil runs within {100 * TAYLOR_TOL:.0f} % "
                   f"of the rigid wall's; steel DAM within {100 * TAYLOR_TOL:.0f} % of steel "
                   "DLM; the steel-anvil results against the rigid wall are reported.",
                   rows, images)


def tube_row(e):
    if not e["ok"]:
        return row(e)
    s = e["stats"]
    v = block_velocity_z(e["rec"]["dump"], TUBE_B_BLOCK)
    ok = s["pen_max"] <= TUBE_PEN_MAX
    if e["method"] == "dlm":
        ok = ok and s["momentum_error"] <= MOMENTUM_ROUNDOFF
    return row(e, f"tube b v_z = {v:+.3e} cm/us ({v / TUBE_V0:+.2f} of the "
                  f"initial {TUBE_V0:g}); penetration {s['pen_max']:.2e} vs "
                  f"{TUBE_PEN_MAX:g} cm", ok)


def do_tubes(opts, img):
    rows, variants, images = [], {}, []
    for variant in TUBE_VARIANTS:
        variants[variant] = []
        for method in METHODS:
            deck = deck_text(TUBE_DECK.format(variant=variant, method=method))
            e = run(f"tubes_{variant}_{method}", deck, opts, f"{variant}, {method.upper()}",
                    PAIRS["tubes"], method)
            e["variant"] = variant
            variants[variant].append(e)
            rows.append(tube_row(e))
    if plot_tubes(variants, os.path.join(img, "contact_tubes_energy.png")):
        images.append(("Crossed tubes energies", "img/contact_tubes_energy.png"))
    decks = [TUBE_DECK.format(variant=v, method="dlm") for v in TUBE_VARIANTS]
    return section("tubes", "Crossed tubes", [(d, deck_setup(d)) for d in decks],
                   "DLM books no momentum (round-off, at most "
                   f"{MOMENTUM_ROUNDOFF:.0e} of the largest momentum); the largest "
                   f"penetration at most {TUBE_PEN_MAX:g} cm (5 % of the wall); the contact "
                   "work and the rebound velocity of tube b (mass-weighted mean z velocity "
                   f"of block {TUBE_B_BLOCK} in the final dump, initially {TUBE_V0:g} cm/us) "
                   "are reported.", rows, images)


# --------------------------------------------------------------------------- report

# Where a section left out of the quick report is measured instead.
NOT_RUN_NOTES = {"al": " Measured numbers per mesh and method, and how the reference "
                       "(0.11995 Mbar) is built: problems/al_on_steel/README.md; the criterion "
                       "is asserted on the fine mesh by the ctests long/al_on_steel_dlm and "
                       "long/al_on_steel_dam.",
                 "tubes": " Parallel-axis variant against the mirror test (two identical tubes "
                          "side by side at +-0.001 cm/us, against one tube on the rigid plane "
                          "wall z = 0 given by &boundary wall_point/wall_normal): tube b's node "
                          "positions stay within 1.3e-5 (DAM) and 7.0e-4 (DLM) of the tube size "
                          "of the wall run's, not the flat-block 1e-8: DLM gates a facet pair on "
                          "the gap at the overlap centroid, so on these curved surfaces the first"
                          " contact line passes the mirror plane by about a facet's sagitta "
                          "(1.2e-3 cm) before any force acts (contact starts at 5.83 us, the "
                          "wall's at 5.00 us); DAM's put-back on the curved master is not exact "
                          "in momentum (6e-6). Set-up and numbers: problems/tubes/README.md; "
                          "asserted by the ctests long/tubes_parallel_dlm (1e-3, momentum z and "
                          "energy to 1e-12) and long/tubes_parallel_dam (3e-5)."}

FULL_TITLES = {"al": "Aluminium block on a steel block",
               "taylor": "Taylor anvil on a deformable anvil", "tubes": "Crossed tubes"}

TABLE_HEAD = ("| run | criterion value(s) | pass | largest penetration | contact work / E0 | "
              "max abs(energy error) | contact momentum error | cycles | wall (s) | "
              "contact search / enforcement (% of run; % of loop) |\n"
              "|---|---|---|---:|---:|---:|---:|---:|---:|---:|")


def fmt(value, spec=".2e"):
    return runs.fmt(value, spec)


def verdict(ok):
    return {True: "PASS", False: "**FAIL**", None: "ref."}[ok]


def share_text(entry):
    timing = entry.get("timing", {})
    if "search" not in timing or not timing.get("total"):
        return "-"
    total = timing["total"]
    return (f"{100 * timing['search'] / total:.1f} / {100 * timing['enforcement'] / total:.1f}"
            f" ({timing['loop_pct']:.1f})")


def table_line(r):
    e = r["entry"]
    rec = e["rec"]
    wall = f"{rec['wall']:.1f}" + (" (reused)" if rec.get("reused") else "")
    if not e["ok"]:
        return (f"| {e['label']} | run failed (exit {rec['rc']}; `{rec['workdir']}/run.log`) | "
                f"**FAIL** | | | | | | {wall} | |")
    s = e["stats"]
    contact = e["pair"] is not None
    return (f"| {e['label']} | {r['criterion']} | {verdict(r['ok'])} | "
            f"{fmt(s['pen_max']) if contact else '-'} | "
            f"{fmt(s['work_rel']) if contact else '-'} | {fmt(s['energy_error_max'], '.1e')} | "
            f"{fmt(s['momentum_error'], '.1e') if contact else '-'} | "
            f"{s['cycles']} | {wall} | {share_text(e)} |")


def section_lines(sec):
    lines = [f"## {sec['title']}\n"]
    if sec.get("not_run"):
        lines.append("Not run; use `--full`." + NOT_RUN_NOTES.get(sec["key"], "") + "\n")
        return lines
    for deck, text in sec["setup"]:
        lines.append(f"- `{deck}`: {text}")
    lines.append("")
    lines.append(f"**Criterion**: {sec['criterion']}\n")
    lines.append(TABLE_HEAD)
    lines.extend(table_line(r) for r in sec["rows"])
    lines.append("")
    lines.extend(f"{note}\n" for note in sec["notes"])
    lines.extend(f"![{alt}]({rel})\n" for alt, rel in sec["images"])
    return lines


def failed_checks(sections):
    out = []
    for sec in sections:
        for r in sec.get("rows", []):
            if r["ok"] is False or not r["entry"]["ok"]:
                out.append(f"{sec['title']}: {r['entry']['name']}")
    return out


def header_lines(opts, sections, wall_total, command):
    git = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"],
                         capture_output=True, text=True).stdout.strip() or "unknown"
    dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no"],
                           capture_output=True, text=True).stdout.strip()
    entries = [r["entry"] for sec in sections for r in sec.get("rows", [])]
    in_runs = sum(e["rec"]["wall"] for e in entries if not e["rec"].get("reused"))
    reused = sum(1 for e in entries if e["rec"].get("reused"))
    lines = ["# Contact verification (docs/problems.md, section D)\n",
             "Generated by `tools/verify_contact.py`; do not edit by hand, rerun it. This "
             "version was produced by\n", f"    {command}\n",
             f"on {datetime.date.today().isoformat()}, commit `{git}`"
             f"{' (with uncommitted changes)' if dirty else ''}, executable "
             f"`{os.path.relpath(os.path.abspath(opts.exe), ROOT)}`, {opts.np} MPI ranks on "
             f"{os.cpu_count()} cores, {'full' if opts.full else 'quick (default)'} mode: "
             f"**{wall_total:.0f} s** wall in all ({in_runs:.0f} s of it in impact3d)"
             + (f"; {reused} run{'s' if reused != 1 else ''} reused from an earlier invocation "
                "(`--reuse`), times from when they ran" if reused else "") + ".\n",
             "Columns of the tables (one row per run; DLM and DAM next to each other):\n",
             "- *criterion value(s)*: the problem's measure against its bound; *pass*: "
             "PASS / FAIL against the bound (reported, not enforced), `ref.` for a "
             "reference run.",
             "- *largest penetration*: max over the cycles of `NAME_pen_max` "
             "(history.txt), in the deck's length unit.",
             "- *contact work / E0*: `contact_work` at the end over the initial total "
             "energy E0 (negative: dissipated by contact).",
             "- *max abs(energy error)*: the `energy_error` column, which books the "
             "boundary and contact work (round-off if the balance is exact).",
             "- *contact momentum error*: norm of the sum over the cycles of "
             "`NAME_dmom_x/y/z` over the largest |momentum| of the run (zero to round-off "
             "for DLM).",
             "- *contact search / enforcement*: seconds (rank 0) over the run's seconds "
             "(`impact3d: done` line), in %; in brackets the share of the loop the run "
             "prints.\n"]
    builds = {e["rec"].get("exe_mtime") for e in entries}
    if len(builds) > 1:
        lines.append(f"**Note**: the runs used {len(builds)} different builds of the "
                     "executable (it was rebuilt while this ran); rerun for one build.\n")
    failed = failed_checks(sections)
    lines.append("**Criteria not met or runs failed**: " + ("; ".join(failed) if failed
                                                            else "none") + ".\n")
    return lines


def write_doc(path, opts, sections, wall_total, command):
    lines = header_lines(opts, sections, wall_total, command)
    for sec in sections:
        lines.extend(section_lines(sec))
    with open(path, "w", encoding="utf-8") as handle:
        handle.write("\n".join(lines))
    print(f"  wrote {os.path.relpath(path, ROOT)}", flush=True)


# --------------------------------------------------------------------------- main

def parse_args(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--exe", default=os.path.join(ROOT, "build", "impact3d"))
    parser.add_argument("--np", type=int, default=2)
    parser.add_argument("--mpirun", default="mpirun")
    parser.add_argument("--full", action="store_true",
                        help="add Sedov 45^3, Al on steel, Taylor and the tubes (long)")
    parser.add_argument("--workdir", default="/tmp/impact3d_verify_contact")
    parser.add_argument("--docs", default=os.path.join(ROOT, "docs"),
                        help="where verification-contact.md and img/ go")
    parser.add_argument("--reuse", action="store_true",
                        help="skip runs already done with the same deck and executable")
    parser.add_argument("--only", nargs="+", metavar="KEY",
                        help="run only these sections and replace them in the existing "
                             "verification-contact.md (sod, sedov, sedov_curved, verney, al, "
                             "taylor, tubes)")
    return parser.parse_args(argv)


def problem_steps(opts):
    """(key, name, callable(img) -> section) in report order. With --only,
    the named steps run, the long ones too."""
    steps = [("sod", "Sod", lambda img: do_sod(opts, img)),
             ("sedov", "Sedov", lambda img: do_sedov(opts, img,
                                                     SEDOV_FULL if opts.full else SEDOV_QUICK)),
             ("sedov_curved", "Sedov curved", lambda img: do_sedov_curved(
                 opts, img, SEDOV_CURVED_FULL if opts.full else SEDOV_CURVED_QUICK)),
             ("verney", "Verney", lambda img: do_verney(opts, img))]
    full = [("al", do_al_on_steel), ("taylor", do_taylor), ("tubes", do_tubes)]
    for key, step in full:
        if opts.full or (opts.only and key in opts.only):
            steps.append((key, FULL_TITLES[key], lambda img, step=step: step(opts, img)))
        else:
            steps.append((key, FULL_TITLES[key],
                          lambda img, key=key: not_run(key, FULL_TITLES[key])))
    return steps


def splice_doc(path, sections, order, command):
    """Put the given sections in place of the sections of the same title in the
    existing document (after the preceding one in report order when absent),
    each with a line saying how and when it was regenerated."""
    with open(path, encoding="utf-8") as handle:
        text = handle.read()
    parts = re.split(r"(?m)^(?=## )", text)
    head, blocks = parts[0], parts[1:]
    titles = [block.splitlines()[0][3:].strip() for block in blocks]
    git = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"],
                         capture_output=True, text=True).stdout.strip() or "unknown"
    for sec in sections:
        lines = section_lines(sec)
        lines.insert(1, f"*This section was regenerated on {datetime.date.today().isoformat()} "
                        f"(commit `{git}`) by `{command}`; the header above describes the last "
                        "full run.*\n")
        block = "\n".join(lines) + "\n"
        if sec["title"] in titles:
            blocks[titles.index(sec["title"])] = block
            continue
        at = len(blocks)
        earlier = order[:order.index(sec["key"])]
        for k in reversed(earlier):
            title = STEP_TITLES.get(k)
            if title in titles:
                at = titles.index(title) + 1
                break
        blocks.insert(at, block)
        titles.insert(at, sec["title"])
    with open(path, "w", encoding="utf-8") as handle:
        handle.write(head + "".join(blocks))
    print(f"  updated {os.path.relpath(path, ROOT)}", flush=True)


STEP_TITLES = {"sod": "Sod shock tube, non-matching meshes",
               "sedov": "Sedov blast wave split by a contact plane",
               "sedov_curved": "Sedov blast wave split along a curved contact surface"}


def main(argv=None):
    opts = parse_args(argv)
    if not os.access(opts.exe, os.X_OK):
        print(f"verify_contact.py: no executable {opts.exe}", file=sys.stderr)
        return 1
    img = os.path.join(opts.docs, "img")
    os.makedirs(img, exist_ok=True)
    os.makedirs(opts.workdir, exist_ok=True)
    start = time.monotonic()
    steps = problem_steps(opts)
    order = [key for key, _, _ in steps]
    if opts.only:
        unknown = [key for key in opts.only if key not in order]
        if unknown:
            print(f"verify_contact.py: --only: unknown section(s) {', '.join(unknown)} "
                  f"(valid: {', '.join(order)})", file=sys.stderr)
            return 1
        steps = [step for step in steps if step[0] in opts.only]
    sections = []
    for _, name, step in steps:
        print(name, flush=True)
        sections.append(step(img))
    wall = time.monotonic() - start
    shown = sys.argv[1:] if argv is None else list(argv)
    command = ("/usr/bin/python3 tools/verify_contact.py " + " ".join(shown)).strip()
    doc = os.path.join(opts.docs, "verification-contact.md")
    if opts.only and os.path.isfile(doc):
        splice_doc(doc, sections, order, command)
    else:
        write_doc(doc, opts, sections, wall, command)
    failed = [r["entry"]["name"] for sec in sections for r in sec.get("rows", [])
              if not r["entry"]["ok"]]
    print(f"done in {wall:.0f} s" + (f"; FAILED runs: {', '.join(failed)}" if failed else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
