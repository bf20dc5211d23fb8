# &control units = 'si': the small Taylor rod in cm-g-us-Mbar and in SI
# (library data converted) agree after unit conversion to round-off; the
# dumps' units attributes name the system.
impact3d_regress(units/taylor_si "regression;solids;parallel"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE}
  ${WORK}/units_si --mpiexec ${MPIEXEC_EXECUTABLE} --np 2)
