# 1D-strain elastic wave: front speed within 1% of sqrt((K + 4G/3)/rho).
impact3d_check(verify/elastic_wave_speed "regression;verification;solids" wavefront
  --workdir ${WORK}/elastic_wave --deck ${CMAKE_CURRENT_LIST_DIR}/elastic_wave.nml
  --target 0.640875 --target-velocity 1e-4 --origin 0 --tol 0.01)
