# tools/cavity_expansion.py (the rigid-rod depth of the penetration problem's
# analytic reference, docs/problems.md E) against an independent RK4
# integration in time of the same model, to 1e-6 relative; the nose factors
# against their closed forms to round-off (check.py states the bounds).
impact3d_regress(tools/cavity_expansion "regression;tools"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py)
