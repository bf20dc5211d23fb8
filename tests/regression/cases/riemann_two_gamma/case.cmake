# Two-gamma Riemann problem on one conforming two-material mesh: interface and
# shock within 2 local zone widths; L1(rho) 5% above the measured 2.70e-3.
impact3d_check(verify/riemann_two_gamma "regression;verification" interface
  --workdir ${WORK}/riemann2 --deck ${CMAKE_CURRENT_LIST_DIR}/riemann2.nml --np 1
  --problem riemann2 --zones-tol 2 --max L1_rho=2.85e-3
  "--compare-args=--gamma-left 1.4 --gamma-right 1.6666666666666667")
