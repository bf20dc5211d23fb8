# The exact solutions and the dump/compare/plot tools (impact3d_tools) against
# published values.
impact3d_regress(unit/exact_solutions "unit" ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py)
