# The failure path: message, final dump, exit code 2, on every rank.
impact3d_check(failure/negative_volume "regression;parallel" failure
  --workdir ${WORK}/fail_volume --deck ${CMAKE_CURRENT_LIST_DIR}/tangle_injected.nml --np 2
  --expect volume)
# A deck built to collapse (cold gas, divergence-free radial squeeze, loosest
# limits): it ends through the failure path, by a zone turning inside out or by
# the step falling below dt_min as the zone flattens, whichever comes first.
impact3d_check(failure/collapse "regression;parallel" failure --workdir ${WORK}/fail_collapse
  --deck ${CMAKE_CURRENT_LIST_DIR}/collapse.nml --np 2 --expect any)
# A NaN made on purpose would trip the floating-point traps of a Debug build.
if(NOT (CMAKE_BUILD_TYPE STREQUAL "Debug" AND IMPACT3D_FPE_TRAPS))
  impact3d_check(failure/nan "regression;parallel" failure --workdir ${WORK}/fail_nan
    --deck ${CMAKE_CURRENT_LIST_DIR}/nan.nml --np 3 --expect nan)
endif()
# The dt_min stop (issue 34): the message names the controlling zone's block,
# material, compression rho/rho0 (1.05 here) and sound speed.
impact3d_check(failure/dt_min "regression;parallel" failure --workdir ${WORK}/fail_dt_min
  --deck ${CMAKE_CURRENT_LIST_DIR}/dt_min.nml --np 2 --expect dt --zone-block box
  --zone-material al --zone-compression 1.05)
