# Surfaces given by blocks (surface_a = 'block:left'): bitwise the dumps and
# history of the deck naming the same faces as face sets, on 1 and 3 ranks.
impact3d_regress(contact/blocks "regression;contact"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE} ${WORK}/contact_blocks
  --mpiexec ${MPIEXEC_EXECUTABLE})
