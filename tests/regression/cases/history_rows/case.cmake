# Restarts of long and wide histories (issue 33): the restart's set-up time
# stays linear in the rows kept (below max(10 x a fresh start's, 0.5 s) after
# 3000 of 6000 rows), rows of any width are kept byte for byte (restarted on
# another rank count), and the history and probe files after a restart are
# byte for byte those of the uninterrupted run.
impact3d_regress(restart/history_long "regression;parallel"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py long ${EXE} ${WORK}/history_long
  ${MPIEXEC_EXECUTABLE})
impact3d_regress(restart/history_wide "regression;parallel"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py wide ${EXE} ${WORK}/history_wide
  ${MPIEXEC_EXECUTABLE})
