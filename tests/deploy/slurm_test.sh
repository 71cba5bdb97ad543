#!/usr/bin/env bash
# End to end on a single-node Slurm cluster that this test starts itself
# (deploy/slurm/local-cluster.sh): submit deploy/slurm/animat.sbatch, let
# the evolution run, cancel it (scancel), resubmit, interrupt it with the
# walltime warning (SIGTERM to the batch script only), resubmit, let it
# finish; then check that the store holds exactly what an uninterrupted
# run of the same configuration holds. Then the same for a campaign of two
# runs of different drags: submitted, cancelled, resubmitted to its end;
# each store is the store of its run made alone.
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

# shellcheck source=tests/deploy/lib.sh
source "$source_dir/tests/deploy/lib.sh"

eval "$("$source_dir/deploy/slurm/local-cluster.sh" start "$cluster")"
export SLURM_CONF

write_small_config "$work/run.txtpb"

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

submit() {  # [KEYS_DIR]: with CurveZMQ keys
  ANIMAT_KEYS="${1:-}" ANIMAT_DB="$work/run.db" ANIMAT_CONFIG="$work/run.txtpb" \
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
[ "$first" -lt "$small_config_generations" ] || fail "the run finished before it was cancelled"

# 2. Resubmit; the walltime warning (SIGTERM to the batch script alone).
job=$(submit)
echo "slurm_test: job $job resubmitted"
wait_generations "$work/run.db" $((first + 3))
scancel --batch --signal=TERM "$job"
wait_job_gone "$job"
second=$(generations_done "$work/run.db")
echo "slurm_test: stopped by the walltime signal after $second generations"
[ "$second" -lt "$small_config_generations" ] || fail "the run finished before the walltime signal"
grep -q "master exited with status 0" "$work/job-$job.log" ||
  fail "the master did not exit 0 on the walltime signal"
[ "$(run_state "$work/run.db")" = running ] ||
  fail "the store does not show a resumable run"

# 3. Resubmit with CurveZMQ keys (the several-node set-up, on one node);
# let it finish.
"$bin/animat" keygen --cluster "$work/keys" > /dev/null
job=$(submit "$work/keys")
echo "slurm_test: job $job resubmitted"
wait_job_gone "$job"
[ "$(run_state "$work/run.db")" = finished ] ||
  fail "the run did not finish"
grep -q "resuming" "$work/job-$job.log" || fail "the last job did not resume"
grep -q "CurveZMQ with 1 allowed worker keys" "$work/job-$job.log" ||
  fail "the last job did not use CurveZMQ"
# The workers left by themselves when the master said the run was over.
[ "$(grep -c "exiting (--exit-when-done)" "$work/job-$job.log")" = 2 ] ||
  fail "the workers did not exit when the run finished"

# The same individuals, parents, evaluations and generations as the
# uninterrupted run.
[ "$(digest "$work/run.db")" = "$(digest "$work/reference.db")" ] ||
  fail "the interrupted run differs from the uninterrupted one"
echo "slurm_test: $(sqlite3 "$work/run.db" "SELECT COUNT(*) FROM individuals") individuals identical to the uninterrupted run"

# 4. A campaign: the small configuration, and the same at another drag.
write_two_drag_campaign "$work/campaign.txtpb"
run_d10_alone "$bin" "$work/run.txtpb" "$work/reference-d10.db"
submit_campaign() {
  ANIMAT_CAMPAIGN="$work/campaign.txtpb" ANIMAT_DIR="$work/campaign" \
    ANIMAT_BIN="$bin" ANIMAT_PORT=25556 \
    sbatch --parsable --ntasks=2 --output="$work/job-%j.log" \
      "$source_dir/deploy/slurm/animat.sbatch"
}
job=$(submit_campaign)
echo "slurm_test: campaign job $job submitted"
wait_generations "$work/campaign/c-d1.db" 3
scancel "$job"
wait_job_gone "$job"
[ "$(generations_done "$work/campaign/c-d1.db")" -lt "$small_config_generations" ] ||
  fail "the campaign finished before it was cancelled"
job=$(submit_campaign)
echo "slurm_test: campaign job $job resubmitted"
wait_job_gone "$job"
grep -q "finished: 2 runs in" "$work/job-$job.log" ||
  fail "the campaign did not finish"
expect_two_drag_stores "$work/campaign" "$work/reference.db" "$work/reference-d10.db"
echo "slurm_test: a campaign of two drags, cancelled and resubmitted, gave each run's store"
keep=0
