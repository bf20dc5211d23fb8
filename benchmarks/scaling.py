#!/usr/bin/python3
"""Parallel contact (RCB) scaling benchmark: Taylor anvil and crossed tubes on
1, 2 and 4 ranks, with the time split into hydro, node halo exchange, contact
search (+ RCB), contact enforcement and contact migration; contact memory per
rank against replicated contact; and a projection of the contact share of the
step at 64 and 1024 ranks for a 10^7-zone problem.

With --weak, the weak-scaling benchmark of set-up and loop instead
(benchmarks/weak_scaling.py: its own options).

Usage (from the repository root):

    /usr/bin/python3 benchmarks/scaling.py [--exe build-release/impact3d]
        [--workdir /tmp/scaling] [--ranks 1 2 4] [--cases taylor_dlm_coarse ...]
        [--json benchmarks/scaling_results.json] [--section benchmarks/scaling_section.md]
        [--render-only]

Runs ``mpirun --oversubscribe -np N exe deck`` in WORKDIR/<case>_np<N>/ with a
copy of the problem deck whose ``t_end`` is shortened and whose dumps are
switched off (``dump_interval`` = 1e6). Each run's end-of-run summary lines
are parsed; the 1-minute load average is recorded before and after each run,
and a run whose load before it was above --max-load is repeated once after
waiting for the machine to quieten. Results go to the JSON file (merged with
what it already holds, so cases can be run in pieces) and the Markdown
section, which benchmarks/run_benchmarks.py includes in docs/benchmarks.md.
"""

import argparse
import json
import math
import os
import re
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")

TAYLOR = "problems/taylor_contact/taylor_case2_steel_%s_%s.nml"
TUBES = "problems/tubes/tubes_same_%s.nml"

# name -> (deck, t_end, extra text replacements, description)
CASES = {}
for _m in ("dlm", "dam"):
    CASES["taylor_%s_coarse" % _m] = (TAYLOR % (_m, "coarse"), 40.0, [],
                                      "Taylor anvil case 2, steel anvil, coarse rod mesh")
    CASES["taylor_%s_fine" % _m] = (TAYLOR % (_m, "fine"), 12.0, [],
                                    "Taylor anvil case 2, steel anvil, fine rod mesh")
    CASES["tubes_%s_coarse" % _m] = (TUBES % _m, 60.0, [],
                                     "crossed tubes, same stiffness, as committed")
    # 2x finer around the tube (n_theta 32 -> 64) and along it (n_axial 40 -> 80),
    # wall thickness kept at 3 zones: 4x the zones and 4x the contact nodes.
    CASES["tubes_%s_fine" % _m] = (TUBES % _m, 40.0,
                                   [("n_theta = 32", "n_theta = 64"),
                                    ("n_axial = 40", "n_axial = 80")],
                                   "crossed tubes, 2x finer in theta and axis")
DEFAULT_CASES = ["taylor_dlm_coarse", "taylor_dam_coarse", "tubes_dlm_coarse",
                 "tubes_dam_coarse"]

PATTERNS = {
    "zones": (r"mesh:\s+(\d+) zones, (\d+) nodes on (\d+) rank", (int, int, int)),
    "halo": (r"node halo exchange\s+([\d.]+) s", (float,)),
    "contact": (r"contact\s+([\d.]+) s search and RCB,\s+([\d.]+) s enforcement,"
                r"\s+([\d.]+) s migration \(\s*([\d.]+)% of the loop", (float,) * 4),
    "sets": (r"contact local sets (\d+) to (\d+) nodes per rank of (\d+) contact nodes;"
             r" (\d+) global searches", (int,) * 4),
    "memory": (r"contact memory per rank\s+([\d.]+) MB working set \(largest\),"
               r"\s+([\d.]+) MB whole-surface topology", (float, float)),
    "done": (r"done, (\d+) cycles,\s+([\d.]+) s \(\s*([\d.]+) s of it in dumps\)",
             (int, float, float)),
}


def load1():
    with open("/proc/loadavg", encoding="utf-8") as handle:
        return float(handle.read().split()[0])


