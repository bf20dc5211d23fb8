# The single-stage scheme (&hydro scheme = 'single', one force evaluation per
# cycle, gas dynamics only): energy to round-off, bitwise rank and restart
# independence, and the default scheme's own verification criteria (README.md).
impact3d_check(single_stage/energy_sedov "regression;parallel" energy
  --workdir ${WORK}/single_energy_sedov --deck ${CMAKE_CURRENT_LIST_DIR}/sedov_single.nml
  --np 2 --tol 1e-12)
impact3d_check(single_stage/bitwise_sedov "regression;parallel" bitwise
  --workdir ${WORK}/single_bitwise_sedov --deck ${CMAKE_CURRENT_LIST_DIR}/sedov_single.nml
  --ranks 1 2 3 4)
impact3d_check(single_stage/restart_sedov "regression;parallel" restart
  --workdir ${WORK}/single_restart_sedov --deck ${CMAKE_CURRENT_LIST_DIR}/sedov_single.nml
  --np 1 --restart-np 2 --from-cycle 100)
# verify/sod_convergence's criteria: first order, L1(rho) at 200 zones <= 2.9e-3.
impact3d_check(single_stage/sod_convergence "regression;verification" convergence
  --workdir ${WORK}/single_sod_conv --deck ${CMAKE_CURRENT_LIST_DIR}/sod_single.nml.in --np 1
  --sizes 100 200 400 --problem sod --key L1_rho --min-rate 0.8 --max-at 200=2.9e-3)
# verify/sedov_30's criterion: shock radius within 2%.
impact3d_check(single_stage/sedov_30 "regression;verification;parallel" compare
  --workdir ${WORK}/single_sedov30 --deck ${CMAKE_CURRENT_LIST_DIR}/sedov_30_single.nml --np 2
  --problem sedov --max shock_r_error_rel=0.02 --min shock_r_error_rel=-0.02)
# verify/noh_40's criteria: to t = 0.6, shock within 10%, plateau at least 48.
impact3d_check(single_stage/noh_40 "regression;verification;parallel" compare
  --workdir ${WORK}/single_noh40 --deck ${CMAKE_CURRENT_LIST_DIR}/noh_40_single.nml --np 2
  --problem noh --max shock_r_error_rel=0.10 --min shock_r_error_rel=-0.10
  --min rho_post_mean=48)
