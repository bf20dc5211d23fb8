# Verney shell (octant, no contact): the inner surface stops at r = 4.0 cm
# (incompressible rigid-plastic energy balance) within 0.1 cm.
impact3d_check(verify/verney_shell "regression;verification;solids;parallel" shell_stop
  --workdir ${WORK}/verney --deck ${CMAKE_CURRENT_LIST_DIR}/verney.nml --np 2 --origin 8.0
  --target 4.0 --tol 0.1)
