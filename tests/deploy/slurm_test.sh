#!/usr/bin/env bash
# End to end on a single-node Slurm cluster that this test starts itself
# (deploy/slurm/local-cluster.sh): submit deploy/slurm/animat.sbatch, let
# the evolution run, cancel it (scancel), resubmit, interrupt it with the
# walltime warning (SIGTERM to the batch script only), resubmit, let it
# finish; then check that the store holds exactly what an uninterrupted
# run of the same configuration holds.
#
#   tests/deploy/slurm_test.sh BIN_DIR
#
# Exit 77 (skipped) when not root or Slurm/munge are not installed; CI
# installs them (scripts/setup.sh).
set -euo pipefail

bin=$(cd "${1:?the directory of animat, animat-master, animat-worker}" && pwd)
source_dir=$(cd "$(dirname "$0")/../.." && pwd)

if [ "$(id -u)" -ne 0 ] || ! command -v slurmctld >/dev/null ||
   ! command -v munged >/dev/null; then
  echo "slurm_test: SKIPPED: needs root, slurm-wlm and munge"
  exit 77
fi

work=$(mktemp -d /tmp/animat-slurm-test.XXXXXX)
cluster="$work/cluster"
cleanup() {
  if [ -n "${SLURM_CONF:-}" ]; then
    scancel --quiet --user root 2>/dev/null || true
  fi
  "$source_dir/deploy/slurm/local-cluster.sh" stop "$cluster" || true
  if [ "${keep:-0}" = 1 ]; then
    echo "slurm_test: files kept in $work"
  else
    rm -rf "$work"
  fi
}
trap cleanup EXIT
keep=1

fail() {
  echo "slurm_test: FAILED: $*" >&2
  for f in "$work"/*.log "$cluster"/log/*.log; do
    [ -f "$f" ] && { echo "--- $f"; tail -40 "$f"; } >&2
  done
  exit 1
}

eval "$("$source_dir/deploy/slurm/local-cluster.sh" start "$cluster")"
export SLURM_CONF

# Small enough for CI, long enough to interrupt twice (a generation takes
# a fraction of a second).
cat > "$work/run.txtpb" <<'CONF'
model { evaluation { motion_steps: 1200 } }
evolution {
  seed: 7
  population: 40
  generations: 24
  elite: 2
}
CONF

generations_done() {  # completed generations in the store, 0 if none yet
  sqlite3 "file:$1?mode=ro" \
    "SELECT COUNT(*) FROM generations WHERE completed_at IS NOT NULL" \
    2>/dev/null || echo 0
}

job_state() {  # the job's state, empty once it has left the queue
  squeue -h -j "$1" -o %T 2>/dev/null || true
}

wait_job_gone() {
  for _ in $(seq 1200); do
    [ -z "$(job_state "$1")" ] && return 0
    sleep 0.1
  done
  fail "job $1 did not end"
}

wait_generations() {  # store, at least this many completed generations
  for _ in $(seq 3000); do
    [ "$(generations_done "$1")" -ge "$2" ] && return 0
    sleep 0.1
  done
  fail "the store did not reach $2 completed generations"
}

submit() {
  ANIMAT_DB="$work/run.db" ANIMAT_CONFIG="$work/run.txtpb" \
    ANIMAT_BIN="$bin" ANIMAT_PORT=25555 \
    sbatch --parsable --ntasks=2 --output="$work/job-%j.log" \
      "$source_dir/deploy/slurm/animat.sbatch"
}

# The reference: the same configuration, uninterrupted, one local worker.
"$bin/animat" evolve --config "$work/run.txtpb" --db "$work/reference.db" \
  --workers 1 > "$work/reference.log" 2>&1 || fail "the reference run failed"

# 1. Submit; cancel mid-run.
job=$(submit)
echo "slurm_test: job $job submitted"
wait_generations "$work/run.db" 3
scancel "$job"
wait_job_gone "$job"
first=$(generations_done "$work/run.db")
echo "slurm_test: cancelled after $first generations"
[ "$first" -lt 24 ] || fail "the run finished before it was cancelled"

# 2. Resubmit; the walltime warning (SIGTERM to the batch script alone).
job=$(submit)
echo "slurm_test: job $job resubmitted"
wait_generations "$work/run.db" $((first + 3))
scancel --batch --signal=TERM "$job"
wait_job_gone "$job"
second=$(generations_done "$work/run.db")
echo "slurm_test: stopped by the walltime signal after $second generations"
[ "$second" -lt 24 ] || fail "the run finished before the walltime signal"
grep -q "master exited with status 0" "$work/job-$job.log" ||
  fail "the master did not exit 0 on the walltime signal"
[ "$(sqlite3 "$work/run.db" "SELECT state FROM runs")" = running ] ||
  fail "the store does not show a resumable run"

# 3. Resubmit; let it finish.
job=$(submit)
echo "slurm_test: job $job resubmitted"
wait_job_gone "$job"
[ "$(sqlite3 "$work/run.db" "SELECT state FROM runs")" = finished ] ||
  fail "the run did not finish"
grep -q "resuming" "$work/job-$job.log" || fail "the last job did not resume"

# The same individuals, parents, evaluations and generations as the
# uninterrupted run (wall times, workers and timestamps aside).
digest() {
  sqlite3 "file:$1?mode=ro" "
    SELECT id, generation, operators, hex(genome), status, reason,
           quote(fitness), cells, steps, state_hash FROM individuals
    ORDER BY id;
    SELECT * FROM parents ORDER BY child, position;
    SELECT generation, id, rank FROM members ORDER BY generation, id;
    SELECT generation, size, evaluated, failed, best_id,
           quote(best_fitness), quote(mean_fitness), quote(median_fitness)
    FROM generations ORDER BY generation;" | sha256sum
}
[ "$(digest "$work/run.db")" = "$(digest "$work/reference.db")" ] ||
  fail "the interrupted run differs from the uninterrupted one"
echo "slurm_test: $(sqlite3 "$work/run.db" "SELECT COUNT(*) FROM individuals") individuals identical to the uninterrupted run"
keep=0
