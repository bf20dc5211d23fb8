# &probe (issue 20 item 2): the elastic bar on a wall, free end reverses at
# L/c, impacted end released at 2L/c; probe rows equal the dumps exactly; CSV
# bitwise on 1-4 ranks and across a restart.
impact3d_regress(probe/bar "regression;solids;parallel"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE}
  ${WORK}/probe_bar --mpiexec ${MPIEXEC_EXECUTABLE} --ranks 1 2 3 4 --restart-np 3)
