# Mie-Gruneisen: a piston at up = 0.05 cm/us into aluminium; the shocked state
# (0.3 < x < 0.8 at t = 2 us) has the Hugoniot density rho0 Us/(Us - up) = 2.9514
# within 0.5% (measured 2.9513).
impact3d_check(verify/mie_gruneisen_piston "regression;verification" window
  --workdir ${WORK}/mg_piston --deck ${CMAKE_CURRENT_LIST_DIR}/mg_piston.nml --np 1 --axis x
  --range 0.3 0.8 --target 2.9514 --tol 0.005)
