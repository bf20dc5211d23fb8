#!/usr/bin/python3
"""The criterion of docs/problems.md, D3: Al block on a steel block through contact.

Usage: check.py --exe IMPACT3D --mpiexec MPIRUN --workdir DIR --deck DECK
                      [--np 2] [--tol 0.03]

Runs DECK (problems/al_on_steel/al_on_steel_{dlm,dam}_fine.nml) on --np ranks in
a fresh DIR, then problems/al_on_steel/analyse.py on it: the axial stress on the
axis next to the interface, averaged over 0.3-1.2 us, must be within --tol
(relative) of the 1D elastic-plastic impedance match built from the same data
(problems/al_on_steel/impedance_match.py, 0.11995 Mbar). Prints
'N passed, M failed' and exits 1 on failure.
"""
import argparse
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ANALYSE = os.path.join(HERE, "..", "..", "..", "..", "problems", "al_on_steel", "analyse.py")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exe", required=True)
    p.add_argument("--mpiexec", default="mpirun")
    p.add_argument("--workdir", required=True)
    p.add_argument("--deck", required=True)
    p.add_argument("--np", type=int, default=2)
    p.add_argument("--tol", type=float, default=0.03)
    a = p.parse_args()
    if os.path.isdir(a.workdir):
        shutil.rmtree(a.workdir)
    os.makedirs(a.workdir)
    shutil.copy(a.deck, os.path.join(a.workdir, "deck.nml"))
    results = []
    proc = subprocess.run([a.mpiexec, "-np", str(a.np), a.exe, "deck.nml"], cwd=a.workdir,
                          env=ENV, capture_output=True, text=True)
    ok = proc.returncode == 0
    results.append(ok)
    print(("PASS" if ok else "FAIL") + " run: exit code %d" % proc.returncode)
    if not ok:
        print(proc.stdout[-2000:] + proc.stderr[-2000:])
    else:
        check = subprocess.run([sys.executable, ANALYSE, a.workdir, "--tol", str(a.tol)],
                               capture_output=True, text=True)
        ok = check.returncode == 0
        results.append(ok)
        print(check.stdout + check.stderr, end="")
        print(("PASS" if ok else "FAIL") + " axial stress within %g%% of the impedance match"
              % (100 * a.tol))
    print("%d passed, %d failed" % (results.count(True), results.count(False)))
    return 0 if all(results) else 1


if __name__ == "__main__":
    sys.exit(main())
