"""Exact solutions of the verification problems (docs/problems.md): the
Riemann problem for two ideal gases (`riemann`), the Sedov-Taylor blast
wave (`sedov`), the Noh implosion (`noh`) and the Verney shell's
rigid-plastic collapse (`verney`). Each module's docstring gives its sources
and derivation; `python3 -m impact3d_tools.exact.sedov` etc. print a sample."""
