#!/bin/bash
# Example Slurm job for impact3d: runs until the wall-time limit, leaving a
# restart dump; resubmit the same script to continue (it restarts from the
# newest dump). Adjust nodes, tasks and time to your cluster.
#SBATCH --job-name=impact3d
#SBATCH --nodes=2
#SBATCH --ntasks-per-node=32
#SBATCH --time=04:00:00
#SBATCH --output=impact3d-%j.log
set -euo pipefail
deck=problem.nml
# Leave impact3d a margin inside the allocation: it stops cleanly before this.
limit=$(( 4 * 3600 - 300 ))
latest=$(ls -1 dump_[0-9][0-9][0-9][0-9][0-9][0-9].h5 2>/dev/null | tail -n 1 || true)
if [ -n "$latest" ] && [ "$latest" != "dump_000000.h5" ]; then
  restart=(--restart "$latest")
else
  restart=()
fi
# The deck's &control should set wall_limit; here it is passed by editing a copy.
sed "s/^&control/\&control wall_limit = ${limit},/" "$deck" > deck.run.nml
set +e
srun ./impact3d "${restart[@]}" deck.run.nml
code=$?
set -e
# 0: done; 3: stopped before t_end with a restart dump (resubmit); else: failed.
if [ $code -eq 3 ]; then
  echo "impact3d stopped before t_end; resubmitting"
  sbatch "$0"
fi
exit $code
