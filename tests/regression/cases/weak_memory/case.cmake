# No whole-mesh array at set-up: the zones' share of the largest rank's peak
# memory at 40^3 zones per rank on 4 ranks is at most 1.25 times that on 1
# rank (check.py's docstring derives the bound).
impact3d_regress(parallel/weak_memory "regression;parallel"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE} ${WORK}/weak_memory
  --mpiexec ${MPIEXEC_EXECUTABLE})
# The Al-on-steel contact pair stacked one pair per rank: the share on 8
# ranks at most 1.10 times that on 4 (contact surfaces built from each
# rank's local mesh; check.py derives the bound).
impact3d_regress(parallel/weak_memory_contact "regression;parallel;contact"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE} ${WORK}/weak_memory_contact
  --mpiexec ${MPIEXEC_EXECUTABLE} --problem contact)
# The same deck on the same rank count gives the same partition every time,
# with at most 3% imbalance (partition_twice.py).
impact3d_regress(parallel/partition_reproducible "regression;parallel"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/partition_twice.py ${EXE}
  ${WORK}/partition_reproducible --mpiexec ${MPIEXEC_EXECUTABLE})
# Imported meshes read by ranges: the Sedov box written at test time as an
# Exodus II file (tests/tools/exodus_box) and read on 1 and 4 ranks; the
# zones' share of the largest rank's peak once the mesh is read, and over
# the whole run, on 4 ranks at most 1.25 times that on 1 rank (check.py
# derives the bound).
impact3d_regress(parallel/weak_memory_exodus "regression;parallel"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE} ${WORK}/weak_memory_exodus
  --mpiexec ${MPIEXEC_EXECUTABLE} --problem sedov_exodus
  --exodus-box $<TARGET_FILE:exodus_box>)
# The same for a Gmsh file (weak.write_gmsh_box, 2.2 ASCII), which rank 0
# streams in chunks of at most 65,536 records.
impact3d_regress(parallel/weak_memory_gmsh "regression;parallel"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE} ${WORK}/weak_memory_gmsh
  --mpiexec ${MPIEXEC_EXECUTABLE} --problem sedov_gmsh)
