# Elastic bar on the rigid unilateral wall: contact lasts 2L/c and the bar
# rebounds at its impact speed, both within 2%.
impact3d_check(verify/bar_rigid_wall "regression;verification;solids" rebound
  --workdir ${WORK}/bar_wall --deck ${CMAKE_CURRENT_LIST_DIR}/bar_wall.nml --target 3.12073
  --tol 0.02)
# Plastic work and wall work close the energy balance to round-off.
impact3d_check(energy/plastic_bar_wall "regression;solids" energy
  --workdir ${WORK}/energy_plastic --deck ${CMAKE_CURRENT_LIST_DIR}/bar_wall_plastic.nml
  --np 2 --tol 1e-12)
# Strength state (deviatoric stress, plastic strain) and the wall: bitwise on
# 1-4 ranks and across a restart.
impact3d_check(parallel/bitwise_plastic_bar "regression;parallel;solids" bitwise
  --workdir ${WORK}/bitwise_plastic --deck ${CMAKE_CURRENT_LIST_DIR}/bar_wall_plastic_dumps.nml
  --ranks 1 2 3 4)
impact3d_check(restart/plastic_bar "regression;parallel;solids" restart
  --workdir ${WORK}/restart_plastic --deck ${CMAKE_CURRENT_LIST_DIR}/bar_wall_plastic_dumps.nml
  --np 3 --restart-np 2 --from-cycle 800)
impact3d_check(energy/steinberg_guinan_bar_wall "regression;solids" energy
  --workdir ${WORK}/energy_sg --deck ${CMAKE_CURRENT_LIST_DIR}/bar_wall_sg.nml --np 2 --tol 1e-12)
impact3d_check(energy/johnson_cook_bar_wall "regression;solids" energy
  --workdir ${WORK}/energy_jc --deck ${CMAKE_CURRENT_LIST_DIR}/bar_wall_jc.nml --np 2 --tol 1e-12)
# Linear isotropic hardening (hardening_modulus) in the plastic bar: the energy
# balance still closes to round-off (measured 6e-15; peak plastic strain 0.0344
# against 0.0356 without hardening).
impact3d_check(energy/hardening_bar_wall "regression;solids" energy
  --workdir ${WORK}/energy_hardening --deck ${CMAKE_CURRENT_LIST_DIR}/bar_wall_hardening.nml
  --np 2 --tol 1e-12)
