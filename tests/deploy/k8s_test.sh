#!/usr/bin/env bash
# deploy/k8s/: the manifests are consistent (tests/deploy/k8s_commands.py),
# and their container commands do what the guide says when run here with
# the same files in the same roles: the master starts with CurveZMQ, a
# worker with the cluster key is served, SIGTERM (a pod's termination)
# leaves a resumable store, the next start resumes and finishes the run
# identical to an uninterrupted one, and a start after that only keeps the
# store available; the campaign overlay (deploy/k8s/campaign) the same for
# a campaign of two drags, each store equal to its run made alone. No
# Kubernetes cluster is involved.
#
#   tests/deploy/k8s_test.sh BIN_DIR
set -euo pipefail

bin=$(cd "${1:?the directory of animat, animat-master, animat-worker}" && pwd)
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
k8s="$source_dir/deploy/k8s"
commands="$source_dir/tests/deploy/k8s_commands.py"

if ! python3 -c "import yaml" 2>/dev/null; then
  echo "k8s_test: SKIPPED: needs python3-yaml"
  exit 77
fi

work=$(mktemp -d /tmp/animat-k8s-test.XXXXXX)
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill -9 "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
fail() {
  echo "k8s_test: FAILED: $*" >&2
  for f in "$work"/*.log; do
    [ -f "$f" ] && { echo "--- $f"; tail -25 "$f"; } >&2
  done
  exit 1
}
# shellcheck source=tests/deploy/lib.sh
source "$source_dir/tests/deploy/lib.sh"

python3 "$commands" "$k8s" check || fail "the manifests are inconsistent"

# The pod's files, here: the ConfigMap, the Secret (animat keygen --cluster,
# as the guide makes it) and the volume.
mkdir -p "$work/config" "$work/data"
write_small_config "$work/config/run.txtpb"
"$bin/animat" keygen --cluster "$work/keys" > /dev/null
port=$((25000 + $$ % 5000))
# The same commands with this machine's paths, port and master address.
localize() {
  sed -e "s#/data/#$work/data/#g" -e "s#/config/#$work/config/#g" \
      -e "s#/keys/#$work/keys/#g" -e "s#0\.0\.0\.0:5555#0.0.0.0:$port#g" \
      -e "s#tcp://animat-master:5555#tcp://127.0.0.1:$port#g" \
      -e "s#exec animat-master#exec $bin/animat-master#g"
}
python3 "$commands" "$k8s" master-script | localize > "$work/master.sh"
mapfile -t worker_args < <(python3 "$commands" "$k8s" worker-args | localize)
[ "${worker_args[0]}" = animat-worker ] || fail "unexpected worker command"
worker_args[0]="$bin/animat-worker"

start_master() {
  PATH="$bin:$PATH" sh "$work/master.sh" >> "$work/master.log" 2>&1 &
  master=$!
  pids+=("$master")
}

"$bin/animat" evolve --config "$work/config/run.txtpb" \
  --db "$work/reference.db" --workers 1 > "$work/reference.log" 2>&1 ||
  fail "the reference run failed"

start_master
"${worker_args[@]}" > "$work/worker.log" 2>&1 &
pids+=("$!")
wait_generations "$work/data/evolution.db" 3
kill -TERM "$master"
status=0
wait "$master" || status=$?
[ "$status" -eq 0 ] || fail "the master exited $status on SIGTERM"
[ "$(run_state "$work/data/evolution.db")" = running ] ||
  fail "no resumable run after SIGTERM"
grep -q "CurveZMQ with 1 allowed worker keys" "$work/master.log" ||
  fail "the master did not use CurveZMQ"
echo "k8s_test: terminated after $(generations_done "$work/data/evolution.db") generations"

start_master
status=0
wait "$master" || status=$?
[ "$status" -eq 0 ] || fail "the resumed master exited $status"
grep -q "resuming run 1" "$work/master.log" || fail "the restart did not resume"
[ "$(run_state "$work/data/evolution.db")" = finished ] ||
  fail "the run did not finish"
[ "$(digest "$work/data/evolution.db")" = "$(digest "$work/reference.db")" ] ||
  fail "the run differs from the uninterrupted one"
echo "k8s_test: resumed and finished identical to an uninterrupted run"

start_master
for _ in $(seq 100); do
  grep -q "has finished" "$work/master.log" && break
  sleep 0.1
done
grep -q "has finished" "$work/master.log" ||
  fail "a start after the end did not keep the store available"
kill -0 "$master" 2>/dev/null || fail "the finished pod's container exited"
echo "k8s_test: a start after the end keeps the store available"
kill -TERM "$master" 2>/dev/null || true

# The campaign overlay (deploy/k8s/campaign): its master's script, with the
# same workers, on a campaign of the small configuration at two drags.
python3 "$commands" "$k8s/campaign" check ||
  fail "the campaign's manifests are inconsistent"
mkdir -p "$work/cconfig" "$work/cdata"
cp "$work/config/run.txtpb" "$work/cconfig/run.txtpb"
write_two_drag_campaign "$work/cconfig/campaign.txtpb"
run_d10_alone "$bin" "$work/config/run.txtpb" "$work/reference-d10.db"
python3 "$commands" "$k8s/campaign" master-script |
  sed -e "s#/data#$work/cdata#g" -e "s#/config/#$work/cconfig/#g" \
      -e "s#/keys/#$work/keys/#g" -e "s#0\.0\.0\.0:5555#0.0.0.0:$port#g" \
      -e "s#exec animat-master#exec $bin/animat-master#g" \
  > "$work/campaign.sh"
start_campaign() {
  PATH="$bin:$PATH" sh "$work/campaign.sh" >> "$work/campaign.log" 2>&1 &
  master=$!
  pids+=("$master")
}
start_campaign
wait_generations "$work/cdata/c-d1.db" 3
kill -TERM "$master"
status=0
wait "$master" || status=$?
[ "$status" -eq 0 ] || fail "the campaign's master exited $status on SIGTERM"
[ "$(generations_done "$work/cdata/c-d1.db")" -lt "$small_config_generations" ] ||
  fail "the campaign finished before SIGTERM"
start_campaign
status=0
wait "$master" || status=$?
[ "$status" -eq 0 ] || fail "the restarted campaign's master exited $status"
grep -q "finished: 2 runs in" "$work/campaign.log" ||
  fail "the campaign did not finish"
expect_two_drag_stores "$work/cdata" "$work/reference.db" "$work/reference-d10.db"
echo "k8s_test: a terminated and restarted campaign gave each run's store"
start_campaign
for _ in $(seq 100); do
  grep -q "campaign in .* has finished" "$work/campaign.log" && break
  sleep 0.1
done
grep -q "campaign in .* has finished" "$work/campaign.log" ||
  fail "a start after the campaign's end did not keep the stores available"
kill -0 "$master" 2>/dev/null || fail "the finished campaign's container exited"
echo "k8s_test: a start after the campaign's end keeps the stores available"
