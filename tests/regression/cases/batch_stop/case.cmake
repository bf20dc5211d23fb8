# --- Batch use: a STOP file, signals and the wall-time limit (issue 7 item 5).
# A STOP file stops the run cleanly with a restart dump (exit 3); the restart
# on another rank count ends bitwise identical.
impact3d_check(restart/stop_file "regression;parallel" stopfile --workdir ${WORK}/stop_file
  --deck ${DECKS}/sedov_small.nml --np 2 --restart-np 3)
# Sedov octant at 18^3 (long enough for a signal to land mid-run), a status
# line every 10 cycles (the signal is sent after the first one). Each test:
# exit code 3 with a restart dump, restarted on 3 ranks ends bitwise identical
# to the uninterrupted run (h5diff, /run excluded).
set(BATCH_VARIANT --replace "nx = 12" "nx = 18" --replace "ny = 12" "ny = 18"
  --replace "nz = 12" "nz = 18" --replace "status_every = 1000" "status_every = 10")
# SIGUSR1 to mpirun, which forwards it to every rank.
impact3d_check(restart/signal_usr1 "regression;parallel" signal --workdir ${WORK}/signal_usr1
  --deck ${DECKS}/sedov_small.nml --np 2 --restart-np 3 --signal USR1 --to mpirun
  ${BATCH_VARIANT})
# SIGTERM to one rank only (not rank 0): the stop request still reaches every rank.
impact3d_check(restart/signal_term_one_rank "regression;parallel" signal
  --workdir ${WORK}/signal_term --deck ${DECKS}/sedov_small.nml --np 2 --restart-np 3
  --signal TERM --to rank ${BATCH_VARIANT})
# &control wall_limit = 1 s + a third of the uninterrupted run's time (smaller
# again if the run still finishes): stops before the end, and before the limit.
impact3d_check(restart/wall_limit "regression;parallel" walllimit --workdir ${WORK}/wall_limit
  --deck ${DECKS}/sedov_small.nml --np 2 --restart-np 3 ${BATCH_VARIANT})