def make_deck(case, path):
    deck, t_end, repl, _ = CASES[case]
    with open(os.path.join(ROOT, deck), encoding="utf-8") as handle:
        text = handle.read()
    text, n = re.subn(r"t_end\s*=\s*[\d.eE+-]+", "t_end = %.1f" % t_end, text, count=1)
    assert n == 1, "no t_end in " + deck
    text, n = re.subn(r"dump_interval\s*=\s*[\d.eE+-]+", "dump_interval = 1.0e6", text)
    assert n == 1, "no dump_interval in " + deck
    for old, new in repl:
        assert old in text, old
        text = text.replace(old, new)
    with open(path, "w", encoding="utf-8") as handle:
        handle.write(text)


def parse(log):
    out = {}
    for key, (pattern, types) in PATTERNS.items():
        m = re.search(pattern, log)
        if not m:
            raise RuntimeError("no '%s' line in the log:\n%s" % (key, log[-2000:]))
        out[key] = [t(g) for t, g in zip(types, m.groups())]
    zones, nodes, ranks = out["zones"]
    search, enforce, migrate, share = out["contact"]
    lmin, lmax, ncn, nsearch = out["sets"]
    ws, topo = out["memory"]
    cycles, total, dumps = out["done"]
    loop = total - dumps
    contact = search + enforce + migrate
    return {"zones": zones, "nodes": nodes, "ranks": ranks, "cycles": cycles,
            "total": total, "dumps": dumps, "loop": loop, "halo": out["halo"][0],
            "search": search, "enforcement": enforce, "migration": migrate,
            "contact": contact, "contact_share": share,
            "hydro": loop - contact - out["halo"][0],
            "local_min": lmin, "local_max": lmax, "contact_nodes": ncn,
            "global_searches": nsearch, "ws_mb": ws, "topo_mb": topo,
            "ns_core": 1e9 * loop * ranks / (zones * cycles),
            "ns_wall": 1e9 * loop / (zones * cycles)}


def run(exe, case, ranks, workdir, max_load):
    wd = os.path.join(workdir, "%s_np%d" % (case, ranks))
    os.makedirs(wd, exist_ok=True)
    make_deck(case, os.path.join(wd, "deck.nml"))
    cmd = ["mpirun", "--oversubscribe", "-np", str(ranks), exe, "deck.nml"]
    result = None
    for attempt in range(2):
        before = load1()
        t0 = time.time()
        proc = subprocess.run(cmd, cwd=wd, env=ENV, capture_output=True, text=True)
        wall = time.time() - t0
        after = load1()
        with open(os.path.join(wd, "log.txt"), "w", encoding="utf-8") as handle:
            handle.write(proc.stdout + proc.stderr)
        if proc.returncode != 0:
            raise RuntimeError("%s on %d ranks failed:\n%s" % (case, ranks, proc.stderr[-3000:]))
        result = parse(proc.stdout)
        result.update({"case": case, "mpirun_wall": wall, "load_before": before,
                       "load_after": after, "attempt": attempt + 1,
                       "oversubscribed": ranks > (os.cpu_count() or 1),
                       "command": "cd %s && OMPI_ALLOW_RUN_AS_ROOT=1 "
                                  "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 %s" % (wd, " ".join(cmd))})
        print("%-18s np=%d loop %7.2f s  hydro %6.2f halo %5.2f search %5.2f enf %5.2f "
              "migr %5.2f  share %5.1f%%  load %.2f -> %.2f" %
              (case, ranks, result["loop"], result["hydro"], result["halo"], result["search"],
               result["enforcement"], result["migration"], result["contact_share"],
               before, after), flush=True)
        # Our own earlier run decays in the 1-minute average; only the load
        # before the run (others' work) decides whether it was disturbed.
        if before <= max_load or attempt == 1:
            break
        print("  load %.2f before the run: waiting and repeating" % before, flush=True)
        time.sleep(30)
    return result


