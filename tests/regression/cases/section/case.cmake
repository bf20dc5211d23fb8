# tools/section.py on real dumps (sizes, not blank, exact zone and outline
# counts of a structured mesh) and the dumps' derived fields: von Mises
# stress and displacement from the initial positions (issue 33).
impact3d_regress(tools/section "regression;solids"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE} ${WORK}/section)
