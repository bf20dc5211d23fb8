# Sedov octant at 30^3: shock radius within 2% of exact at t = 1.
impact3d_check(verify/sedov_30 "regression;verification;parallel" compare
  --workdir ${WORK}/sedov30 --deck ${CMAKE_CURRENT_LIST_DIR}/sedov_30.nml --np 2
  --problem sedov --max shock_r_error_rel=0.02 --min shock_r_error_rel=-0.02)
