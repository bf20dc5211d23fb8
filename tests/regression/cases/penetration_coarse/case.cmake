# The penetration problem's coarse deck (problems/penetration/
# penetration_coarse.nml, 1147 m/s, erosion and eroding DLM contact):
# * parallel/bitwise_penetration: its first 6 us (zones eroded in several
#   cycles by then) on 1, 2, 3 and 4 ranks, every dump and the exact history
#   columns bitwise;
# * long/penetration_coarse_20us: 20 us on 2 ranks, energy balance to 1e-10
#   and no kinetic energy beyond the initial total (check.py).
impact3d_check(parallel/bitwise_penetration "regression;parallel;contact;solids" bitwise
  --workdir ${WORK}/bitwise_penetration --deck ${PROBLEMS}/penetration/penetration_coarse.nml
  --replace "t_end = 1.0e-3" "t_end = 6.0e-6"
  --replace "file = 'penetration_coarse.msh'"
            "file = '${PROBLEMS}/penetration/penetration_coarse.msh'"
  --replace "dump_interval = 10.0e-6" "dump_interval = 2.0e-6"
  --ranks 1 2 3 4 --history --history-except _force _pen_rms _dmom_x _dmom_y _dmom_z)
impact3d_regress(long/penetration_coarse_20us "regression;contact;solids;long"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE} ${WORK}/penetration_coarse_20us
  --t-end 20.0e-6 --mpiexec ${MPIEXEC_EXECUTABLE} --np 2)
# * long/penetration_coarse_2166: the same checks at 2166 m/s to 50 us, past
#   the cycles where the contact did positive work (+55 J at 47.7 us) before
#   DLM's recovery was bounded at the audit's tolerance.
impact3d_regress(long/penetration_coarse_2166 "regression;contact;solids;long"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE} ${WORK}/penetration_coarse_2166
  --t-end 50.0e-6 --velocity 2166 --mpiexec ${MPIEXEC_EXECUTABLE} --np 2)
# * long/restart_penetration: 12 us on 2 ranks, restarted from the dump at
#   6 us (cycle 357 when written; 27 zones eroded, the surfaces rebuilt with
#   offsets measured)
#   on 3 ranks: every later dump bitwise the uninterrupted run's (eroded
#   zones turned inside out keep their density from the dump).
impact3d_check(long/restart_penetration "regression;parallel;contact;solids;long" restart
  --workdir ${WORK}/restart_penetration --deck ${PROBLEMS}/penetration/penetration_coarse.nml
  --replace "t_end = 1.0e-3" "t_end = 12.0e-6"
  --replace "file = 'penetration_coarse.msh'"
            "file = '${PROBLEMS}/penetration/penetration_coarse.msh'"
  --replace "dump_interval = 10.0e-6" "dump_interval = 3.0e-6"
  --np 2 --restart-np 3 --from-time 6.0e-6)