# The text around the generated tables (written after looking at the numbers
# of the run recorded in scaling_results.json; update it with them).
NOTES = {}
NOTES["command"] = r"""# search on the RCB parts, sparse exchanges, Release (cmake -DCMAKE_BUILD_TYPE=Release), 2026-11-22
/usr/bin/python3 benchmarks/scaling.py --exe build-release/impact3d --workdir /tmp/scaling2
/usr/bin/python3 benchmarks/scaling.py --exe build-release/impact3d --workdir /tmp/scaling2 \
    --max-load 1.5 --cases taylor_dlm_fine taylor_dam_fine tubes_dlm_fine
# after the pair-only RCB weights and the load-drift re-cut (commit "RCB weights: ..."):
/usr/bin/python3 benchmarks/scaling.py --exe build-release/impact3d --workdir /tmp/scaling4 \
    --max-load 99 --cases taylor_dlm_coarse taylor_dam_coarse tubes_dlm_coarse \
    tubes_dam_coarse tubes_dlm_fine
# each run: cd <workdir>/<case>_np<N> && mpirun --oversubscribe -np <N> impact3d deck.nml"""
NOTES["preamble"] = r"""Decks: `problems/taylor_contact/taylor_case2_steel_{dlm,dam}_{coarse,fine}.nml`
(contact from the first cycle; coarse t_end = 40 us, fine t_end = 12 us;
measured with the rods' copper of the time, Steinberg's annealed `cu_ofhc`, before the
decks moved to the fitted `cu_taylor`) and
`problems/tubes/tubes_same_{dlm,dam}.nml` (7680 zones; contact from 26 us, t_end = 60 us),
each with `dump_interval = 1.0e6` (the summary's dump time is subtracted anyway).
Fine tubes: the same deck 2x finer around the tube (`n_theta` 32 -> 64) and along
it (`n_axial` 40 -> 80), wall kept at 3 zones (30 720 zones), t_end = 40 us (contact
for the last 14 us), DLM only. Machine: 2-core AMD EPYC VM, Open MPI 4.1.4,
gfortran -O3. No other work ran on the machine this time (1-minute load before the runs
0.5-3.5, "load before" below: our own previous run decaying, as the second set
ran back to back): 2 ranks are real parallel runs, 4 ranks are oversubscribed
(2 processes per core).

**Executable.** The code with the search on the RCB parts (no replicated
positions or search) and sparse exchanges. Every run's final dump is bitwise
identical to the replicated-search code of the previous measurement and across
1-4 ranks (Taylor DAM/DLM, tubes DAM/DLM, `h5diff --exclude-path /run`)."""
NOTES["split"] = r"""Loop = run time minus dumps; hydro = loop - (search+RCB + enforcement +
migration) - halo, so hydro also takes whatever waiting the timers do not see.
"Search+RCB" starts with the first collective of every contact step (the maximum
node speed, before the rebuild decision), so on 2 and 4 ranks it **absorbs the
load imbalance of the hydro** (METIS balances zones, not the contact nodes and
boundary work); migration (marked *) likewise absorbs the waits in the later
exchanges of each stage and holds the owners' sums in key order. On 1 rank both
are real work: search+RCB 0.05-0.86 s (0.2-1.0% of the loop), migration 0.3-0.7 s.

* **2 ranks now run faster than 1**: Taylor coarse loop 13.5 -> 7.4 s (DLM)
  and 14.2 -> 7.9 s (DAM), tubes coarse 21.0 -> 12.2 s (DLM), fine tubes
  93 -> 56 s. 4 oversubscribed ranks do not gain over 2 (two processes per
  core, every exchange waits for a descheduled rank).
* **Enforcement scales** with the RCB parts (largest over the ranks): Taylor
  coarse DLM 1.18 -> 0.64 -> 0.37 s, DAM 1.68 -> 0.90 -> 0.50 s on 1, 2, 4 ranks;
  the largest local set falls 241 -> 186 -> 135 (DLM) and 262 -> 197 -> 155 (DAM):
  the rings around each part's pairs cost 50% over the ideal halving at 2
  ranks.
* **Search**: on 1 rank the search (with the RCB, the plan and the local
  sets) costs what the replicated one did (0.05-0.06 s Taylor, 0.2-0.26 s
  tubes, 0.86 s fine tubes); on 2 and 4 ranks the column is dominated by the
  wait described above (tubes: METIS puts one tube on each rank and the struck
  tube's ranks wait for the other).
* **Tubes, pair balance**: the first version weighted every key node by 1 plus
  its pairs; on the tubes the 1's (2706 surface nodes) outweighed the ~100
  pairs of the crossing patch and every pair landed on one part (local sets
  0-102 on 2 and 4 ranks). Weights are now the pairs alone, and a search
  whose pairs put more than 1.2x the mean on one part (with at least 16 pairs
  per part) re-cuts the RCB with the fresh counts and searches again. End-of-run
  line `contact pairs per part` (`<workdir>/<case>_np<N>/log.txt`), largest
  part over the mean: Taylor coarse 1.02-1.06 on average (worst 1.07-1.17, no
  re-cut) on 2-4 ranks; tubes coarse 1.08-1.30 (worst 2-4 when the first
  handful of pairs appears; 16 re-cuts in 86 searches for DLM on 4 ranks).
  Tubes local sets are back to 74-95 nodes (DLM, 2 ranks), as with the
  replicated search's exact weights."""
