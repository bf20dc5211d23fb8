# Contact energy bounded by physics: the equal and dissimilar elastic bars
# (the shared decks tests/regression/decks/bars_*), both methods: no contact
# work after the impact cycle (1e-6 E0), the impact cycle's loss equal to the
# inelastic stop of the interface nodes derived in the test, halving with h.
foreach(c equal dissimilar)
  foreach(m dam dlm)
    impact3d_regress(contact/bars_energy_${c}_${m} "regression;contact"
      ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE}
      ${WORK}/bars_energy_${c}_${m} --case ${c} --method ${m}
      --mpiexec ${MPIEXEC_EXECUTABLE} --np 1)
  endforeach()
endforeach()
