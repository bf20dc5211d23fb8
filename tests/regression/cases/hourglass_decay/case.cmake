# Decay of a pure hourglass mode of one cube under the viscous hourglass
# control, against the exact discrete factor (1 - 16 kappa c dt / L)^2 of the
# kinetic energy per cycle (the force once per cycle, in the corrector, on
# the step's starting velocities): check.py's docstring.
impact3d_regress(hydro/hourglass_decay "regression"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE} ${WORK}/hourglass_decay)