NOTES["memory"] = r"""Working set = per-node arrays of the local set (10 doubles + 1 integer), the
local surfaces, their geometry caches and the pair caches (DLM's facet pairs,
DAM's exchange lists), largest over the ranks; whole-surface topology = global
ids, masses, owners and the whole surfaces' segment lists, held by every rank
(about 95-100 B per contact node: 0.035 MB for 369 nodes, 0.271 MB for 2706).
Replicated contact (before the RCB) held on every rank x, v, f, fc of every
contact node of the whole surfaces (12 doubles = 96 B per node), their geometry
caches and all the pairs. Two estimates from the 1-rank run of the same case
(which holds all the pairs but only the nodes of the pairs' segments and rings):
*scaled* = 1-rank working set x contact nodes / 1-rank local set + topology
(every byte treated as per node: an upper estimate, since pair caches do not
grow with the surface); *lower bound* = 1-rank working set + 96 B x (contact
nodes - 1-rank local set) + topology.

The RCB working set falls with the ranks (Taylor DLM 0.507 -> 0.296 -> 0.180 MB)
while the replicated one would stay at 0.55-0.81 MB on every rank. The search
on the parts adds one array of 3 doubles per contact node (`xs`, written only
where the part received positions; untouched pages are never mapped) and
no longer sums all positions onto every rank. What stays replicated is the
static topology (about 100 B per contact node: 100 MB at 10^6 contact nodes)
and a few O(N_c) scans per search over whole-surface mark arrays."""
NOTES["projection"] = r"""Model of one cycle on one rank for a 10^7-zone problem (everything below is
**assumed** unless marked measured):

* hydro + halo compute: measured 1-rank hydro ns per zone-cycle of the Taylor
  runs times 10^7 / P zones; halo: 2 exchanges per cycle of 12 doubles per
  shared node over 6 (10^7/P)^(2/3) nodes, 26 messages each;
* contact nodes N_c = 10^5 and 10^6 (the measured meshes scaled at zones^(2/3)
  give 5 x 10^4 for the Taylor anvil and 3 x 10^5 for the tubes); the local-set
  fraction of N_c as measured on 1 rank (65-71%); the RCB splits the local
  nodes over **all** P parts, each part's local set = n + 2 x 4 sqrt(n) ring
  nodes for n = fraction x N_c / P;
* enforcement: measured us per local node per stage x local set x 2 stages;
* migration per stage: 72 B (x, v, f) + 48 B (DLM record) per local node, or
  72 + 104 + 24 + 48 = 248 B (DAM); latency alpha = 2 us, bandwidth 10 GB/s;
  3 (DLM) or 8 (DAM) exchanges per stage to ~26 partners (sparse, as the code
  now does), and 3 (DLM) or 5 (DAM) all-to-alls of one count per rank pair or
  allreduces (2 log2 P latencies + 4 P bytes each);
* rebuild every K cycles (measured K = 14.7-14.8): the RCB (~3 log2 P
  histogram allreduces per level, log2 P levels); the search of the part's
  share of the contact nodes (N_c / P plus a ring) at the measured 1-rank cost
  per contact node per rebuild (which includes the plan and the local sets),
  after the homes shipped them (120 B per item); 3 sparse exchanges with
  their counts (shipping, plan, key counts); O(N_c) scans of whole-surface
  arrays on every rank, 5 ns per contact node (assumed).
* "before" columns: the previous code (positions summed onto every rank, the
  whole search on every rank, dense alltoallv with P - 1 messages each)."""
