# Al block on a steel block (docs/problems.md, D3, long): on the fine mesh (Al 20,
# steel 16 zones/cm, to 1.5 us) the axial stress on the axis next to the
# interface, averaged over 0.3-1.2 us, is within 3% of the 1D elastic-plastic
# impedance match from the same data (0.11995 Mbar; problems/al_on_steel).
foreach(m dlm dam)
  impact3d_regress(long/al_on_steel_${m} "long;contact;solids"
    ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py --exe ${EXE} --mpiexec ${MPIEXEC_EXECUTABLE}
    --workdir ${WORK}/al_on_steel_${m} --deck ${PROBLEMS}/al_on_steel/al_on_steel_${m}_fine.nml
    --np 2 --tol 0.03)
endforeach()
