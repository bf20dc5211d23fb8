"""impact3d's Python tools as one package: the dump reader (`dump`), the
history reader (`history`). Import it with `tools/` on the path: scripts in
`tools/` have it there already; the tests get it through PYTHONPATH (set by
CTest); elsewhere `PYTHONPATH=<repo>/tools`."""
