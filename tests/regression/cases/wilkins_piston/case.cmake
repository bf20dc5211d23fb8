# Wilkins-type elastic-plastic wave (piston-driven, 1D strain): precursor speed
# within 2% of c_L, precursor amplitude within 3% of the HEL, plastic wave within
# 3% of c0 + s up at the measured particle velocity.
impact3d_check(verify/elastic_plastic_waves "regression;verification;solids" twowave
  --workdir ${WORK}/twowave --deck ${CMAKE_CURRENT_LIST_DIR}/wilkins_piston.nml
  --target 0.640875 --hel 5.8325e-3 --c0 0.524 --s1 1.40 --rho0 2.703 --target-velocity 0.02
  --origin 0)
