#!/bin/bash
# Tutorial 8: a scaling study handed to a cluster's launcher (Slurm's srun), and the same script run
# here with mpiexec.
#
#   sbatch tutorials/ex08_scaling_on_a_cluster.sh        # on a Slurm cluster, from the source folder
#   LAUNCHER=mpiexec RANKS=1,2 STEPS=5 REPEATS=1 PYTHON=/usr/bin/python3 bash tutorials/ex08_scaling_on_a_cluster.sh   # here, in seconds
#   /usr/bin/python3 scripts/study_scaling.py --help     # what the study does and all of its flags
#
# 1. The allocation. sbatch reads the #SBATCH lines below (up to the first command); edit the node
#    count, the tasks per node (one MPI rank per core) and the time limit for your machine. The study
#    runs one job step after the other inside this allocation, from 1 rank up to all its tasks.
#    A line starting with ##SBATCH is ignored: remove one # to use it.
#SBATCH --job-name=burst-scaling
#SBATCH --nodes=2
#SBATCH --ntasks-per-node=32
#SBATCH --cpus-per-task=1
#SBATCH --time=00:30:00
#SBATCH --output=burst-scaling-%j.out
##SBATCH --partition=<partition>
##SBATCH --account=<account>
##SBATCH --exclusive
#
# 2. The environment: the same MPI and PETSc that build/burst was built with (scripts/build.sh),
#    e.g. "module load openmpi petsc" on your cluster, and a Python with numpy and matplotlib.
#
# 3. The launcher. scripts/study_scaling.py takes the launch command as a template with {n} for the
#    rank count (--launcher) and runs every point through it: with LAUNCHER=srun (the default here)
#    each point is a job step "srun --ntasks=n --cpu-bind=cores build/burst ..." inside the
#    allocation, one rank included (--launch-one: an MPI built for Slurm may not start without srun);
#    LAUNCHER=mpiexec is Open MPI's launcher on this machine; any other value is taken as the template
#    itself, e.g. LAUNCHER="mpirun -np {n} --bind-to core". By hand, one point of the study is
#      srun --ntasks=8 --cpu-bind=cores build/burst -options_file tests/decks/taylor3d.opts -max_steps 150 -output_dir output/ex08_np8
#    and its stepping time (without set-up and output) is wall_time_s in output/ex08_np8/summary.json.
#
# 4. The study (RANKS, SCENES, KINDS, STEPS, REPEATS, CHECK_RANKS, EXTRA, OUT below; each can be given
#    in the environment, which sbatch passes on: RANKS=1,4,16 sbatch tutorials/ex08_scaling_on_a_cluster.sh):
#    - strong: the same problem on each rank count: speed-up T(1)/T(n) and efficiency T(1)/(n T(n));
#    - weak: the cells refined with the ranks (about the same particles per rank): efficiency as the
#      particle-steps per second per core against one rank's;
#    - balance: the largest rank count without and with -grid_balance (the particle work's imbalance);
#    - check: each of CHECK_RANKS against one rank: the energies, momentum and mass must agree to
#      round-off ("same to round-off"); this script fails when one prints DIFFERENT.
#    The Taylor deck (tests/decks/taylor3d.opts, 3-D, 21 866 particles at 0.5 mm) is small for many
#    ranks (at 64, about 340 particles each): strong scaling flattens once the exchange between ranks
#    costs as much as a rank's particles. For strong scaling on many nodes make it larger, e.g.
#      KINDS=strong EXTRA="-grid_cell_size 2.5e-4,2.5e-4,2.5e-4" sbatch tutorials/ex08_scaling_on_a_cluster.sh
#    (8 x the particles; with weak scaling EXTRA would override the refined cells). Add -grid_balance
#    to EXTRA on several ranks (doc/performance.md: 80-89 % efficiency on 2 ranks with it).
#
# 5. The result, in OUT: scaling.csv (one row per scene, kind and rank count), checks.csv, scaling.png
#    (speed-up and efficiency against ranks) and study.log (what the study printed).
set -euo pipefail

# the source folder: this script's parent, or under sbatch (which runs a copy of the script) the folder
# it was submitted from
ROOT=$(cd "$(dirname "$0")/.." && pwd)
[ -f "$ROOT/scripts/study_scaling.py" ] || ROOT=${SLURM_SUBMIT_DIR:-$PWD}
cd "$ROOT"
if [ ! -f scripts/study_scaling.py ]; then
  echo "ex08: run from (or submit from) burst's source folder; $ROOT has no scripts/study_scaling.py" >&2
  exit 2
fi

BURST=${BURST:-build/burst}
PYTHON=${PYTHON:-python3}
LAUNCHER=${LAUNCHER:-srun}
NTASKS=${SLURM_NTASKS:-2}
# rank counts 1, 2, 4, ... up to the allocation's tasks (and the allocation itself when not a power of 2)
default_ranks() {
  local n=1 list=""
  while [ "$n" -lt "$NTASKS" ]; do list="$list$n,"; n=$((2 * n)); done
  echo "$list$NTASKS"
}
RANKS=${RANKS:-$(default_ranks)}
SCENES=${SCENES:-taylor}
KINDS=${KINDS:-strong,weak}
STEPS=${STEPS:-0}             # 0: the scene's own (Taylor 150 steps)
REPEATS=${REPEATS:-2}         # runs per point, the fastest kept
CHECK_RANKS=${CHECK_RANKS-$NTASKS}   # "" for no check
EXTRA=${EXTRA:-}
OUT=${OUT:-output/ex08_scaling${SLURM_JOB_ID:+_$SLURM_JOB_ID}}

LAUNCH_ONE=""
case "$LAUNCHER" in
  srun) TEMPLATE="srun --ntasks={n} --cpu-bind=cores"; LAUNCH_ONE=--launch-one ;;
  mpiexec) TEMPLATE="mpiexec --allow-run-as-root --oversubscribe -x OMP_NUM_THREADS=1 -n {n}" ;;
  *{n}*) TEMPLATE=$LAUNCHER ;;
  *) echo "ex08: LAUNCHER is srun, mpiexec or a template with {n}, not '$LAUNCHER'" >&2; exit 2 ;;
esac

mkdir -p "$OUT"
echo "ex08: ranks $RANKS, scenes $SCENES, kinds $KINDS, launcher: $TEMPLATE"
"$PYTHON" scripts/study_scaling.py --burst "$BURST" --launcher="$TEMPLATE" $LAUNCH_ONE --ranks="$RANKS" \
  --scenes="$SCENES" --kinds="$KINDS" --steps="$STEPS" --repeats="$REPEATS" --check-ranks="$CHECK_RANKS" \
  --extra="$EXTRA" --out="$OUT" 2>&1 | tee "$OUT/study.log"
if grep -q DIFFERENT "$OUT/study.log"; then
  echo "ex08: FAIL: a rank count gave a different answer from one rank (see $OUT/study.log)"
  exit 1
fi
if [ -n "$CHECK_RANKS" ] && ! grep -q "same to round-off" "$OUT/study.log"; then
  echo "ex08: FAIL: no rank-count check was printed (see $OUT/study.log)"
  exit 1
fi
echo "ex08: OK; wrote $OUT/scaling.csv, $OUT/scaling.png"