NOTES["conclusion"] = r"""With the search on the parts and sparse exchanges the projected contact
share at **1024 ranks is 8% (DLM) and 12% (DAM) for 10^5 contact nodes and
24% / 31% for 10^6**, against 64-91% for the previous code, where the
replicated rebuild (12-133 ms per cycle) and the dense alltoallv latency
(12.5-33 ms) dominated. At 64 ranks contact is 2-4% (10^5) and 17-22% (10^6),
mostly enforcement itself (5.3-65 ms per cycle), which scales with the parts.
What remains: at 10^6 contact nodes and 1024 ranks the per-stage exchanges
and the all-to-alls of counts (1.2-1.3 ms) are a quarter of the contact
time; the whole-surface topology on every rank (100 B per contact node) and
its O(N_c) scans per search (0.3 ms per search at 10^6) would have to become
part-local for 10^7 contact nodes. These are model numbers from a 2-core
machine: the latency and bandwidth are assumptions, not measurements."""


# --------------------------------------------------------------------------
# Projection to 10^7 zones at 64 and 1024 ranks.

PROJ = {
    "zones": 1.0e7,
    "ranks": [64, 1024],
    "contact_nodes": [1.0e5, 1.0e6],
    "alpha": 2.0e-6,          # s, network latency per message (assumed)
    "beta": 10.0e9,           # B/s, network bandwidth per rank (assumed)
    "rebuild_every": None,    # cycles between global searches (measured, Taylor DLM 1 rank)
    "halo_doubles": 12,       # doubles per shared node per cycle in the node halo (assumed)
    "halo_neighbours": 26,    # messages per halo exchange (assumed)
    "ring_width": 2.0,        # local set = n + ring_width * 4 sqrt(n) (ring nodes, assumed)
}
# Bytes per local node per stage (formulas of src/contact/contact_enforce.f90):
# owners -> parts x, v, f (9 doubles); back: DLM one record (3 int64 + 3
# doubles) per local node; DAM an exchange entry (3 int64 + 10 doubles), the
# matched velocities back to the parts (3 doubles), the put-back record
# (3 int64 + 3 doubles).
BYTES_PER_NODE = {"dlm": 9 * 8 + 48, "dam": 9 * 8 + 104 + 24 + 48}
# Collectives per stage (contact_apply): velocity max (allreduce), gather
# (alltoallv), DLM records (alltoall of counts + 2 alltoallv, sent whatever
# the method), diagnostics (allreduce, corrector only); DAM adds its exchange
# records (alltoall + 2 alltoallv), the matched-velocity scatter (alltoallv)
# and the put-back records (alltoall + 2 alltoallv). The alltoall of counts
# is costed like an allreduce (log2 P latencies).
ALLTOALLV_PER_STAGE = {"dlm": 3, "dam": 8}
ALLREDUCE_PER_STAGE = {"dlm": 3, "dam": 5}


