# Eroding contact: the contact surfaces given by blocks follow the erosion
# (check.py: audit clean after every rebuild, contact on the new surfaces,
# contact work <= 0, energy balance with the eroded columns), DLM and DAM;
# every dump and the exact history columns bitwise on 1, 2 and 3 ranks; a
# restart from the dump at t = 2, before the first erosion (t = 2.7 DLM, 2.9
# DAM), bitwise the uninterrupted run after it.
foreach(m dlm dam)
  impact3d_regress(contact/eroding_${m} "regression;contact;solids"
    ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE} ${WORK}/eroding_${m} --method ${m}
    --mpiexec ${MPIEXEC_EXECUTABLE} --np 1)
  impact3d_check(parallel/bitwise_eroding_${m} "regression;parallel;contact;solids" bitwise
    --workdir ${WORK}/bitwise_eroding_${m} --deck ${CMAKE_CURRENT_LIST_DIR}/pen_${m}.nml
    --ranks 1 2 3 --history --history-except _force _pen_rms _dmom_x _dmom_y _dmom_z)
endforeach()
impact3d_regress(contact/eroding_distortion "regression;contact;solids"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE} ${WORK}/eroding_distortion
  --method distortion --mpiexec ${MPIEXEC_EXECUTABLE} --np 1)
impact3d_regress(contact/eroding_emptied "regression;contact;solids"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE} ${WORK}/eroding_emptied
  --method emptied --mpiexec ${MPIEXEC_EXECUTABLE} --np 1)
foreach(m dlm dam)
  impact3d_check(restart/eroding_${m} "regression;parallel;contact;solids" restart
    --workdir ${WORK}/restart_eroding_${m} --deck ${CMAKE_CURRENT_LIST_DIR}/pen_${m}.nml
    --np 1 --restart-np 2 --from-time 2.0)
endforeach()
