"""Weak-scaling runs: the Sedov box stacked along z, K x K x K N zones on N
ranks ([0, 1.2] x [0, 1.2] x [0, 1.2 N], symmetry planes xmin, ymin and
zmin, the problems/sedov deposit at the origin, t_end = 5e-4: about four
cycles), and the parsing of a run's end-of-run report (peak memory per rank,
set-up phases, partition line, halo traffic)."""

import os
import re
import subprocess

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")

SETUP_PHASES = ("mesh generate", "dual graph", "partition", "migrate", "halo plans",
                "contact set-up")


def sedov_stack_deck(k, n, dumps=True):
    """Deck text: K^3 zones per rank on N ranks."""
    dump = "  dump_cycles = 2\n" if dumps else ""
    return f"""&control
  title = 'weak scaling Sedov, {k}^3 zones per rank, {n} ranks'
  units = 'none'
  t_end = 5.0e-4
/
&mesh
  type = 'box'
  x = 0.0, 1.2
  nx = {k}
  y = 0.0, 1.2
  ny = {k}
  z = 0.0, {1.2 * n}
  nz = {k * n}
/
&material
  name = 'gas', eos = 'ideal_gas', gamma = 1.4
/
&block
  name = 'all', material = 'gas'
/
&region
  density = 1.0, energy = 1.0e-10
  deposit_energy = 0.106384, deposit_point = 0.0, 0.0, 0.0
/
&boundary set = 'xmin', type = 'symmetry' /
&boundary set = 'ymin', type = 'symmetry' /
&boundary set = 'zmin', type = 'symmetry' /
&output
  status_every = 1000
{dump}/
"""


def sedov_import_deck(k, n, mesh_type, mesh_file, dumps=True):
    """Deck text: the stacked Sedov box read from mesh_file (type 'gmsh' or
    'exodus'; element block or physical volume 'all', face sets xmin ...
    zmax), as write_gmsh_box and tests/tools/exodus_box write it."""
    text = sedov_stack_deck(k, n, dumps)
    start, end = text.index("&mesh"), text.index("/", text.index("&mesh")) + 1
    return text[:start] + f"&mesh type = '{mesh_type}', file = '{mesh_file}' /" + text[end:]


def write_gmsh_box(path, nx, ny, nz, lx, ly, lz):
    """A Gmsh 2.2 ASCII box [0, lx] x [0, ly] x [0, lz] of nx x ny x nz
    hexahedra (physical volume 'all', tag 1), numbered i fastest as the box
    generator numbers them, with quadrilaterals in the physical surfaces
    xmin, xmax, ymin, ymax, zmin, zmax (tags 1-6), outward."""
    def node(i, j, k):
        return 1 + i + (nx + 1) * (j + (ny + 1) * k)
    quads = []
    for k in range(nz):
        for j in range(ny):
            quads.append((1, (node(0, j, k), node(0, j, k + 1), node(0, j + 1, k + 1),
                              node(0, j + 1, k))))
            quads.append((2, (node(nx, j, k), node(nx, j + 1, k), node(nx, j + 1, k + 1),
                              node(nx, j, k + 1))))
    for k in range(nz):
        for i in range(nx):
            quads.append((3, (node(i, 0, k), node(i + 1, 0, k), node(i + 1, 0, k + 1),
                              node(i, 0, k + 1))))
            quads.append((4, (node(i, ny, k), node(i, ny, k + 1), node(i + 1, ny, k + 1),
                              node(i + 1, ny, k))))
    for j in range(ny):
        for i in range(nx):
            quads.append((5, (node(i, j, 0), node(i, j + 1, 0), node(i + 1, j + 1, 0),
                              node(i + 1, j, 0))))
            quads.append((6, (node(i, j, nz), node(i + 1, j, nz), node(i + 1, j + 1, nz),
                              node(i, j + 1, nz))))
    nnode = (nx + 1) * (ny + 1) * (nz + 1)
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n7\n")
        for t, name in enumerate(("xmin", "xmax", "ymin", "ymax", "zmin", "zmax"), start=1):
            f.write(f'2 {t} "{name}"\n')
        f.write('3 1 "all"\n$EndPhysicalNames\n$Nodes\n%d\n' % nnode)
        for k in range(nz + 1):
            for j in range(ny + 1):
                f.write("".join(f"{node(i, j, k)} {repr(lx * i / nx)} {repr(ly * j / ny)} "
                                f"{repr(lz * k / nz)}\n" for i in range(nx + 1)))
        f.write("$EndNodes\n$Elements\n%d\n" % (len(quads) + nx * ny * nz))
        e = 0
        for tag, q in quads:
            e += 1
            f.write(f"{e} 3 2 {tag} {tag} {q[0]} {q[1]} {q[2]} {q[3]}\n")
        for k in range(nz):
            for j in range(ny):
                rows = []
                for i in range(nx):
                    e += 1
                    c = (node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k),
                         node(i, j + 1, k), node(i, j, k + 1), node(i + 1, j, k + 1),
                         node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1))
                    rows.append(f"{e} 5 2 1 1 " + " ".join(map(str, c)) + "\n")
                f.write("".join(rows))
        f.write("$EndElements\n")


