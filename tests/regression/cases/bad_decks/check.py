#!/usr/bin/python3
"""Bad-deck regression test for impact3d.

Usage: check.py /path/to/impact3d [--mpiexec mpirun --np 2] [--jobs 4] [--verbose]

Each case starts from a small valid deck (a 10 x 1 x 1 Sod-like box whose
&output directory is the case's own temporary directory), plants one defect
(or, for the "every problem at once" case, several), runs the program in a
fresh temporary directory and checks that

  1. the exit code is 1 (input error),
  2. stderr holds every expected message fragment (group, key and a word of
     the reason, as in `input error: &control: t_end: required ...`),
  3. no *.h5 dump and no history.txt was written in the case directory,
  4. the summary line `impact3d: N input error(s); nothing was run` is there,
     and N is the number of `input error:` lines printed,
  5. stderr holds none of the case's unwanted fragments (e.g. a consequence
     of the planted defect reported as a second problem), and no 'STOP n'
     line of the Fortran run-time library.

A last case runs the base deck itself and must exit 0, so that the failures
above are known to come from the planted defects. Standard library only.
"""

import argparse
import concurrent.futures
import os
import re
import shutil
import subprocess
import sys
import tempfile

CASE_TIMEOUT = 30.0  # seconds per run

# The valid base deck. {dir} becomes the case directory (also the working
# directory) after a case's edits, so edits may use {dir} too.
BASE_DECK = """\
! bad_decks.py base deck: Sod-like shock tube, 10 x 1 x 1 zones, symmetry walls.
&control
  title = 'bad-deck base'
  t_end = 0.05
  cfl = 0.5
/
&mesh
  type = 'box'
  x = 0.0, 1.0
  nx = 10
  y = 0.0, 0.1
  ny = 1
  z = 0.0, 0.1
  nz = 1
/
&material
  name = 'gas', eos = 'ideal_gas', gamma = 1.4
/
&block
  name = 'tube', material = 'gas'
/
&region
  density = 1.0, pressure = 1.0, box = 0.0, 0.5, -1, 1, -1, 1
/
&region
  density = 0.125, pressure = 0.1, box = 0.5, 1.0, -1, 1, -1, 1
/
&boundary set = 'xmin', type = 'symmetry' /
&boundary set = 'xmax', type = 'symmetry' /
&boundary set = 'ymin', type = 'symmetry' /
&boundary set = 'ymax', type = 'symmetry' /
&boundary set = 'zmin', type = 'symmetry' /
&boundary set = 'zmax', type = 'symmetry' /
&output
  directory = '{dir}'
  status_every = 100
/
"""

SUMMARY = re.compile(r"^impact3d: (\d+) input error\(s\); nothing was run$", re.M)


class DeckEditError(Exception):
    """A case's edit did not apply to the base deck (a bug in this script)."""


def sub(old, new, count=1):
    """Edit: replace the first `count` occurrences of `old`; `old` must be there."""

    def edit(text):
        if text.count(old) < count:
            raise DeckEditError("%r occurs %d time(s), need %d" % (old, text.count(old), count))
        return text.replace(old, new, count)

    return edit


def chain(*edits):
    def edit(text):
        for e in edits:
            text = e(text)
        return text

    return edit


def remove_group(header):
    """Edit: delete the whole group that starts with the line `header`."""

    def edit(text):
        start = text.find(header + "\n")
        if start < 0:
            raise DeckEditError("group %r not found" % header)
        end = text.find("\n/\n", start)
        return text[:start] + text[end + 3:]

    return edit


def append(extra):
    return lambda text: text + extra


class Case:
    def __init__(self, name, edit, expect, min_errors=1, deck_arg=None, expect_code=1,
                 absent=(), max_errors=None):
        self.name = name
        self.absent = absent  # fragments that must not appear in stderr
        self.max_errors = max_errors
        self.edit = edit  # base text -> bad text
        self.expect = expect  # fragments that must all appear in stderr
        self.min_errors = min_errors
        self.deck_arg = deck_arg  # callable(case_dir, deck_path) -> program argument
        self.expect_code = expect_code


