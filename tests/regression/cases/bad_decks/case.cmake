# Deck validation: >= 20 bad decks, each rejected with group, key and reason.
impact3d_regress(deck/bad_decks "regression"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE})
impact3d_regress(deck/bad_decks_np2 "regression;parallel"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE} --mpiexec ${MPIEXEC_EXECUTABLE} --np 2)
