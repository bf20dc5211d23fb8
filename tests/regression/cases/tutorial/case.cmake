# docs/tutorial.md as written (issue 34): its deck and commands (check, both
# contact methods on 2 ranks, the probe plot, a restart on 3 ranks) run in an
# empty folder; the numbers the text quotes and physical bounds are checked.
impact3d_regress(tutorial/first_impact "regression;contact;parallel"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE} ${CMAKE_SOURCE_DIR}
  ${WORK}/tutorial --mpiexec ${MPIEXEC_EXECUTABLE})