def build_cases():
    c = []
    # --- groups and keys -------------------------------------------------
    c.append(Case("unknown_group", sub("&control\n", "&contorl\n"),
                  ["&contorl: unknown group on deck line 2; did you mean '&control'?",
                   "valid groups: control", "&control: required group is missing"],
                  min_errors=2))
    c.append(Case("every_problem_at_once",
                  chain(sub("  t_end = 0.05\n", "  tend = 0.05\n"),
                        sub("  cfl = 0.5\n", "  cfl = 1.3\n")),
                  ["&control: tend: unknown key", "valid keys: title, t_end",
                   "&control: t_end: required",
                   "&control: cfl: must be in (0, 1]"], min_errors=3))
    c.append(Case("repeated_key",
                  sub("  t_end = 0.05\n", "  t_end = 0.05, t_end = 2.0\n"),
                  ["&control: t_end: given twice in one group (deck lines 4 and 4)"]))
    c.append(Case("material_unknown_strength",
                  sub("name = 'gas', eos", "name = 'gas', strength = 'rigid', eos"),
                  ["&material(1): strength: 'rigid' is not a strength model",
                   "valid: none, elastic_plastic, steinberg_guinan"]))
    c.append(Case("material_unknown_library",
                  sub("name = 'gas', eos = 'ideal_gas', gamma = 1.4",
                      "name = 'gas', eos = 'mie_gruneisen', library = 'unobtainium'"),
                  ["&material(1): library: 'unobtainium' is not a built-in material"]))
    c.append(Case("contact_bad_method_and_set",
                  append("&contact surface_a = 'xmax', surface_b = 'xlow', method = 'glue' /\n"),
                  ["&contact(1): method: 'glue' is not a contact method (valid: dam, dlm)"]))
    c.append(Case("contact_unknown_surface",
                  append("&contact surface_a = 'xmax', surface_b = 'xlow', method = 'dlm' /\n"),
                  ["&contact(1): surface_b: 'xlow' is not a face set of the mesh "
                   "(valid: xmin, xmax, ymin, ymax, zmin, zmax; did you mean 'xmin'?)"]))
    c.append(Case("contact_form_unknown",
                  append("&contact surface_a = 'xmax', surface_b = 'xmin', method = 'dlm', "
                         "form = 'penalty' /\n"),
                  ["&contact(1): form: 'penalty' is not a DLM form"]))
    c.append(Case("contact_form_for_dam",
                  append("&contact surface_a = 'xmax', surface_b = 'xmin', method = 'dam', "
                         "form = 'velocity' /\n"),
                  ["&contact(1): form: only DLM has forms"]))
    c.append(Case("contact_recovery_range",
                  append("&contact surface_a = 'xmax', surface_b = 'xmin', method = 'dlm', "
                         "recovery = 0.8 /\n"),
                  ["&contact(1): recovery: must be in [0, 0.5]"]))
    c.append(Case("contact_penetration_warning_replaced",
                  append("&contact surface_a = 'xmax', surface_b = 'xmin', method = 'dlm', "
                         "penetration_warning = 0.01 /\n"),
                  ["&contact(1): penetration_warning: replaced by penetration_tolerance"]))
    c.append(Case("contact_penetration_tolerance_negative",
                  append("&contact surface_a = 'xmax', surface_b = 'xmin', method = 'dam', "
                         "penetration_tolerance = -1.0 /\n"),
                  ["&contact(1): penetration_tolerance: must be >= 0"]))
    c.append(Case("contact_on_penetration_unknown",
                  append("&contact surface_a = 'xmax', surface_b = 'xmin', method = 'dam', "
                         "on_penetration = 'abort' /\n"),
                  ["&contact(1): on_penetration: 'abort' is not a choice (valid: warn, stop)"]))
    c.append(Case("contact_initial_penetration_unknown",
                  append("&contact surface_a = 'xmax', surface_b = 'xmin', method = 'dlm', "
                         "initial_penetration = 'push' /\n"),
                  ["&contact(1): initial_penetration: 'push' is not a choice "
                   "(valid: error, adjust, ignore)"]))
    c.append(Case("contact_block_unknown",
                  append("&contact surface_a = 'block:tube', surface_b = 'block:nope', "
                         "method = 'dlm' /\n"),
                  ["'block:nope': no block 'nope'"]))
    c.append(Case("contact_blocks_and_sets",
                  append("&contact surface_a = 'block:tube, xmax', method = 'dlm' /\n"),
                  ["'xmax': a surface is either face sets or blocks (block:NAME), not both"]))
    c.append(Case("mesh_rotation_without_axis",
                  lambda t: t.replace("  nz = 1\n/", "  nz = 1\n  rotation_angle = 30.0\n/", 1),
                  ["&mesh: rotation_axis: required with rotation_angle"]))
    c.append(Case("contact_recovery_for_combined",
                  append("&contact surface_a = 'xmax', surface_b = 'xmin', method = 'dlm', "
                         "form = 'combined', recovery = 0.1 /\n"),
                  ["&contact(1): recovery: only for the DLM velocity form"]))
    c.append(Case("contact_normal_for_dlm",
                  append("&contact surface_a = 'xmax', surface_b = 'xmin', method = 'dlm', "
                         "normal = 'slave' /\n"),
                  ["&contact(1): normal: only for DAM"]))
    c.append(Case("contact_normal_unknown",
                  append("&contact surface_a = 'xmax', surface_b = 'xmin', method = 'dam', "
                         "normal = 'average' /\n"),
                  ["&contact(1): normal: 'average' is not a DAM normal"]))
    c.append(Case("mesh_parts_need_names",
                  append("&mesh x = 2.0, 3.0, nx = 2, y = 0.0, 1.0, ny = 1, z = 0.0, 1.0, "
                         "nz = 1 /\n"),
                  ["&mesh(1): name: required when the deck has several &mesh parts",
                   "&mesh(2): name: required"]))
    c.append(Case("mesh_part_unknown_block",
                  sub("&mesh", "&mesh block = 'plate',"),
                  ["&mesh: block: 'plate' is not the name of a &block (valid: tube; "
                   "did you mean 'tube'?)"]))
    c.append(Case("unknown_key_other_group",
                  sub("name = 'gas', eos", "name = 'gas', gama = 1.4, eos"),
                  ["&material: gama: unknown key on deck line 17; did you mean 'gamma'?",
                   "valid keys: name, eos, gamma"]))
    c.append(Case("unknown_key_line_and_guess",
                  sub("  cfl = 0.5\n", "  cfl = 0.5\n  max_cycle = 10\n"),
                  ["&control: max_cycle: unknown key on deck line 6; "
                   "did you mean 'max_cycles'?"], max_errors=1))
    c.append(Case("unknown_key_no_guess",
                  sub("  cfl = 0.5\n", "  cfl = 0.5\n  colour = 'red'\n"),
                  ["&control: colour: unknown key on deck line 6 (valid keys: title"],
                  absent=["did you mean"], max_errors=1))
    # Values of the wrong type: group, key and deck line, and nothing about the
    # key being missing (it was given, wrongly), no raw run-time library text.
    c.append(Case("syntax_error_in_value", sub("  nx = 10\n", "  nx = 1o\n"),
                  ["&mesh: nx: deck line 10: '1o' is not an integer"],
                  absent=["nx: required", "cannot read the group"], max_errors=1))
    c.append(Case("syntax_error_in_real",
                  sub("gamma = 1.4", "gamma = 1.4.2"),
                  ["&material(1): gamma: deck line 17: '1.4.2' is not a real number"],
                  absent=["gamma: required", "cannot read the group"], max_errors=1))
    c.append(Case("string_for_real", sub("  t_end = 0.05\n", "  t_end = 'abc'\n"),
                  ["&control: t_end: deck line 4: 'abc' is not a real number"],
                  absent=["t_end: required", "Cannot match namelist"], max_errors=1))
    c.append(Case("string_for_integer",
                  sub("  status_every = 100\n", "  status_every = 'often'\n"),
                  ["&output: status_every: deck line 36: 'often' is not an integer"],
                  max_errors=1))
    c.append(Case("real_for_integer", sub("  nz = 1\n", "  nz = 1.5\n"),
                  ["&mesh: nz: deck line 14: '1.5' is not an integer"], max_errors=1))
    c.append(Case("string_without_quotes", sub("eos = 'ideal_gas'", "eos = ideal_gas"),
                  ["&material(1): eos: deck line 17: 'ideal_gas' is not a character string "
                   "(put it in quotes)"], absent=["eos: required", "Cannot match"],
                  max_errors=1))
    c.append(Case("number_for_logical", append("&hydro q_limiter = 2 /\n"),
                  ["&hydro: q_limiter: deck line 38: '2' is not a logical"], max_errors=1))
    c.append(Case("bad_item_in_array",
                  sub("density = 1.0, pressure = 1.0, box = 0.0, 0.5, -1, 1, -1, 1",
                      "density = 1.0, pressure = 1.0, box = 0.0, 0.5, -1, one, -1, 1"),
                  ["&region(1): box: deck line 23: 'one' is not a real number"],
                  max_errors=1))
    # Every real finite: overflow to infinity, Inf and NaN, in any group and
    # any item of an array.
    c.append(Case("real_overflow", sub("  t_end = 0.05\n", "  t_end = 1.0e400\n"),
                  ["&control: t_end: deck line 4: '1.0e400' is not a finite number"],
                  absent=["t_end: required"], max_errors=1))
    c.append(Case("real_inf", sub("  cfl = 0.5\n", "  cfl = Inf\n"),
                  ["&control: cfl: deck line 5: 'Inf' is not a finite number"],
                  absent=["cfl: must be"], max_errors=1))
    c.append(Case("real_nan", sub("gamma = 1.4", "gamma = NaN"),
                  ["&material(1): gamma: deck line 17: 'NaN' is not a finite number"],
                  absent=["gamma: required", "gamma: must be"], max_errors=1))
    c.append(Case("real_minus_infinity_in_array", sub("  x = 0.0, 1.0\n",
                                                      "  x = -Infinity, 1.0\n"),
                  ["&mesh: x: deck line 9: '-Infinity' is not a finite number"],
                  max_errors=1))
    c.append(Case("real_overflow_in_region",
                  sub("  density = 0.125,", "  velocity = 0.0, 0.125d999, 0.0, density = 0.125,"),
                  ["&region(2): velocity: deck line 26: '0.125d999' is not a finite number"],
                  max_errors=1))
    c.append(Case("missing_mesh_group", remove_group("&mesh"),
                  ["&mesh: required group is missing"]))
    c.append(Case("missing_material_group", remove_group("&material"),
                  ["&material: at least one is required"]))
    c.append(Case("duplicate_control",
                  append("&control\n  t_end = 1.0\n/\n"),
                  ["&control: group given more than once"]))
    c.append(Case("group_never_closed",
                  sub("  status_every = 100\n/\n", "  status_every = 100\n"),
                  ["&output: group opened on line", "never closed with '/'"]))
    # A group left open before the next one: the next '&' must not be taken as
    # part of the open group (it would swallow &block and misreport its keys).
    c.append(Case("group_never_closed_middle",
                  sub("gamma = 1.4\n/\n", "gamma = 1.4\n"),
                  ["&material: group opened on line", "never closed with '/'"]))
    c.append(Case("text_outside_group",
                  sub("&mesh\n", "t_end = 1.0\n&mesh\n"),
                  ["text outside any group", "t_end = 1.0"]))
    # --- &control ----------------------------------------------------------
    c.append(Case("control_t_end_missing", sub("  t_end = 0.05\n", ""),
                  ["&control: t_end: required"]))
    c.append(Case("control_t_end_negative", sub("  t_end = 0.05\n", "  t_end = -1.0\n"),
                  ["&control: t_end: must be > 0"]))
    c.append(Case("control_dt_min_ge_dt_max",
                  sub("  cfl = 0.5\n", "  cfl = 0.5\n  dt_min = 1.0e-3\n  dt_max = 1.0e-4\n"),
                  ["&control: dt_min: must be smaller than dt_max"]))
    c.append(Case("control_restart_missing_file",
                  sub("  cfl = 0.5\n", "  cfl = 0.5\n  restart = '{dir}/no_such_dump.h5'\n"),
                  ["&control: restart: file", "no_such_dump.h5' does not exist"]))
    c.append(Case("control_deck_version", sub("  cfl = 0.5\n", "  cfl = 0.5\n  deck_version = 2\n"),
                  ["&control: deck_version: this code reads deck version 1"]))
    # --- &hydro --------------------------------------------------------------
    c.append(Case("hydro_unknown_hourglass", append("&hydro hourglass = 'magic' /\n"),
                  ["&hydro: hourglass: 'magic' is not a hourglass control"]))
    c.append(Case("hydro_single_stage_wall",
                  append("&hydro scheme = 'single' /\n&boundary set = 'xmax', type = 'wall', "
                         "wall_point = 1.0, 0.0, 0.0, wall_normal = -1.0, 0.0, 0.0 /\n"),
                  ["&hydro: scheme: 'single' is for gas dynamics: not with a 'wall' &boundary"]))
    c.append(Case("hydro_negative_heat_flux",
                  append("&hydro heat_flux_quadratic = -1.0, heat_flux_linear = -0.5 /\n"),
                  ["&hydro: heat_flux_linear: must be >= 0",
                   "&hydro: heat_flux_quadratic: must be >= 0"], min_errors=2))
    # --- &mesh ---------------------------------------------------------------
    box_group = ("  type = 'box'\n  x = 0.0, 1.0\n  nx = 10\n  y = 0.0, 0.1\n  ny = 1\n"
                 "  z = 0.0, 0.1\n  nz = 1\n")
    c.append(Case("mesh_box_minus_ball_bad",
                  sub(box_group, "  type = 'box_minus_ball', radius = 0.5, length = 0.4,\n"
                      "  n_patch = 0, radial_ratio = -1.0\n"),
                  ["&mesh: length: must be > radius", "&mesh: n_patch: must be >= 1",
                   "&mesh: radial_ratio: must be > 0"], min_errors=3))
    c.append(Case("mesh_ball_bad",
                  sub(box_group, "  type = 'ball', radius = 0.5, core_fraction = 0.7,\n"
                      "  n_radial = 0, n_patch = 4\n"),
                  ["&mesh: core_fraction: must be in [0.2, 0.5]",
                   "&mesh: n_radial: must be >= 1", "&mesh: type: 'ball' takes radius"],
                  min_errors=3))
    c.append(Case("mesh_nx_missing", sub("  nx = 10\n", ""),
                  ["&mesh: nx: required"]))
    c.append(Case("mesh_points_not_increasing", sub("  x = 0.0, 1.0\n", "  x = 1.0, 0.0\n"),
                  ["&mesh: x: points must increase"]))
    c.append(Case("mesh_wrong_number_of_points",
                  sub("  y = 0.0, 0.1\n", "  y = 0.0, 0.05, 0.1\n"),
                  ["&mesh: y: needs one more point than ny"]))
    c.append(Case("mesh_ratio_not_positive", sub("  nx = 10\n", "  nx = 10\n  ratio_x = -2.0\n"),
                  ["&mesh: ratio_x: must be > 0"]))
    c.append(Case("mesh_zero_zones", sub("  nz = 1\n", "  nz = 0, 3\n"),
                  ["&mesh: nz: every interval needs >= 1 zone"]))
    c.append(Case("mesh_unknown_type", sub("  type = 'box'\n", "  type = 'cylinder'\n"),
                  ["&mesh: type: 'cylinder' is not a mesh type", "valid: box"]))
    # --- &material -------------------------------------------------------------
    c.append(Case("material_name_missing", sub("name = 'gas', eos", "eos"),
                  ["&material(1): name: required"]))
    c.append(Case("material_duplicate_name",
                  sub("&block\n", "&material\n  name = 'gas', eos = 'ideal_gas', gamma = 1.67\n/\n"
                      "&block\n"),
                  ["&material", "name: 'gas' is given twice"]))
    c.append(Case("material_unknown_eos", sub("eos = 'ideal_gas'", "eos = 'stiffened_gas'"),
                  ["&material(1): eos: 'stiffened_gas' is not an equation of state",
                   "valid: ideal_gas"]))
    c.append(Case("material_eos_missing", sub("eos = 'ideal_gas', ", ""),
                  ["&material(1): eos: required"]))
    c.append(Case("material_gamma_not_above_one", sub("gamma = 1.4", "gamma = 1.0"),
                  ["&material(1): gamma: must be > 1"]))
    c.append(Case("material_gamma_missing", sub(", gamma = 1.4", ""),
                  ["&material(1): gamma: required for eos = 'ideal_gas'"]))
    # --- &material: strength parameters (issue 17 item 1) -------------------------
    gas = "name = 'gas', eos = 'ideal_gas', gamma = 1.4"
    mg = "name = 'gas', eos = 'mie_gruneisen', rho0 = 1.0, c0 = 1.0, s1 = 1.0, gamma0 = 0.4"
    ep = mg + ", strength = 'elastic_plastic', shear_modulus = 0.3, yield_stress = 0.003"
    jc = (mg + ", strength = 'johnson_cook', shear_modulus = 0.3, jc_a = 9e-4, jc_b = 3e-3, "
          "jc_n = 0.3, jc_c = 0.025, jc_m = 1.1, t_melt = 1356.0, cv = 0.4e-5")
    sg = (mg + ", strength = 'steinberg_guinan', shear_modulus = 0.477, yield_stress = 0.0012, "
          "sg_ymax = 0.0064, sg_beta = 36.0, sg_n = 0.45, sg_a = 2.83, sg_b = 3.77e-4, "
          "sg_tmelt0 = 1790.0, sg_a_melt = 1.5, cv = 0.385e-5")

    def mat(text):
        return sub(gas, text)

    c.append(Case("material_hardening_negative", mat(ep + ", hardening_modulus = -0.1"),
                  ["&material(1): hardening_modulus: must be >= 0 (Mbar) for strength = "
                   "'elastic_plastic'"]))
    c.append(Case("material_hardening_without_strength",
                  mat(mg + ", hardening_modulus = 0.1"),
                  ["&material(1): hardening_modulus: only for strength = 'elastic_plastic', "
                   "not 'none'"]))
    c.append(Case("material_elastic_plastic_no_library",
                  mat(mg + ", strength = 'elastic_plastic'"),
                  ["&material(1): shear_modulus: required (> 0) for strength = "
                   "'elastic_plastic'",
                   "&material(1): yield_stress: required (> 0) for strength = "
                   "'elastic_plastic'"], min_errors=2))
    c.append(Case("material_other_model_keys",
                  mat(ep + ", jc_a = 9e-4, sg_beta = 36.0, cv = 0.4e-5, sg_cold_energy = .true."),
                  ["&material(1): jc_a: only for strength = 'johnson_cook', not "
                   "'elastic_plastic'",
                   "&material(1): sg_beta: only for strength = 'steinberg_guinan', not "
                   "'elastic_plastic'",
                   "&material(1): cv: only for strength = 'steinberg_guinan' or "
                   "'johnson_cook'",
                   "&material(1): sg_cold_energy: only for strength = 'steinberg_guinan', "
                   "not 'elastic_plastic'"], min_errors=4))
    c.append(Case("material_jc_no_library",
                  mat(mg + ", strength = 'johnson_cook', shear_modulus = 0.3"),
                  ["&material(1): %s: required for strength = 'johnson_cook' (or a library "
                   "with Johnson-Cook data: al6061, cu_ofhc, wha, steel_1006, steel_4340)" % k
                   for k in ["jc_a", "jc_b", "jc_n", "jc_c", "jc_m", "t_melt", "cv"]],
                  min_errors=7))
    c.append(Case("material_jc_shear_missing",
                  mat(jc.replace(", shear_modulus = 0.3", "")),
                  ["&material(1): shear_modulus: required for strength = 'johnson_cook'"]))
    c.append(Case("material_jc_bad_values",
                  mat(jc.replace("jc_a = 9e-4, jc_b = 3e-3, jc_n = 0.3, jc_c = 0.025, "
                                 "jc_m = 1.1",
                                 "jc_a = 0.0, jc_b = -3e-3, jc_n = -0.3, jc_c = -0.025, "
                                 "jc_m = 0.0, eps_dot0 = 0.0, t_room = -5.0")
                      .replace("cv = 0.4e-5", "cv = 0.0")
                      .replace("shear_modulus = 0.3", "shear_modulus = -0.3")),
                  ["&material(1): shear_modulus: must be > 0 (Mbar) for strength = "
                   "'johnson_cook'",
                   "&material(1): jc_a: must be > 0 (Mbar) for strength = 'johnson_cook'",
                   "&material(1): jc_b: must be >= 0 (Mbar)",
                   "&material(1): jc_n: must be >= 0",
                   "&material(1): jc_c: must be >= 0",
                   "&material(1): jc_m: must be > 0",
                   "&material(1): eps_dot0: must be > 0 (1/us)",
                   "&material(1): t_room: must be > 0 (K)",
                   "&material(1): cv: must be > 0 (Mbar cm^3/(g K)) for strength = "
                   "'johnson_cook'"], min_errors=9))
    c.append(Case("material_jc_melt_below_room",
                  mat(jc.replace("t_melt = 1356.0", "t_melt = 1356.0, t_room = 1400.0")),
                  ["&material(1): t_melt: must be > t_room (K) for strength = 'johnson_cook'"]))
    c.append(Case("material_jc_other_model_keys",
                  mat(jc + ", yield_stress = 0.003, sg_n = 0.45, hardening_modulus = 0.1"),
                  ["&material(1): yield_stress: only for strength = 'elastic_plastic' or "
                   "'steinberg_guinan' (the initial yield of 'johnson_cook' is jc_a)",
                   "&material(1): sg_n: only for strength = 'steinberg_guinan', not "
                   "'johnson_cook'",
                   "&material(1): hardening_modulus: only for strength = 'elastic_plastic', "
                   "not 'johnson_cook'"], min_errors=3))
    c.append(Case("material_sg_no_library",
                  mat(mg + ", strength = 'steinberg_guinan'"),
                  ["&material(1): %s: required for strength = 'steinberg_guinan' (or a "
                   "library with Steinberg-Guinan data: al6061, cu_ofhc, cu_taylor, ss304)" % k
                   for k in ["shear_modulus", "yield_stress", "sg_ymax", "sg_beta", "sg_n",
                             "sg_a", "sg_b", "sg_tmelt0", "sg_a_melt", "cv"]],
                  min_errors=10))
    c.append(Case("material_sg_library_without_sg_data",
                  mat("name = 'gas', eos = 'mie_gruneisen', library = 'be_verney', "
                      "strength = 'steinberg_guinan'"),
                  ["&material(1): sg_beta: required for strength = 'steinberg_guinan' (or a "
                   "library with Steinberg-Guinan data"], min_errors=8))
    c.append(Case("material_sg_bad_values",
                  mat(sg.replace("shear_modulus = 0.477, yield_stress = 0.0012",
                                 "shear_modulus = 0.0, yield_stress = -0.0012")
                      .replace("sg_beta = 36.0, sg_n = 0.45, sg_a = 2.83, sg_b = 3.77e-4",
                               "sg_beta = -36.0, sg_n = -0.45, sg_a = -2.83, sg_b = -3.77e-4, "
                               "sg_eps_i = -0.1, sg_gamma0 = 0.0")
                      .replace("sg_tmelt0 = 1790.0, sg_a_melt = 1.5, cv = 0.385e-5",
                               "sg_tmelt0 = 250.0, sg_a_melt = -1.5, cv = -0.385e-5")),
                  ["&material(1): shear_modulus: must be > 0 (G0, Mbar) for strength = "
                   "'steinberg_guinan'",
                   "&material(1): yield_stress: must be > 0 (Y0, Mbar)",
                   "&material(1): sg_beta: must be >= 0",
                   "&material(1): sg_n: must be >= 0",
                   "&material(1): sg_a: must be >= 0 (1/Mbar)",
                   "&material(1): sg_b: must be >= 0 (1/K)",
                   "&material(1): sg_eps_i: must be >= 0",
                   "&material(1): sg_gamma0: must be > 0",
                   "&material(1): sg_tmelt0: must be > 300 K",
                   "&material(1): sg_a_melt: must be >= 0",
                   "&material(1): cv: must be > 0 (Mbar cm^3/(g K)) for strength = "
                   "'steinberg_guinan'"], min_errors=11))
    c.append(Case("material_sg_ymax_below_y0",
                  mat(sg.replace("sg_ymax = 0.0064", "sg_ymax = 0.001")),
                  ["&material(1): sg_ymax: must be >= yield_stress (Ymax >= Y0, Mbar)"]))
    c.append(Case("material_sg_ideal_gas",
                  mat(gas + ", strength = 'steinberg_guinan', shear_modulus = 0.477"),
                  ["&material(1): strength: 'steinberg_guinan' needs eos = 'mie_gruneisen'"]))
    c.append(Case("material_sg_other_model_keys",
                  mat(sg + ", jc_m = 1.1, t_melt = 1356.0, hardening_modulus = 0.1"),
                  ["&material(1): jc_m: only for strength = 'johnson_cook', not "
                   "'steinberg_guinan'",
                   "&material(1): t_melt: only for strength = 'johnson_cook'",
                   "&material(1): hardening_modulus: only for strength = 'elastic_plastic', "
                   "not 'steinberg_guinan'"], min_errors=3))
    c.append(Case("material_cv_without_strength", mat(mg + ", cv = 0.4e-5"),
                  ["&material(1): cv: only for strength = 'steinberg_guinan' or "
                   "'johnson_cook' (the models with a temperature), not 'none'"]))
    # A region density far from its material's rho0 (mixed units) is a warning, not an
    # error: the run goes ahead. Region 1 (density = rho0) is not warned about.
    c.append(Case("region_density_far_from_rho0_warns", mat(mg),
                  ["warning: &region(2): density: 1.2500E-01 differs by more than 20% from "
                   "the rho0 of material 'gas' (rho0 = 1.0000E+00)"],
                  expect_code=0, absent=["warning: &region(1)"]))
    # --- &block ----------------------------------------------------------------
    c.append(Case("block_unknown_material", sub("material = 'gas'", "material = 'air'"),
                  ["&block(1): material: 'air' is not a material of this deck (valid: gas; "
                   "did you mean 'gas'?)"]))
    c.append(Case("block_box_min_gt_max",
                  sub("name = 'tube', material = 'gas'",
                      "name = 'tube', material = 'gas', box = 1.0, 0.0, -1, 1, -1, 1"),
                  ["&block(1): box: needs xmin <= xmax"]))
    c.append(Case("block_zones_in_no_block",
                  sub("name = 'tube', material = 'gas'",
                      "name = 'tube', material = 'gas', box = 0.0, 0.5, -1, 1, -1, 1"),
                  ["&block: box: 5 zones lie in no block's box"]))
    # --- &region ---------------------------------------------------------------
    c.append(Case("region_unknown_block",
                  sub("  density = 1.0, pressure = 1.0,",
                      "  block = 'pipe', density = 1.0, pressure = 1.0,"),
                  ["&region(1): block: 'pipe' is not a block of this deck (valid: tube; "
                   "did you mean 'tube'?)"]))
    c.append(Case("region_energy_and_pressure",
                  sub("  density = 0.125, pressure = 0.1,",
                      "  density = 0.125, energy = 2.0, pressure = 0.1,"),
                  ["&region(2): pressure: give energy or pressure, not both"]))
    c.append(Case("region_negative_density",
                  sub("  density = 0.125,", "  density = -0.125,"),
                  ["&region(2): density: must be > 0"]))
    c.append(Case("region_no_density",
                  sub("  density = 0.125, pressure = 0.1,", "  energy = 2.0,"),
                  ["&region: density: 5 zones of block 'tube' get no density from any region, "
                   "and their material 'gas' has no reference density (ideal gas)"],
                  max_errors=1))
    c.append(Case("region_pressure_without_density",
                  sub("  density = 0.125, pressure = 0.1,", "  pressure = 0.1,"),
                  ["&region(2): pressure: needs density in the same region"]))
    # --- &boundary -------------------------------------------------------------
    c.append(Case("boundary_unknown_set", sub("set = 'xmax'", "set = 'xhigh'"),
                  ["&boundary(2): set: 'xhigh' is not a face set",
                   "(valid: xmin, xmax, ymin, ymax, zmin, zmax; did you mean 'xmin'?)"]))
    c.append(Case("boundary_unknown_type",
                  sub("set = 'xmax', type = 'symmetry'", "set = 'xmax', type = 'rigid'"),
                  ["&boundary(2): type: 'rigid' is not a boundary condition",
                   "valid: free, symmetry, wall, velocity, pressure"]))
    c.append(Case("boundary_velocity_without_velocity",
                  sub("set = 'xmin', type = 'symmetry'", "set = 'xmin', type = 'velocity'"),
                  ["&boundary(1): velocity: required (3 components) for type = 'velocity'"]))
    c.append(Case("boundary_pressure_on_symmetry",
                  sub("set = 'xmax', type = 'symmetry'",
                      "set = 'xmax', type = 'symmetry', pressure = 1.0"),
                  ["&boundary(2): pressure: only for type = 'pressure'"]))
    c.append(Case("boundary_set_missing",
                  sub("set = 'zmax', type = 'symmetry'", "type = 'symmetry'"),
                  ["&boundary(6): set: required"]))
    # Coulomb friction (issue 17 item 2): a coefficient >= 0, finite, and only
    # on a rigid wall.
    c.append(Case("boundary_friction_negative",
                  sub("set = 'xmax', type = 'symmetry'",
                      "set = 'xmax', type = 'wall', friction = -0.1"),
                  ["&boundary(2): friction: must be >= 0"]))
    c.append(Case("boundary_friction_nan",
                  sub("set = 'xmax', type = 'symmetry'",
                      "set = 'xmax', type = 'wall', friction = NaN"),
                  ["&boundary(2): friction: deck line", "'NaN' is not a finite number"],
                  absent=["must be >= 0"]))
    c.append(Case("boundary_friction_not_wall",
                  sub("set = 'xmax', type = 'symmetry'",
                      "set = 'xmax', type = 'symmetry', friction = 0.2"),
                  ["&boundary(2): friction: only for type = 'wall'"]))
    # DAM's second pass (symmetric): DLM is symmetric already.
    c.append(Case("contact_symmetric_dlm",
                  append("&contact surface_a = 'xmax', surface_b = 'xmin', method = 'dlm', "
                         "symmetric = .true. /\n"),
                  ["&contact(1): symmetric: only for DAM"]))
    c.append(Case("contact_friction_negative",
                  append("&contact surface_a = 'xmax', surface_b = 'xmin', method = 'dam', "
                         "friction = -0.5 /\n"),
                  ["&contact(1): friction: must be >= 0"]))
    c.append(Case("contact_friction_infinite",
                  append("&contact surface_a = 'xmax', surface_b = 'xmin', method = 'dlm', "
                         "friction = Inf /\n"),
                  ["&contact(1): friction: deck line", "'Inf' is not a finite number"],
                  absent=["must be >= 0"]))
    # A wall given by a plane: both keys or neither, a nonzero normal, and the
    # set on the body side of the plane at t = 0.
    c.append(Case("boundary_wall_point_without_normal",
                  sub("set = 'xmax', type = 'symmetry'",
                      "set = 'xmax', type = 'wall', wall_point = 2.0, 0.0, 0.0"),
                  ["&boundary(2): wall_normal: required with wall_point"]))
    c.append(Case("boundary_wall_normal_zero",
                  sub("set = 'xmax', type = 'symmetry'",
                      "set = 'xmax', type = 'wall', wall_point = 2.0, 0.0, 0.0, "
                      "wall_normal = 0.0, 0.0, 0.0"),
                  ["&boundary(2): wall_normal: must not be the zero vector"]))
    c.append(Case("boundary_wall_set_beyond_plane",
                  sub("set = 'xmax', type = 'symmetry'",
                      "set = 'xmax', type = 'wall', wall_point = 0.5, 0.0, 0.0, "
                      "wall_normal = -1.0, 0.0, 0.0"),
                  ["&boundary(2): wall_point: 4 node(s) of set 'xmax' start beyond the wall "
                   "plane"]))
    c.append(Case("boundary_wall_normal_on_symmetry",
                  sub("set = 'xmax', type = 'symmetry'",
                      "set = 'xmax', type = 'symmetry', wall_normal = -1.0, 0.0, 0.0"),
                  ["&boundary(2): wall_normal: only for type = 'wall'"]))
    # --- &output ---------------------------------------------------------------
    # A missing output directory is made (with its parents); one that cannot
    # be made (a file is in the way) is an input error.
    c.append(Case("output_directory_created",
                  sub("  directory = '{dir}'\n", "  directory = '{dir}/new/sub dir'\n"),
                  [], expect_code=0))
    c.append(Case("output_directory_cannot_be_made",
                  sub("  directory = '{dir}'\n", "  directory = '{dir}/deck.nml/out'\n"),
                  ["&output: directory:", "deck.nml/out' does not exist and cannot be created"]))
    c.append(Case("output_prefix_with_slash",
                  sub("  status_every = 100\n", "  status_every = 100\n  prefix = 'run/a'\n"),
                  ["&output: prefix: must be a non-empty file name without '/'"]))
    c.append(Case("output_status_every_zero",
                  sub("  status_every = 100\n", "  status_every = 0\n"),
                  ["&output: status_every: must be >= 1"]))
    # --- &probe and &control units (issue 20 items 2 and 4) -------------------------
    c.append(Case("probe_unknown_field",
                  append("&probe name = 'p', node = 1, fields = 'velocity, temperature' /\n"),
                  ["&probe 'p': fields: 'temperature' is not a probe field (valid: velocity"]))
    c.append(Case("probe_node_out_of_range",
                  append("&probe name = 'p', node = 45, fields = 'velocity' /\n"),
                  ["&probe 'p': node: 45 is out of range (the mesh has nodes 1 to 44)"]))
    c.append(Case("probe_point_outside",
                  append("&probe name = 'p', point = 2.0, 0.05, 0.05, fields = 'pressure' /\n"),
                  ["&probe 'p': point: (", "is outside the mesh"]))
    c.append(Case("probe_node_and_point",
                  append("&probe name = 'p', node = 1, point = 0.5, 0.05, 0.05, "
                         "fields = 'pressure' /\n"),
                  ["&probe 'p': node: give either node or point, not both"]))
    c.append(Case("probe_every_and_interval",
                  append("&probe name = 'p', node = 1, fields = 'pressure', every = 2, "
                         "interval = 0.01 /\n"),
                  ["&probe 'p': every: give either every (cycles) or interval (time), not both"]))
    c.append(Case("probe_stress_without_strength",
                  append("&probe name = 'p', node = 1, fields = 'stress' /\n"),
                  ["&probe 'p': fields: stress and plastic_strain need a &material with "
                   "strength"]))
    c.append(Case("probe_name_twice",
                  append("&probe name = 'p', node = 1, fields = 'velocity' /\n"
                         "&probe name = 'p', node = 2, fields = 'velocity' /\n"),
                  ["&probe 'p': name: given to two probes"]))
    c.append(Case("control_units_unknown",
                  sub("  cfl = 0.5\n", "  cfl = 0.5\n  units = 'furlongs'\n"),
                  ["&control: units: 'furlongs' is not a unit system (valid: cm-g-us-mbar, si, "
                   "none)"]))
    c.append(Case("units_none_refuses_library",
                  chain(sub("  cfl = 0.5\n", "  cfl = 0.5\n  units = 'none'\n"),
                        sub("name = 'gas', eos = 'ideal_gas', gamma = 1.4",
                            "name = 'gas', eos = 'mie_gruneisen', library = 'al6061'")),
                  ["&material(1): library: 'al6061' has data in cm-g-us-mbar; with &control "
                   "units = 'none' give every property yourself"]))
    # --- the program argument ------------------------------------------------------
    c.append(Case("deck_file_missing", lambda t: t,
                  ["deck: file", "no_such_deck.nml", "does not exist"],
                  deck_arg=lambda d, p: os.path.join(d, "no_such_deck.nml")))
    # --- sanity: the base deck itself runs -------------------------------------------
    # --- unit mistakes and names (issue 34) -------------------------------------
    al = "name = 'gas', eos = 'mie_gruneisen', library = 'al6061'"
    al_regions = chain(sub(gas, al), sub("  density = 1.0, pressure = 1.0,",
                                         "  density = 2.703, pressure = 1.0e-6,"),
                       sub("  density = 0.125, pressure = 0.1,",
                           "  density = 2.703, pressure = 1.0e-6,"))
    c.append(Case("al_regions_valid", al_regions, [], expect_code=0))
    c.append(Case("units_density_si",
                  chain(al_regions, sub("  density = 2.703, pressure = 1.0e-6,",
                                        "  density = 2703.0, pressure = 1.0e-6,")),
                  ["&region(1): density: 2.7030E+03 is 1000 times the rho0 of material "
                   "'gas' (rho0 = 2.7030E+00), more than 10 times from it: expected about the "
                   "rho0; a density in kg/m^3 (SI) in a cm-g-us-mbar deck?"], max_errors=1))
    c.append(Case("units_rho0_si", chain(al_regions, sub(al, al + ", rho0 = 2703.0")),
                  ["&material(1): rho0: 2703.0 is 1000 times the rho0 2.7030 of library "
                   "'al6061' (in cm-g-us-mbar), more than 10 times from it: expected about "
                   "2.7030; a density in kg/m^3 (SI) in a cm-g-us-mbar deck?"], max_errors=1))
    c.append(Case("units_density_within_10x_warns",
                  chain(al_regions, sub("  density = 2.703, pressure = 1.0e-6,",
                                        "  density = 5.0, pressure = 1.0e-6,")),
                  ["warning: &region(1): density: 5.0000E+00 differs by more than 20%"],
                  expect_code=0))
    c.append(Case("units_velocity_m_per_s",
                  sub("  density = 1.0, pressure = 1.0,",
                      "  velocity = 800.0, 0.0, 0.0, density = 1.0, pressure = 1.0,"),
                  ["&region(1): velocity: speed 800.00 is above 10 cm/us (100 km/s); impacts "
                   "are below about 1 cm/us (10 km/s): a speed in m/s in a cm-g-us-mbar deck?",
                   "&control allow_high_speed = .true."], max_errors=1))
    c.append(Case("units_boundary_velocity_m_per_s",
                  sub("&boundary set = 'xmin', type = 'symmetry' /",
                      "&boundary set = 'xmin', type = 'velocity', velocity = 300.0, 0.0, 0.0 /"),
                  ["&boundary(1): velocity: speed 300.00 is above 10 cm/us (100 km/s)"],
                  max_errors=1))
    c.append(Case("units_radial_field_too_fast",
                  sub("  density = 1.0, pressure = 1.0,",
                      "  radial_u0 = 5.0, radial_r0 = 1.0, radial_k = 2.0, "
                      "center = -0.05, -0.05, -0.05, density = 1.0, pressure = 1.0,"),
                  ["&region: radial_u0: the initial speed of node", ", above 10 cm/us"],
                  max_errors=1))
    c.append(Case("units_high_speed_allowed",
                  chain(sub("  cfl = 0.5\n", "  cfl = 0.5\n  allow_high_speed = .true.\n"),
                        sub("  density = 1.0, pressure = 1.0,",
                            "  velocity = 800.0, 0.0, 0.0, density = 1.0, pressure = 1.0,"),
                        sub("  t_end = 0.05\n", "  t_end = 1.0e-5\n")),
                  [], expect_code=0))
    c.append(Case("units_none_not_checked",
                  chain(sub("  cfl = 0.5\n", "  cfl = 0.5\n  units = 'none'\n"),
                        sub("  density = 1.0, pressure = 1.0,",
                            "  velocity = 800.0, 0.0, 0.0, density = 1.0, pressure = 1.0,"),
                        sub("  t_end = 0.05\n", "  t_end = 1.0e-5\n")),
                  [], expect_code=0))
    c.append(Case("default_density_from_rho0",
                  chain(al_regions, sub("  density = 2.703, pressure = 1.0e-6,",
                                        "  energy = 0.0,")),
                  [], expect_code=0))
    # Two independent errors, one in a group read with the deck (&boundary
    # type) and one that used to wait for the mesh (&mesh block): one run
    # reports both, and says what it could not check.
    c.append(Case("two_independent_errors",
                  chain(sub("set = 'xmax', type = 'symmetry'", "set = 'xmax', type = 'rigid'"),
                        sub("&mesh", "&mesh block = 'tub',")),
                  ["&boundary(2): type: 'rigid' is not a boundary condition",
                   "&mesh: block: 'tub' is not the name of a &block (valid: tube; did you "
                   "mean 'tube'?)",
                   "impact3d: not checked because of the deck errors above: the mesh"],
                  min_errors=2, max_errors=2))
    c.append(Case("contact_unknown_surface_closest",
                  append("&contact surface_a = 'zmaxx', surface_b = 'xmin', method = 'dam' /\n"),
                  ["&contact(1): surface_a: 'zmaxx' is not a face set of the mesh (valid: "
                   "xmin, xmax, ymin, ymax, zmin, zmax; did you mean 'zmax'?)"], max_errors=1))
    # --- failure, erosion, the kinetic-energy stop (issue 32) -------------------
    gas = "name = 'gas', eos = 'ideal_gas', gamma = 1.4"
    ep = ("name = 'gas', eos = 'mie_gruneisen', rho0 = 1.0, c0 = 1.0, s1 = 1.0, gamma0 = 0.4, "
          "strength = 'elastic_plastic', shear_modulus = 0.3, yield_stress = 0.003")
    c.append(Case("failure_unknown_model", sub(gas, ep + ", failure = 'gurson'"),
                  ["&material(1): failure: 'gurson' is not a failure model (valid: none, "
                   "johnson_cook, plastic_strain)"]))
    c.append(Case("failure_without_strength", sub(gas, gas + ", failure = 'plastic_strain', "
                                                   "failure_strain = 0.3"),
                  ["&material(1): failure: needs a strength model"]))
    c.append(Case("failure_jc_damage_missing", sub(gas, ep + ", failure = 'johnson_cook', "
                                                   "jc_damage = 0.05, 3.44"),
                  ["&material(1): jc_damage: five values D1, D2, D3, D4, D5 required for "
                   "failure = 'johnson_cook'"]))
    c.append(Case("failure_jc_damage_nonpositive", sub(gas, ep + ", failure = 'johnson_cook', "
                                                       "jc_damage = -1.0, 0.5, -1.0, 0.0, 0.0"),
                  ["&material(1): jc_damage: D1 + D2 (the failure strain at zero triaxiality"]))
    c.append(Case("failure_jc_damage_without_model", sub(gas, ep + ", jc_damage = 0.05, 3.44, "
                                                         "-2.12, 0.002, 0.61"),
                  ["&material(1): jc_damage: only for failure = 'johnson_cook'"]))
    c.append(Case("failure_strain_missing", sub(gas, ep + ", failure = 'plastic_strain'"),
                  ["&material(1): failure_strain: required for failure = 'plastic_strain'"]))
    c.append(Case("failure_strain_nonpositive", sub(gas, ep + ", failure = 'plastic_strain', "
                                                    "failure_strain = 0.0"),
                  ["&material(1): failure_strain: must be > 0"]))
    c.append(Case("failure_strain_without_model", sub(gas, ep + ", failure_strain = 0.3"),
                  ["&material(1): failure_strain: only for failure = 'plastic_strain'"]))
    c.append(Case("spall_strength_negative", sub(gas, ep + ", spall_strength = -0.01"),
                  ["&material(1): spall_strength: must be > 0"]))
    c.append(Case("erode_without_failure", sub(gas, ep + ", erode = .true."),
                  ["&material(1): erode: needs failure or spall_strength"]))
    c.append(Case("erosion_bad_values", append("&erosion volume_ratio = 1.5, dt_fraction = -0.1, "
                                               "blocks = 'tube, tubes' /\n"),
                  ["&erosion: volume_ratio: must be in [0, 1)",
                   "&erosion: dt_fraction: must be in [0, 1)",
                   "&erosion: blocks: 'tubes' is not a block of this deck"], min_errors=3))
    c.append(Case("erosion_nothing", append("&erosion blocks = 'tube' /\n"),
                  ["&erosion: volume_ratio, dt_fraction: give at least one (> 0)"]))
    c.append(Case("erosion_twice", append("&erosion volume_ratio = 0.1 /\n"
                                          "&erosion volume_ratio = 0.2 /\n"),
                  ["&erosion: group given more than once"]))
    c.append(Case("stop_block_unknown", sub("  cfl = 0.5\n", "  cfl = 0.5\n  stop_block = 'tubo', "
                                             "stop_kinetic_fraction = 0.1\n"),
                  ["&control: stop_block: 'tubo' is not a block of this deck"]))
    c.append(Case("stop_fraction_missing", sub("  cfl = 0.5\n", "  cfl = 0.5\n  stop_block = "
                                                "'tube'\n"),
                  ["&control: stop_kinetic_fraction: required with stop_block"]))
    c.append(Case("stop_fraction_range", sub("  cfl = 0.5\n", "  cfl = 0.5\n  stop_block = "
                                              "'tube', stop_kinetic_fraction = 1.5\n"),
                  ["&control: stop_kinetic_fraction: must be in (0, 1)"]))
    c.append(Case("stop_fraction_without_block", sub("  cfl = 0.5\n", "  cfl = 0.5\n  "
                                                      "stop_kinetic_fraction = 0.1\n"),
                  ["&control: stop_kinetic_fraction: only with stop_block"]))
    c.append(Case("failure_erosion_valid",
                  chain(sub(gas, ep + ", failure = 'johnson_cook', jc_damage = 0.05, 3.44, "
                                      "-2.12, 0.002, 0.61, spall_strength = 0.01, erode = .true."),
                        sub("  cfl = 0.5\n", "  cfl = 0.5\n  stop_block = 'tube', "
                                              "stop_kinetic_fraction = 0.1\n"),
                        append("&erosion volume_ratio = 0.1, dt_fraction = 0.01, "
                               "blocks = 'tube' /\n"),
                        sub("  t_end = 0.05\n", "  t_end = 1.0e-3\n")),
                  [], expect_code=0))
    c.append(Case("valid_base_deck", lambda t: t, [], expect_code=0))
    return c


