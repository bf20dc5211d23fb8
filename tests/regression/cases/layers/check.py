#!/usr/bin/python3
"""The layering of src/ (docs/design.md): every `use` statement names a
module of its own layer or of a lower one (HDF5's Fortran module counts as
io, the configured core_version as core), in the order

    core <- parallel <- mesh <- eos/material <- hydro <- contact <- solver <- io <- app

(eos and material are one level), and no file outside src/parallel uses MPI.

Usage: check.py SRC_DIR
"""

import os
import re
import sys

ORDER = ["core", "parallel", "mesh", "eos", "material", "hydro", "contact", "solver", "io",
         "app"]
LEVEL = {name: i for i, name in enumerate(ORDER)}
LEVEL["material"] = LEVEL["eos"]
USE = re.compile(r"^\s*use\b(?:\s*,\s*(intrinsic|non_intrinsic)\s*::|\s*::|\s+)\s*(\w+)",
                 re.I | re.M)
# Modules from outside src/: the library each layer may use.
EXTERNAL = {"hdf5": "io", "core_version": "core"}
MODULE = re.compile(r"^\s*module\s+(\w+)\s*$", re.I | re.M)
MPI = re.compile(r"^\s*(use\s+mpi(_f08)?\b|include\s+['\"]mpif\.h['\"])", re.I | re.M)


def main(src):
    layer_of = {}
    files = []
    for dirpath, _, names in os.walk(src):
        for n in names:
            if not n.endswith(".f90"):
                continue
            path = os.path.join(dirpath, n)
            layer = os.path.relpath(path, src).split(os.sep)[0]
            text = open(path).read()
            files.append((path, layer, text))
            for m in MODULE.findall(text):
                layer_of[m.lower()] = layer
    bad = []
    for path, layer, text in files:
        if layer not in LEVEL:
            bad.append("%s: directory '%s' is not a layer" % (path, layer))
            continue
        for kind, mod in USE.findall(text):
            if kind.lower() == "intrinsic" or mod.lower() in ("iso_fortran_env",
                                                               "iso_c_binding",
                                                               "ieee_arithmetic"):
                continue
            if mod.lower() in ("mpi", "mpi_f08"):
                continue
            target = layer_of.get(mod.lower(), EXTERNAL.get(mod.lower()))
            if target is None:
                bad.append("%s: uses '%s', not a module of src/" % (path, mod))
            elif LEVEL[target] > LEVEL[layer]:
                bad.append("%s (%s) uses %s (%s): a higher layer" % (path, layer, mod, target))
        if layer != "parallel" and MPI.search(text):
            bad.append("%s: MPI outside src/parallel" % path)
    for line in bad:
        print("FAIL " + line)
    print("%d files, %d modules checked: %d passed, %d failed"
          % (len(files), len(layer_of), 0 if bad else 1, 1 if bad else 0))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