def projection(results):
    """Per-cycle cost model; the measured constants come from the 1-rank
    coarse Taylor runs (DLM and DAM). Two variants: the code as it is
    (search on the RCB parts, sparse exchanges) and, for comparison, the
    previous one (replicated positions and search, dense alltoallv)."""
    out = {"assumptions": dict(PROJ), "rows": []}
    for method in ("dlm", "dam"):
        r = results.get("taylor_%s_coarse" % method, {}).get("1")
        if not r:
            continue
        cyc = r["cycles"]
        c_hydro = (r["hydro"] + r["halo"]) / (r["zones"] * cyc)     # s per zone-cycle
        c_enf = r["enforcement"] / (2 * cyc * r["local_max"])       # s per local node per stage
        c_search = r["search"] / (r["global_searches"] * r["contact_nodes"])  # s per contact node per rebuild
        k = cyc / r["global_searches"]
        const = {"local_fraction": r["local_max"] / r["contact_nodes"],
                 "hydro_s_per_zone_cycle": c_hydro, "enf_s_per_node_stage": c_enf,
                 "search_s_per_node_rebuild": c_search, "cycles_per_rebuild": k}
        out["const_" + method] = const
        for ncn in PROJ["contact_nodes"]:
            for p in PROJ["ranks"]:
                a, b = PROJ["alpha"], PROJ["beta"]
                lg = math.log2(p)
                zr = PROJ["zones"] / p
                hydro = c_hydro * zr
                halo = 2 * (PROJ["halo_neighbours"] * a
                            + 6 * zr ** (2.0 / 3.0) * PROJ["halo_doubles"] * 8 / b)
                # Only the nodes near a pair are in the local sets: the
                # 1-rank local set over the contact nodes (Taylor coarse)
                # gives that fraction; the RCB spreads them over all P parts.
                n = r["local_max"] / r["contact_nodes"] * ncn / p
                local = n + PROJ["ring_width"] * 4 * math.sqrt(n)
                enf = 2 * c_enf * local
                # Per stage: the exchanges to the non-empty partners (~26,
                # sparse) or to all P - 1 (dense), the all-to-all of counts
                # before each record exchange (one integer per rank pair:
                # 2 log2 P latencies + 4 P bytes), the allreduces.
                bytes_stage = BYTES_PER_NODE[method] * local
                counts = ALLREDUCE_PER_STAGE[method] * (2 * lg * a + 4 * p / b)
                mig_dense = 2 * (ALLTOALLV_PER_STAGE[method] * (p - 1) * a
                                 + ALLREDUCE_PER_STAGE[method] * 2 * lg * a + bytes_stage / b)
                mig = 2 * (ALLTOALLV_PER_STAGE[method] * 26 * a + counts + bytes_stage / b)
                # Rebuild every k cycles. The RCB: ~ 3 log2 P histogram
                # allreduces per level, log2 P levels. Now: every part
                # searches its share of all contact nodes (the keys in its
                # region and the candidates reaching it: N_c / P plus a ring)
                # at the measured 1-rank cost per contact node, after the
                # homes shipped them (120 B per item, ~26 partners); the
                # plan and the key counts (2 sparse exchanges + counts); the
                # scans of whole-surface arrays (marks, rings, the local-set
                # map) over all N_c on every rank, 5 ns per node (assumed).
                # Before: allreduce of 3 doubles per contact node (ring:
                # 2 x bytes / beta + 2 log2 P latencies), the search of all
                # contact nodes on every rank, the plan (alltoall + dense
                # alltoallv).
                rcb = 3 * lg * 2 * lg * a / k
                m = ncn / p + PROJ["ring_width"] * 4 * math.sqrt(ncn / p)
                search = (c_search * m + 120 * m / b + 3 * (26 * a + 2 * lg * a + 4 * p / b)
                          + 5e-9 * ncn) / k
                allred_old = (2 * 24 * ncn / b + 2 * lg * a) / k
                search_old = c_search * ncn / k
                plan_old = 2 * (p - 1) * a / k
                contact = enf + mig + search + rcb
                contact_old = enf + mig_dense + allred_old + search_old + rcb + plan_old
                total = hydro + halo + contact
                total_old = hydro + halo + contact_old
                out["rows"].append({
                    "method": method, "contact_nodes": ncn, "ranks": p,
                    "hydro_ms": 1e3 * hydro, "halo_ms": 1e3 * halo,
                    "enf_ms": 1e3 * enf, "mig_ms": 1e3 * mig, "mig_dense_ms": 1e3 * mig_dense,
                    "search_ms": 1e3 * search, "rcb_ms": 1e3 * rcb,
                    "search_old_ms": 1e3 * (allred_old + search_old + plan_old),
                    "share": 100 * contact / total,
                    "share_old": 100 * contact_old / total_old})
    return out


