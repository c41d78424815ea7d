#!/bin/bash
# A touchdown sweep over a Slurm cluster: one MPI rank per node, each running one worker process
# per core it was given (the hybrid layout of `touchdown sweep`: -j is the workers of a rank).
# Rank 0 hands out the points one at a time to every free worker of every node, its own included,
# and writes the table; each rank records its rows in PREFIX.journal.rank-K as they end, so the
# same script submitted again after a time limit or a lost node runs only the points left.
#
#   sbatch examples/slurm-sweep.sh            (edit the #SBATCH lines and the sweep below first)
#
# Needs touchdown built with MPI (`touchdown --version` says "built with MPI"), the same build and
# the case files on every node, and the output directory on a file system every node sees (the
# parts are written there, and rank 0 reads them all at the end).
#SBATCH --job-name=touchdown-sweep
#SBATCH --nodes=4
#SBATCH --ntasks-per-node=1
#SBATCH --cpus-per-task=32
#SBATCH --time=02:00:00
#SBATCH --output=touchdown-sweep-%j.log
set -euo pipefail

touchdown=${TOUCHDOWN:-touchdown}
case_file=${CASE:-cases/rub-damped.cfg}
prefix=${PREFIX:-out/rub-map}
mkdir -p "$(dirname "$prefix")"

# 100 speeds x 100 unbalance steps = 10,000 points, each the case to its own end (2 s simulated,
# about half a second of a core; docs/performance.md, "Sweeps", predicts some 45 s on 4 x 32
# cores); --progress prints a line every 5 s into the job's log (the ETA is there); --json the
# counts, check_time and merge_time at the end.
# srun starts the ranks (PMIx or PMI2, whichever the cluster's Slurm offers); with a cluster whose
# Open MPI is not built against Slurm's PMI, replace `srun --mpi=pmix` by
# `mpirun --map-by ppr:1:node:pe=$SLURM_CPUS_PER_TASK`.
srun --mpi=pmix "$touchdown" sweep -j "$SLURM_CPUS_PER_TASK" --progress --json \
    --vary speed=60:150:100 --vary 'schedule[0].magnitude=0.02:0.2:100' \
    -o "$prefix" "$case_file"
