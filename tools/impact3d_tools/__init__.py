"""impact3d's Python tools as one package: the dump reader (`dump`), the
history reader (`history`), the exact solutions (`exact.riemann`,
`exact.sedov`, `exact.noh`, `exact.verney`), the comparison of a dump with
them (`compare`, its measures in `measures`), shape and gap measures
(`shapes`, `radial`), profile plots (`profiles`), the Gmsh-to-Exodus writer
(`exodus`) and the verification runs (`runs`).

Import it with `tools/` on the path: scripts in `tools/` have it there
already (it is their own directory); the tests get it through PYTHONPATH (set
by CTest); elsewhere `PYTHONPATH=<repo>/tools`. No module edits the import path."""
