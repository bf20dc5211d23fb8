# ParaView reads the dumps (label viz): pvbatch under xvfb-run opens
# dump.xmf; times, arrays and ranges equal the HDF5 dumps'; a rendered PNG is
# not blank. Skipped (exit 77) without pvbatch/xvfb-run (./setup.sh --viz
# installs them).
impact3d_regress(viz/paraview_dump "viz"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE}
  ${WORK}/paraview --mpiexec ${MPIEXEC_EXECUTABLE} --np 2)
set_tests_properties(viz/paraview_dump PROPERTIES SKIP_RETURN_CODE 77)
