# tools/penetration_depth.py (the depth P of the penetration problem,
# docs/problems.md E1) on synthetic dumps with known answers: the deepest live
# rod node over the dumps, eroded zones and other blocks left out, the 10 us
# gap limit and the unknown-block error (check.py).
impact3d_regress(tools/penetration_depth "regression;tools"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py)
