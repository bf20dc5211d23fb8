# Failure, erosion and the kinetic-energy stop (check.py: a bar in tension
# failing at the plastic strain derived from its stretching; one zone eroded
# with its mass and energy booked exactly and the balance at round-off; a
# bar on a wall stopped by its kinetic energy at L / (2c)).
foreach(c failure erosion stop spall)
  impact3d_regress(solids/failure_${c} "regression;solids"
    ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE} ${WORK}/failure_${c} --case ${c}
    --mpiexec ${MPIEXEC_EXECUTABLE} --np 1)
endforeach()
# Erosion active: every dump and history.txt bitwise on 1, 2, 3, 4 ranks.
impact3d_check(parallel/bitwise_erosion "regression;parallel;solids" bitwise
  --workdir ${WORK}/bitwise_erosion --deck ${CMAKE_CURRENT_LIST_DIR}/bar_erosion.nml
  --ranks 1 2 3 4 --history)
# Restart across the erosion event (cycle 547) and after it, on other rank
# counts: final dump bitwise, history byte for byte.
impact3d_check(restart/erosion_across "regression;parallel;solids" restart
  --workdir ${WORK}/restart_erosion_across --deck ${CMAKE_CURRENT_LIST_DIR}/bar_erosion.nml
  --np 1 --restart-np 3 --from-cycle 500 --history-bitwise)
impact3d_check(restart/erosion_after "regression;parallel;solids" restart
  --workdir ${WORK}/restart_erosion_after --deck ${CMAKE_CURRENT_LIST_DIR}/bar_erosion.nml
  --np 2 --restart-np 1 --from-cycle 600 --history-bitwise)
# The stop's reference energy travels in the restart dump.
impact3d_check(restart/kinetic_stop "regression;parallel;solids" restart
  --workdir ${WORK}/restart_kinetic_stop --deck ${CMAKE_CURRENT_LIST_DIR}/bar_stop.nml
  --np 1 --restart-np 2 --from-cycle 100 --history-bitwise)
# The Johnson-Cook failure path with D = (0.05, 0.05, 0, 0, 0), eps_f = 0.1
# exactly: dumps bitwise those of failure_strain = 0.1.
impact3d_check(solids/failure_jc_constant "regression;solids" same
  --workdir ${WORK}/failure_jc_constant --deck ${CMAKE_CURRENT_LIST_DIR}/bar_failure_jc.nml
  --reference ${CMAKE_CURRENT_LIST_DIR}/bar_failure.nml --np 1)
