#!/bin/bash
# Example Slurm job for impact3d: runs until shortly before the job's time
# limit, leaves a restart dump and resubmits itself; each resubmission
# restarts from the newest dump. Adjust nodes, tasks and time to your cluster.
#
# Two independent ways to stop cleanly (restart dump, exit code 3):
# 1. Slurm sends SIGUSR1 300 s before the time limit (--signal below);
#    impact3d stops at the end of the cycle in progress.
# 2. &control wall_limit (set below from the allocation, minus a margin):
#    impact3d budgets three cycles and two dump times itself.
# The margin of either must cover one cycle plus writing one dump. Slurm may
# send the signal up to a minute earlier than asked; that costs nothing.
#
# Without "B:" Slurm signals the job steps (the processes started by srun),
# not the batch shell: every rank gets SIGUSR1 directly. That is the right
# form when the ranks are started with srun, as here.
#SBATCH --job-name=impact3d
#SBATCH --nodes=2
#SBATCH --ntasks-per-node=32
#SBATCH --time=04:00:00
#SBATCH --signal=USR1@300
#SBATCH --output=impact3d-%j.log
set -euo pipefail
deck=problem.nml
# Backup for the signal: stop cleanly 10 minutes before the limit.
limit=$(( 4 * 3600 - 600 ))
latest=$(ls -1 dump_[0-9][0-9][0-9][0-9][0-9][0-9].h5 2>/dev/null | tail -n 1 || true)
if [ -n "$latest" ] && [ "$latest" != "dump_000000.h5" ]; then
  restart=(--restart "$latest")
else
  restart=()
fi
# The deck's &control could set wall_limit itself; here it goes into a copy.
sed "s/^&control/\&control wall_limit = ${limit},/" "$deck" > deck.run.nml
set +e
srun ./impact3d "${restart[@]}" deck.run.nml
code=$?
set -e
# With mpirun instead of srun (Open MPI), ask for the signal on the batch
# shell (#SBATCH --signal=B:USR1@300) and forward it: mpirun passes SIGUSR1
# and SIGUSR2 on to every rank. Do not forward SIGTERM: Open MPI's mpirun
# answers it by sending SIGTERM to the ranks and SIGKILL one second later
# (MCA odls_base_sigkill_timeout), too soon for a restart dump. A trapped
# signal interrupts "wait", hence the loop for the real exit code (in place
# of the srun line, between set +e and set -e):
#
#   mpirun ./impact3d "${restart[@]}" deck.run.nml &
#   pid=$!
#   trap 'kill -USR1 $pid' USR1
#   wait $pid; code=$?
#   while kill -0 $pid 2>/dev/null; do wait $pid; code=$?; done
#   trap - USR1
#
# 0: done; 3: stopped before t_end with a restart dump (resubmit); else: failed.
if [ $code -eq 3 ]; then
  echo "impact3d stopped before t_end; resubmitting"
  sbatch "$0"
fi
exit $code
