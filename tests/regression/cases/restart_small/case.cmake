# Restart from a mid-run dump, on another rank count, ends bitwise identical;
# history.txt byte for byte the uninterrupted run's.
impact3d_check(restart/sod_small "regression;parallel" restart --workdir ${WORK}/restart_sod
  --deck ${DECKS}/sod_small.nml --np 2 --restart-np 3 --from-cycle 40 --history-bitwise)
impact3d_check(restart/sedov_small "regression;parallel" restart --workdir ${WORK}/restart_sedov
  --deck ${DECKS}/sedov_small.nml --np 1 --restart-np 2 --from-cycle 50 --history-bitwise)
# The deck travels in every dump's /run; a restart refuses a changed &material
# (unless --restart-force) and takes a reformatted deck.
impact3d_check(restart/deck_check "regression;parallel" restartdeck
  --workdir ${WORK}/restart_deck --deck ${DECKS}/sod_small.nml --np 2 --restart-np 1
  --from-cycle 40)