def written_outputs(case_dir):
    found = []
    for root, _dirs, files in os.walk(case_dir):
        for f in files:
            if f.endswith(".h5") or f == "history.txt":
                found.append(os.path.relpath(os.path.join(root, f), case_dir))
    return sorted(found)


def run_case(case, program, launcher, top):
    case_dir = tempfile.mkdtemp(prefix=case.name[:20] + "_", dir=top)
    try:
        text = case.edit(BASE_DECK).replace("{dir}", case_dir)
    except DeckEditError as err:
        return False, "deck edit did not apply: %s" % err, ""
    deck = os.path.join(case_dir, "deck.nml")
    with open(deck, "w") as f:
        f.write(text)
    arg = case.deck_arg(case_dir, deck) if case.deck_arg else deck
    env = dict(os.environ)
    if launcher:
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                   OMPI_MCA_rmaps_base_oversubscribe="1")
    cmd = launcher + [program, arg]
    try:
        proc = subprocess.run(cmd, cwd=case_dir, env=env, stdin=subprocess.DEVNULL,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              timeout=CASE_TIMEOUT,
                              universal_newlines=True)
    except subprocess.TimeoutExpired as err:
        return False, "timed out after %.0f s" % CASE_TIMEOUT, str(err.stderr or "")
    except OSError as err:
        return False, "cannot run %s: %s" % (" ".join(cmd), err), ""
    err_text = proc.stderr
    why = []
    if re.search(r"^\s*STOP\b", err_text, re.M):
        why.append("stderr holds a 'STOP' line of the run-time library")
    for frag in case.absent:
        if frag in err_text:
            why.append("stderr holds the unwanted %r" % frag)
    if proc.returncode != case.expect_code:
        why.append("exit code %d, expected %d" % (proc.returncode, case.expect_code))
    outputs = written_outputs(case_dir)
    if case.expect_code == 0:
        if not any(o.endswith(".h5") for o in outputs) or \
                not any(os.path.basename(o) == "history.txt" for o in outputs):
            why.append("valid run wrote no dump/history (found %s)" % outputs)
        if "input error" in err_text:
            why.append("valid run reported input errors")
        for frag in case.expect:
            if frag not in err_text:
                why.append("stderr lacks %r" % frag)
    else:
        for frag in case.expect:
            if frag not in err_text:
                why.append("stderr lacks %r" % frag)
        if outputs:
            why.append("output written: %s" % ", ".join(outputs))
        m = SUMMARY.search(err_text)
        if not m:
            why.append("no summary line 'impact3d: N input error(s); nothing was run'")
        else:
            n = int(m.group(1))
            lines = len(re.findall(r"^input error: ", err_text, re.M))
            if n < case.min_errors:
                why.append("summary counts %d error(s), expected at least %d"
                           % (n, case.min_errors))
            if case.max_errors is not None and n > case.max_errors:
                why.append("summary counts %d error(s), expected at most %d"
                           % (n, case.max_errors))
            if n != lines:
                why.append("summary counts %d error(s) but %d 'input error:' lines were "
                           "printed" % (n, lines))
            if len(SUMMARY.findall(err_text)) != 1:
                why.append("summary line printed %d times" % len(SUMMARY.findall(err_text)))
    if not why:
        shutil.rmtree(case_dir, ignore_errors=True)
    return not why, "; ".join(why), err_text


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("program", help="path to the impact3d executable")
    p.add_argument("--mpiexec", help="MPI launcher (e.g. mpirun)")
    p.add_argument("--np", type=int, default=2, help="ranks with --mpiexec (default 2)")
    p.add_argument("--jobs", type=int, default=4, help="cases run at once (default 4)")
    p.add_argument("--verbose", action="store_true", help="print stderr of every case")
    p.add_argument("--keep", action="store_true", help="keep the temporary directories")
    args = p.parse_args()

    program = os.path.abspath(args.program)
    if not os.access(program, os.X_OK):
        print("bad_decks.py: %s is not an executable" % program)
        return 1
    launcher = []
    if args.mpiexec:
        launcher = [args.mpiexec, "-np", str(args.np)]

    top = tempfile.mkdtemp(prefix="impact3d_bad_decks_")
    passed = failed = 0
    cases = build_cases()
    # The runs are short and mostly wait (an MPI job that exits with code 1
    # takes mpirun about a second to wind down), so a few run side by side.
    pool = concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs))
    try:
        results = pool.map(lambda case: run_case(case, program, launcher, top), cases)
        for case, (ok, why, err_text) in zip(cases, results):
            if ok:
                passed += 1
                print("PASS %s" % case.name)
                if args.verbose:
                    print("  | " + "\n  | ".join(err_text.rstrip("\n").split("\n")))
            else:
                failed += 1
                print("FAIL %s: %s" % (case.name, why))
                print("  stderr:\n  | " + "\n  | ".join(err_text.rstrip("\n").split("\n")))
            sys.stdout.flush()
    finally:
        pool.shutdown(wait=True)
        if args.keep or failed:
            print("(case directories kept under %s)" % top)
        else:
            shutil.rmtree(top, ignore_errors=True)
    print("%d passed, %d failed" % (passed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
