# Curved mesh + Steinberg-Guinan + wall (the shared deck taylor_small.nml):
# bitwise on 1-4 ranks and across a restart.
impact3d_check(parallel/bitwise_taylor_small "regression;parallel;solids" bitwise
  --workdir ${WORK}/bitwise_taylor --deck ${DECKS}/taylor_small.nml --ranks 1 2 3 4)
impact3d_check(restart/taylor_small "regression;parallel;solids" restart
  --workdir ${WORK}/restart_taylor --deck ${DECKS}/taylor_small.nml --np 2 --restart-np 3
  --from-cycle 100)
