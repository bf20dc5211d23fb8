# Noh octant 40^3: runs to t = 0.6 (no tangling); shock radius within 10% of
# 0.2 (measured 0.2152, +7.6%); the mass-weighted density of the shell
# 0.05 < r < 0.15 (a quarter to three quarters of the shock radius) at least 48
# (measured 50.4, exact 64: the gas shocked while the shock was a few zones from
# the origin keeps the start-up entropy error of scalar viscosity - wall heating -
# and the plateau rises from 42 near the origin to 57 behind the front). At 30^3
# the radius is +11.5%: not enough zones behind the front.
impact3d_check(verify/noh_40 "regression;verification;parallel" compare --workdir ${WORK}/noh40
  --deck ${CMAKE_CURRENT_LIST_DIR}/noh.nml --np 2 --problem noh --max shock_r_error_rel=0.10
  --min shock_r_error_rel=-0.10 --min rho_post_mean=48)
