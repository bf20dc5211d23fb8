# Model summary (issue 34): block masses, momenta and kinetic energies to
# round-off for boxes and within the faceting error for a rod, face set areas,
# probe distance, the material's rho0 as the default density; 1 and 3 ranks.
impact3d_regress(deck/model_summary "regression;parallel"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE} ${WORK}/model_summary
  --mpiexec ${MPIEXEC_EXECUTABLE} --ranks 1 3)