# --------------------------------------------------------------------------

def fmt(x, d=2):
    return ("%." + str(d) + "f") % x


def render(data, path):
    res = data["results"]
    L = []
    add = L.append
    add("## 5. Parallel contact (RCB): scaling, memory, projection (kept in benchmarks/scaling_section.md)")
    add("")
    add("Written by `benchmarks/scaling.py` (raw numbers in `benchmarks/scaling_results.json`); "
        "the text between the generated tables is kept in the script (NOTES).")
    add("")
    add("```")
    add(NOTES["command"])
    add("```")
    add("")
    add(NOTES["preamble"])
    add("")
    add("### Time split (seconds over the time loop; contact and halo are the largest over the ranks)")
    add("")
    add("| case | zones | ranks | cycles | loop | hydro | halo | search+RCB | enforcement | migration* "
        "| contact share | ns/zone-cycle (core) | ns/zone-cycle (wall) | load before |")
    add("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for case in sorted(res, key=lambda c: list(CASES).index(c)):
        for nr in sorted(res[case], key=int):
            r = res[case][nr]
            mark = " (oversubscribed)" if r["oversubscribed"] else ""
            add("| %s | %d | %s%s | %d | %s | %s | %s | %s | %s | %s | %s%% | %s | %s | %.2f |" % (
                case, r["zones"], nr, mark, r["cycles"], fmt(r["loop"]), fmt(r["hydro"]),
                fmt(r["halo"]), fmt(r["search"]), fmt(r["enforcement"]), fmt(r["migration"]),
                fmt(r["contact_share"], 1), fmt(r["ns_core"], 0), fmt(r["ns_wall"], 0),
                r["load_before"]))
    add("")
    add(NOTES["split"])
    add("")
    add("### Contact memory per rank")
    add("")
    add("| case | ranks | contact nodes | local set min-max | working set (largest) | "
        "whole-surface topology | replicated, scaled | replicated, lower bound | "
        "RCB / replicated (scaled - lower bound) |")
    add("|---|---|---|---|---|---|---|---|---|")
    for case in sorted(res, key=lambda c: list(CASES).index(c)):
        for nr in sorted(res[case], key=int):
            r = res[case][nr]
            one = res[case].get("1", r)
            rep = replicated_mb(one)
            low = replicated_low_mb(one)
            add("| %s | %s%s | %d | %d-%d | %.3f MB | %.3f MB | %.3f MB | %.3f MB | %s |" % (
                case, nr, " (os)" if r["oversubscribed"] else "", r["contact_nodes"],
                r["local_min"], r["local_max"], r["ws_mb"], r["topo_mb"], rep,
                low, "%.2f-%.2f" % ((r["ws_mb"] + r["topo_mb"]) / rep,
                                    (r["ws_mb"] + r["topo_mb"]) / low)))
    add("")
    add(NOTES["memory"])
    add("")
    proj = data.get("projection")
    if proj:
        add("### Projection: contact share of the step, 10^7 zones, 64 and 1024 ranks")
        add("")
        add(NOTES["projection"])
        add("")
        for m in ("dlm", "dam"):
            c = proj.get("const_" + m)
            if c:
                add("* measured (%s, Taylor coarse, 1 rank): hydro+halo %.0f ns per zone-cycle; "
                    "enforcement %.2f us per local node per stage; global search "
                    "(with the RCB, the plan and the local sets) %.2f us per contact node per "
                    "rebuild; "
                    "a rebuild every %.1f cycles; %.0f%% of the contact nodes in the local "
                    "sets." % (
                        m.upper(), 1e9 * c["hydro_s_per_zone_cycle"],
                        1e6 * c["enf_s_per_node_stage"], 1e6 * c["search_s_per_node_rebuild"],
                        c["cycles_per_rebuild"], 100 * c["local_fraction"]))
        add("")
        add("Milliseconds per cycle per rank:")
        add("")
        add("| method | contact nodes | ranks | hydro | halo | enforcement | migration "
            "| search on the parts (amortised) | RCB | **contact share** | before: migration "
            "(dense) | before: replicated rebuild | before: contact share |")
        add("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        for r in proj["rows"]:
            add("| %s | %.0e | %d | %.2f | %.3f | %.3f | %.3f | %.3f | %.3f | **%.0f%%** | "
                "%.3f | %.2f | %.0f%% |" % (
                    r["method"].upper(), r["contact_nodes"], r["ranks"], r["hydro_ms"],
                    r["halo_ms"], r["enf_ms"], r["mig_ms"], r["search_ms"], r["rcb_ms"],
                    r["share"], r["mig_dense_ms"], r["search_old_ms"], r["share_old"]))
        add("")
        add(NOTES["conclusion"])
        add("")
    with open(path, "w", encoding="utf-8") as handle:
        handle.write("\n".join(L).rstrip() + "\n")


def replicated_mb(r):
    """Replicated contact per rank, scaled estimate (upper): every rank held
    the whole surfaces, so the 1-rank working set (which holds all the pairs
    but only the nodes of the pairs' segments and rings) is scaled by contact
    nodes / local set, as if every byte of it were per node (per-node arrays
    and per-segment geometry caches are; the pair caches are not, hence an
    upper estimate); plus the whole-surface topology."""
    return r["ws_mb"] * r["contact_nodes"] / r["local_max"] + r["topo_mb"]


def replicated_low_mb(r):
    """Replicated contact per rank, lower bound from first principles: the
    1-rank working set (all pairs and their caches) plus x, v, f, fc
    (12 doubles = 96 B) for every contact node outside the 1-rank local set,
    plus the whole-surface topology."""
    return (r["ws_mb"] + 96e-6 * (r["contact_nodes"] - r["local_max"]) + r["topo_mb"])


def main():
    if "--weak" in sys.argv:
        # Weak scaling of set-up and loop: benchmarks/weak_scaling.py.
        sys.argv.remove("--weak")
        import weak_scaling
        return weak_scaling.main()
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exe", default=os.path.join(ROOT, "build-release", "impact3d"))
    p.add_argument("--workdir", default="/tmp/scaling")
    p.add_argument("--ranks", type=int, nargs="+", default=[1, 2, 4])
    p.add_argument("--cases", nargs="+", default=DEFAULT_CASES, choices=sorted(CASES))
    p.add_argument("--max-load", type=float, default=1.0,
                   help="repeat a run once if the 1-min load before it was above this")
    p.add_argument("--json", default=os.path.join(ROOT, "benchmarks", "scaling_results.json"))
    p.add_argument("--section", default=os.path.join(ROOT, "benchmarks", "scaling_section.md"))
    p.add_argument("--render-only", action="store_true")
    args = p.parse_args()

    data = {"results": {}}
    if os.path.exists(args.json):
        with open(args.json, encoding="utf-8") as handle:
            data = json.load(handle)
    if not args.render_only:
        for case in args.cases:
            for nr in args.ranks:
                r = run(os.path.abspath(args.exe), case, nr, args.workdir, args.max_load)
                data["results"].setdefault(case, {})[str(nr)] = r
                data["projection"] = projection(data["results"])
                with open(args.json, "w", encoding="utf-8") as handle:
                    json.dump(data, handle, indent=1, sort_keys=True)
    data["projection"] = projection(data["results"])
    with open(args.json, "w", encoding="utf-8") as handle:
        json.dump(data, handle, indent=1, sort_keys=True)
    render(data, args.section)
    print("wrote", args.json, "and", args.section)


if __name__ == "__main__":
    sys.exit(main())
