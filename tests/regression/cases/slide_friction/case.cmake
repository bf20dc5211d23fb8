# Coulomb friction (issue 17 item 2): a block (0.6 x 0.6 x 0.4 cm, elastic
# aluminium, m = 0.389232 g) pressed by p = 1e-4 Mbar on its top face onto a
# plane - the rigid wall, or an aluminium plate held at its bottom through DLM
# or DAM contact - slides from v0 = 0.01 cm/us with friction 0.3: deceleration
# a = mu p A / m = 2.7747e-5 cm/us^2, stopping time v0/a = 360.40 us and
# distance v0^2/(2a) = 1.8020 cm, each within 1%; energy balance to round-off
# with the friction work booked, and that work = -(the block's initial kinetic
# energy). Why 1% holds for a block that is not rigid (each a bound; the
# measured deviations, 0.03-0.25%, are in docs/contact.md):
# * the applied pressure is a step: the load reaches the bottom H/c_L =
#   0.4/0.641 = 0.62 us late and then rings (normal force 0..2pA, period
#   2.5 us) - the stop moves by at most 2H/c_L = 1.25 us, 0.35% of 360 us;
# * elastic compression p/(rho c_L^2) = 9e-5 changes the loaded area by < 2e-4;
# * the bottom layer is slowed by the shear wave tau/(rho c_s) = mu p/(rho c_s)
#   = 3.5e-5 cm/us ahead of the mean velocity, 0.35% of v0: it stops at most
#   0.35% early, and the rest keeps being braked;
# * the friction torque pitches the block; the pressure follows the tilted top
#   face, whose x component is the tilt (penetration allowed at the front
#   over the 0.6 cm length: DLM 0.4 x penetration_tolerance = 4e-4 cm, 6.7e-4
#   rad) times pA: <= 0.22% of the friction force (with DLM's default
#   allowance, 4e-3 cm, this was 2.2%: measured +0.7%);
# * the plate's x momentum (<= 2e-3 m v0 at every dump, checked) enters the
#   stopping time read from the history's momentum_x: <= 0.2%.
# Deceleration (slope over the dumps at 0.2-0.8 v0, 216 us): ringing (one
# half period of 2pA over 216 us, 0.6%, halved by the least-squares fit over
# 20 dumps: ~0.3%), area and tilt: <= 0.55%. Stopping time: the late load
# (late) and the early stick of the bottom (early) pull opposite ways, each
# <= 0.35%; with tilt and plate momentum <= 0.8%. Distance: the late load
# adds v0 H/c_L = 6e-3 cm (0.35%), the tilt <= 0.22%; the early stick of the
# bottom acts near the stop, where the block is slow: <= 0.6%.
foreach(m wall dlm dam)
  impact3d_check(contact/slide_friction_${m} "regression;contact" slide
    --workdir ${WORK}/slide_friction_${m} --deck ${CMAKE_CURRENT_LIST_DIR}/slide_friction_${m}.nml
    --v0 0.01 --friction 0.3 --pressure 1e-4 --area 0.36 --tol 0.01 --pair slide)
endforeach()
# Friction in the bitwise 1-4 rank and restart tests: the first 40 us of the
# sliding block (sliding throughout), dumps every 50 cycles.
set(SLIDE_SHORT --replace "t_end = 400.0" "t_end = 40.0"
  --replace "dump_interval = 10.0" "dump_cycles = 50")
foreach(m wall dlm dam)
  impact3d_check(parallel/bitwise_slide_friction_${m} "regression;parallel;contact" bitwise
    --workdir ${WORK}/bitwise_slide_friction_${m}
    --deck ${CMAKE_CURRENT_LIST_DIR}/slide_friction_${m}.nml --ranks 1 2 3 4 ${SLIDE_SHORT})
  impact3d_check(restart/slide_friction_${m} "regression;parallel;contact" restart
    --workdir ${WORK}/restart_slide_friction_${m}
    --deck ${CMAKE_CURRENT_LIST_DIR}/slide_friction_${m}.nml --np 2 --restart-np 3
    --from-cycle 200 ${SLIDE_SHORT})
endforeach()
