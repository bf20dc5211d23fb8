# Total energy conserved to round-off (compatible scheme), with boundary work.
impact3d_check(energy/sedov_20 "regression;parallel" energy --workdir ${WORK}/energy_sedov
  --deck ${CMAKE_CURRENT_LIST_DIR}/sedov_energy.nml --np 2 --tol 1e-12)
impact3d_check(energy/piston_pressure "regression" energy --workdir ${WORK}/energy_piston
  --deck ${CMAKE_CURRENT_LIST_DIR}/piston_energy.nml --np 1 --tol 1e-12)
