#!/usr/bin/env bash
# deploy/systemd/: the unit files pass `systemd-analyze verify` (no error,
# no warning), and their ExecStart lines do what the guide says, run as
# systemd would run them: the master's starts a run, resumes it after
# SIGTERM (its KillSignal), and the run ends identical to an uninterrupted
# one; the worker's serves it. The campaign's unit does the same for a
# campaign of two drags, each store equal to its run made alone.
#
#   tests/deploy/systemd_test.sh BIN_DIR
#
# Exit 77 (skipped) without systemd-analyze; CI installs it.
set -euo pipefail

bin=$(cd "${1:?the directory of animat, animat-master, animat-worker}" && pwd)
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
units="$source_dir/deploy/systemd"

if ! command -v systemd-analyze >/dev/null; then
  echo "systemd_test: SKIPPED: needs systemd-analyze (package systemd)"
  exit 77
fi

work=$(mktemp -d /tmp/animat-systemd-test.XXXXXX)
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill -9 "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
fail() {
  echo "systemd_test: FAILED: $*" >&2
  for f in "$work"/*.log; do
    [ -f "$f" ] && { echo "--- $f"; tail -30 "$f"; } >&2
  done
  exit 1
}
# shellcheck source=tests/deploy/lib.sh
source "$source_dir/tests/deploy/lib.sh"

# 1. verify, with the programs where this build has them.
mkdir -p "$work/units"
for unit in animat-master.service animat-campaign.service \
            animat-worker@.service; do
  sed "s#/usr/local/bin/#$bin/#g" "$units/$unit" > "$work/units/$unit"
done
cp "$work/units/animat-worker@.service" "$work/units/animat-worker@1.service"
for unit in animat-master.service animat-campaign.service \
            animat-worker@.service animat-worker@1.service; do
  if ! out=$(cd "$work/units" && systemd-analyze verify "./$unit" 2>&1); then
    fail "systemd-analyze verify $unit: $out"
  fi
  [ -z "$out" ] || fail "systemd-analyze verify $unit warns: $out"
done
echo "systemd_test: the units pass systemd-analyze verify"

# 2. The ExecStart lines, with the environment files the guide writes.
exec_start() {  # UNIT: its ExecStart command line, for sh
  sed -n 's/^ExecStart=//p' "$work/units/$1"
}
master_cmd=$(exec_start animat-master.service)
worker_cmd=$(exec_start animat-worker@.service)
[[ "$master_cmd" == "/bin/sh -c '"*"'" ]] ||
  fail "the master's ExecStart is not the /bin/sh -c '...' the test expects"
master_script=${master_cmd#/bin/sh -c \'}
master_script=${master_script%\'}

write_small_config "$work/run.txtpb"
port=$((20000 + $$ % 20000))
export ANIMAT_CONFIG="$work/run.txtpb" ANIMAT_DB="$work/run.db" \
       ANIMAT_BIND="tcp://127.0.0.1:$port"
ANIMAT_MASTER="tcp://127.0.0.1:$port"

start_master() {
  sh -c "$master_script" >> "$work/master.log" 2>&1 &
  master=$!
  pids+=("$master")
}
# systemd expands ${ANIMAT_MASTER} from the environment file.
eval "exec ${worker_cmd//\$\{ANIMAT_MASTER\}/$ANIMAT_MASTER}" \
  >> "$work/worker.log" 2>&1 &
pids+=("$!")
worker=$!

"$bin/animat" evolve --config "$work/run.txtpb" --db "$work/reference.db" \
  --workers 1 > "$work/reference.log" 2>&1 || fail "the reference run failed"

start_master
wait_generations "$work/run.db" 3
kill -TERM "$master"
status=0
wait "$master" || status=$?
[ "$status" -eq 0 ] || fail "the master exited $status on SIGTERM, not 0"
stopped=$(generations_done "$work/run.db")
[ "$stopped" -lt "$small_config_generations" ] ||
  fail "the run finished before SIGTERM"
[ "$(run_state "$work/run.db")" = running ] || fail "no resumable run"
echo "systemd_test: stopped after $stopped generations; starting again"

start_master
status=0
wait "$master" || status=$?
[ "$status" -eq 0 ] || fail "the resumed master exited $status"
[ "$(run_state "$work/run.db")" = finished ] || fail "the run did not finish"
[ "$(digest "$work/run.db")" = "$(digest "$work/reference.db")" ] ||
  fail "the stopped and restarted run differs from the uninterrupted one"
echo "systemd_test: the restarted run equals the uninterrupted one"

# 3. The campaign's unit: two runs (the small configuration at two drags),
# stopped with SIGTERM mid-way, started again to the end, with the same
# worker.
write_two_drag_campaign "$work/campaign.txtpb"
run_d10_alone "$bin" "$work/run.txtpb" "$work/reference-d10.db"
campaign_cmd=$(exec_start animat-campaign.service)
export ANIMAT_CAMPAIGN="$work/campaign.txtpb" ANIMAT_DIR="$work/campaign"
start_campaign() {
  # systemd expands ${VAR} from the environment file: eval does here.
  eval "exec $campaign_cmd" >> "$work/campaign.log" 2>&1 &
  master=$!
  pids+=("$master")
}
start_campaign
wait_generations "$work/campaign/c-d1.db" 3
kill -TERM "$master"
status=0
wait "$master" || status=$?
[ "$status" -eq 0 ] || fail "the campaign exited $status on SIGTERM, not 0"
[ "$(generations_done "$work/campaign/c-d1.db")" -lt "$small_config_generations" ] ||
  fail "the campaign finished before SIGTERM"
start_campaign
status=0
wait "$master" || status=$?
[ "$status" -eq 0 ] || fail "the restarted campaign exited $status"
grep -q "finished: 2 runs in" "$work/campaign.log" ||
  fail "the campaign did not finish"
expect_two_drag_stores "$work/campaign" "$work/reference.db" "$work/reference-d10.db"
echo "systemd_test: the stopped and restarted campaign gave each run's store"

kill -TERM "$worker"
status=0
wait "$worker" || status=$?
[ "$status" -eq 0 ] || fail "the worker exited $status on SIGTERM, not 0"
