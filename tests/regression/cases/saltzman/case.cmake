# Saltzman piston: runs to t = 0.7 on the skewed mesh; density 4 +- 5% between
# the piston and the shock, away from both (0.75 < x < 0.88).
impact3d_check(verify/saltzman "regression;verification" window --workdir ${WORK}/saltzman
  --deck ${CMAKE_CURRENT_LIST_DIR}/saltzman.nml --np 1 --axis x --range 0.75 0.88 --target 4.0
  --tol 0.05)