def parse_report(text):
    """The run report's figures: memory (MB), set-up phases (s), partition
    and halo lines."""
    out = {}
    m = re.search(r"peak memory per rank \(VmHWM\): rank 0 ([\d.]+) MB, median ([\d.]+) MB, "
                  r"largest ([\d.]+) MB \(rank (\d+)\)", text)
    if m:
        out["rss_rank0"], out["rss_median"], out["rss_largest"] = (float(m.group(i))
                                                                  for i in (1, 2, 3))
    m = re.search(r"mesh read: peak memory per rank \(VmHWM\) so far: rank 0 ([\d.]+) MB, "
                  r"largest ([\d.]+) MB", text)
    if m:
        out["rss_read_rank0"], out["rss_read_largest"] = float(m.group(1)), float(m.group(2))
    for name in ("set-up",) + SETUP_PHASES + ("step",):
        m = re.search(r"^\s+" + re.escape(name) + r"\s+([\d.]+)", text, re.M)
        if m:
            out["t_" + name] = float(m.group(1))
    m = re.search(r"partition: (\d+) parts, edge cut (\d+) faces, imbalance ([\d.]+)%, ghost "
                  r"nodes per rank <= (\d+), set-up sent <= ([\d.]+) MB per rank", text)
    if m:
        out["edge_cut"] = int(m.group(2))
        out["imbalance_pct"] = float(m.group(3))
        out["ghost_nodes_max"] = int(m.group(4))
        out["setup_sent_mb"] = float(m.group(5))
    m = re.search(r"halo exchange per cycle, largest rank: ([\d.]+) kB in ([\d.]+) messages", text)
    if m:
        out["halo_kb_per_cycle"] = float(m.group(1))
        out["halo_messages_per_cycle"] = float(m.group(2))
    m = re.search(r"done, (\d+) cycles", text)
    if m:
        out["cycles"] = int(m.group(1))
    return out


def run_stack(exe, k, n, workdir, mpiexec="mpirun", deck_text=None, extra=()):
    """Run the stacked deck (or deck_text) on n ranks in workdir; returns
    (exit code, parsed report, output)."""
    os.makedirs(workdir, exist_ok=True)
    deck = os.path.join(workdir, "deck.nml")
    with open(deck, "w") as f:
        f.write(deck_text if deck_text is not None else sedov_stack_deck(k, n))
    cmd = [mpiexec, "--oversubscribe", "-np", str(n), exe, *extra, "deck.nml"]
    r = subprocess.run(cmd, cwd=workdir, env=ENV, capture_output=True, text=True)
    return r.returncode, parse_report(r.stdout), r.stdout + r.stderr


def contact_stack_deck(k, n, method="dlm", dumps=True):
    """Deck text: the Al-on-steel pair stacked along z, one pair per rank.
    Pair i: a 304 SS box [0, 1.2]^2 x [2.4 i, 2.4 i + 0.6] at rest under an
    Al 6061 box [0, 1.2]^2 x [2.4 i + 0.6, 2.4 i + 1.2] at 0.01 cm/us along
    -z, K x K x K/2 zones each (K^3 per pair); one interface whose sides are
    the pairs' touching faces; symmetry planes xmin and ymin; t_end = 2/K
    (about four cycles)."""
    half = max(k // 2, 1)
    dump = "  dump_cycles = 2\n" if dumps else ""
    parts, regions = [], []
    for i in range(n):
        z0 = 2.4 * i
        parts.append(f"&mesh name = 'ss{i}', x = 0.0, 1.2, nx = {k}, y = 0.0, 1.2, ny = {k}, "
                     f"z = {z0:.6g}, {z0 + 0.6:.6g}, nz = {half}, block = 'ss' /")
        parts.append(f"&mesh name = 'al{i}', x = 0.0, 1.2, nx = {k}, y = 0.0, 1.2, ny = {k}, "
                     f"z = {z0 + 0.6:.6g}, {z0 + 1.2:.6g}, nz = {half}, block = 'al' /")
    surf_a = ", ".join(f"al{i}_zmin" for i in range(n))
    surf_b = ", ".join(f"ss{i}_zmax" for i in range(n))
    nl = "\n"
    return f"""&control
  title = 'weak scaling contact, Al on steel, {k}^3 zones per pair, {n} pairs'
  t_end = {2.0 / k:.6g}
/
{nl.join(parts)}
&material name = 'al', eos = 'mie_gruneisen', library = 'al6061', strength = 'steinberg_guinan' /
&material name = 'ss', eos = 'mie_gruneisen', library = 'ss304', strength = 'steinberg_guinan' /
&block name = 'al', material = 'al' /
&block name = 'ss', material = 'ss' /
&region block = 'al', density = 2.703, velocity = 0.0, 0.0, -0.01 /
&region block = 'ss', density = 7.90 /
&boundary set = 'xmin', type = 'symmetry' /
&boundary set = 'ymin', type = 'symmetry' /
&contact name = 'hit', surface_a = '{surf_a}', surface_b = '{surf_b}', method = '{method}' /
&output
  status_every = 1000
{dump}/
"""
