# --- Stability stress tests: run to the end or stop through the failure path,
# never crash, never a NaN in a dump.
impact3d_check(stability/sedov_perturbed "regression;stability;parallel" stability
  --workdir ${WORK}/stab_sedov_pert --deck ${CMAKE_CURRENT_LIST_DIR}/sedov_perturbed.nml --np 2)
foreach(cfl 0.3 0.5 0.7 0.9)
  file(READ ${DECKS}/sedov_conv.nml.in _deck)
  string(REPLACE "{n}" "20" _deck "${_deck}")
  string(REPLACE "t_end = 1.0 /" "t_end = 1.0, cfl = ${cfl} /" _deck "${_deck}")
  file(WRITE ${WORK}/decks/sedov_cfl_${cfl}.nml "${_deck}")
  impact3d_check(stability/sedov_cfl_${cfl} "regression;stability" stability
    --workdir ${WORK}/stab_cfl_${cfl} --deck ${WORK}/decks/sedov_cfl_${cfl}.nml --np 1)
endforeach()
