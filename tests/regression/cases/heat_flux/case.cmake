# Noh's artificial heat flux (&hydro heat_flux_quadratic): energy to round-off,
# bitwise rank independence, Noh against the scalar viscosity alone, first-order
# Sod, and (long) Noh 45^3 against the exact solution (README.md).
impact3d_check(heat_flux/energy_sedov "regression;parallel" energy
  --workdir ${WORK}/hf_energy_sedov --deck ${CMAKE_CURRENT_LIST_DIR}/sedov_hf.nml --np 2
  --tol 1e-12)
impact3d_check(heat_flux/bitwise_sedov "regression;parallel" bitwise
  --workdir ${WORK}/hf_bitwise_sedov --deck ${CMAKE_CURRENT_LIST_DIR}/sedov_hf.nml
  --ranks 1 2 3 4)
# Noh 20^3: the heat flux against the same deck without it: a higher plateau
# density (less wall heating) and a shock closer to the exact radius.
impact3d_check(heat_flux/noh_20 "regression;verification;parallel" versus
  --workdir ${WORK}/hf_noh20 --deck ${CMAKE_CURRENT_LIST_DIR}/noh_hf_20.nml
  --reference ${CMAKE_CURRENT_LIST_DIR}/noh_scalar_20.nml --np 2
  --problem noh --closer shock_r_error_rel --higher rho_post_mean)
# Sod with the heat flux stays first order (rate of L1(rho) >= 0.8).
impact3d_check(heat_flux/sod_convergence "regression;verification" convergence
  --workdir ${WORK}/hf_sod_conv --deck ${CMAKE_CURRENT_LIST_DIR}/sod_hf.nml.in --np 1
  --sizes 100 200 400 --problem sod --key L1_rho --min-rate 0.8)
# Noh 45^3 (long): plateau density within 4 of the exact 64 (the target 60
# and as far above), shock radius within 3% of 0.2.
impact3d_check(long/noh_45_heat_flux "long;verification;parallel" compare
  --workdir ${WORK}/hf_noh45 --deck ${CMAKE_CURRENT_LIST_DIR}/noh_hf_45.nml --np 2
  --problem noh --max shock_r_error_rel=0.03 --min shock_r_error_rel=-0.03
  --min rho_post_mean=60 --max rho_post_mean=68)
