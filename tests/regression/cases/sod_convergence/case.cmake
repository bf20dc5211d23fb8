# Sod: first-order convergence of L1(rho) (shock-dominated: rate ~1) and a bound
# at 200 zones 5% above the measured 2.77e-3 (round-off cannot move it; a change
# in the scheme that degrades it by more than 5% must be looked at).
impact3d_check(verify/sod_convergence "regression;verification" convergence
  --workdir ${WORK}/sod_conv --deck ${DECKS}/sod_conv.nml.in --np 1
  --sizes 100 200 400 --problem sod --key L1_rho --min-rate 0.8 --max-at 200=2.9e-3)
