# Edge viscosity (&hydro viscosity = 'edge'): energy to round-off, bitwise
# rank independence, Noh and Sod criteria (README.md).
impact3d_check(edge_viscosity/energy_sedov "regression;parallel" energy
  --workdir ${WORK}/edge_energy_sedov --deck ${CMAKE_CURRENT_LIST_DIR}/sedov_edge.nml --np 2
  --tol 1e-12)
impact3d_check(edge_viscosity/bitwise_sedov "regression;parallel" bitwise
  --workdir ${WORK}/edge_bitwise_sedov --deck ${CMAKE_CURRENT_LIST_DIR}/sedov_edge.nml
  --ranks 1 2 3 4)
# Noh 20^3: what the edge viscosity is for, against the scalar viscosity on the
# same mesh: less wall heating (a higher plateau density, 0.05 < r < 0.15) and
# a shock closer to the exact radius; and the shock within 10% of it.
impact3d_check(edge_viscosity/noh_20 "regression;verification;parallel" versus
  --workdir ${WORK}/edge_noh20 --deck ${CMAKE_CURRENT_LIST_DIR}/noh_edge_20.nml
  --reference ${CMAKE_CURRENT_LIST_DIR}/noh_scalar_20.nml --np 2
  --problem noh --max shock_r_error_rel=0.10 --min shock_r_error_rel=-0.10
  --closer shock_r_error_rel --higher rho_post_mean)
# Sod with the edge viscosity: first order (rate >= 0.8) and L1(rho) at 200
# zones at most 2.85e-3 (5% above the measured 2.714e-3; the scalar gives 2.721e-3).
impact3d_check(edge_viscosity/sod_convergence "regression;verification" convergence
  --workdir ${WORK}/edge_sod_conv --deck ${CMAKE_CURRENT_LIST_DIR}/sod_edge.nml.in --np 1
  --sizes 100 200 400 --problem sod --key L1_rho --min-rate 0.8 --max-at 200=2.85e-3)
# Restart from cycle 100 on another rank count ends bitwise identical (the edge
# limiter is rebuilt from the restart state, not carried).
impact3d_check(edge_viscosity/restart_sedov "regression;parallel" restart
  --workdir ${WORK}/edge_restart_sedov --deck ${CMAKE_CURRENT_LIST_DIR}/sedov_edge.nml --np 1
  --restart-np 2 --from-cycle 100)
