# Initial penetration: an Al block half a zone inside a steel block, each
# method with each initial_penetration choice: 'error' refuses the deck,
# 'adjust' moves the overlap out before the run, 'ignore' holds it without
# pushing it out; no energy gain beyond 1%, no audit violation, nothing unheld.
foreach(m dam dlm)
  foreach(o error adjust ignore)
    impact3d_regress(contact/initial_overlap_${m}_${o} "regression;contact"
      ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE}
      ${WORK}/initial_overlap_${m}_${o} --method ${m} --option ${o}
      --mpiexec ${MPIEXEC_EXECUTABLE} --np 2)
  endforeach()
endforeach()
