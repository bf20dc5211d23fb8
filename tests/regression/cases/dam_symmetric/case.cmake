# DAM's optional second pass: on the coarse planar Sedov split the one-pass run
# has master nodes beyond the audit's tolerance and the two-pass run none, no
# unheld node, no positive contact work, energy to round-off.
impact3d_regress(contact/dam_symmetric "regression;contact"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE} ${WORK}/dam_symmetric)
