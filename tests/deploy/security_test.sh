#!/usr/bin/env bash
# The master's security rules (docs/security.md), end to end with the real
# programs over TCP:
#   1. beyond loopback without keys the master refuses to start;
#   2. with CurveZMQ, a worker whose key is not on the allow-list is
#      refused and logged, a listed worker is served, and the bytes on the
#      wire (recorded by a relay) carry none of the plaintext an
#      unencrypted session shows; the run equals one on loopback;
#   3. --insecure serves workers without keys, and warns.
#
#   tests/deploy/security_test.sh BIN_DIR
set -euo pipefail

bin=$(cd "${1:?the directory of animat, animat-master, animat-worker}" && pwd)
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d /tmp/animat-security-test.XXXXXX)
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill -9 "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
# No "Killed" notices from the cleanup.
set +m
fail() {
  echo "security_test: FAILED: $*" >&2
  for f in "$work"/*.log; do
    [ -f "$f" ] && { echo "--- $f"; tail -25 "$f"; } >&2
  done
  exit 1
}
# shellcheck source=tests/deploy/lib.sh
source "$source_dir/tests/deploy/lib.sh"

base=$((20000 + ($$ % 5000) * 4))
master_port=$base
relay_port=$((base + 1))
write_small_config "$work/run.txtpb"
# What an unencrypted session shows on the wire: the build id, in Hello.
build_id() {  # MASTER_LOG: the build id it announced
  sed -n 's/.*listening on .* (build \([^)]*\)).*/\1/p' "$1" | head -1
}

start_relay() {  # CAPTURE: relay_port -> master_port, recording bytes
  python3 "$source_dir/tests/deploy/tcp_relay.py" "$relay_port" \
    "$master_port" "$1" > "$work/relay.out" 2>&1 &
  relay=$!
  pids+=("$relay")
  for _ in $(seq 100); do
    grep -q ready "$work/relay.out" 2>/dev/null && return 0
    sleep 0.05
  done
  fail "the relay did not start"
}

# 1. Beyond loopback, no keys: refused, the store untouched.
status=0
"$bin/animat-master" --config "$work/run.txtpb" --db "$work/refused.db" \
  --bind "tcp://0.0.0.0:$master_port" > "$work/refused.log" 2>&1 || status=$?
[ "$status" -ne 0 ] || fail "the master listened beyond loopback without keys"
grep -q "CurveZMQ" "$work/refused.log" || fail "the refusal does not say why"
[ ! -e "$work/refused.db" ] || fail "a refused master created its store"
echo "security_test: beyond loopback without keys: refused"

# Keys: the cluster's, and a stranger's.
"$bin/animat" keygen --cluster "$work/keys" > /dev/null
"$bin/animat" keygen -o "$work/stranger" > /dev/null
[ "$(stat -c %a "$work/keys/master.key")" = 600 ] ||
  fail "the secret key file is not private"
stranger_key=$(sed -n 's/^public-key = "\(.*\)"$/\1/p' "$work/stranger.pub")

# The reference: loopback, no keys.
"$bin/animat" evolve --config "$work/run.txtpb" --db "$work/reference.db" \
  --workers 1 > "$work/reference.log" 2>&1 || fail "the reference run failed"

# 2. CurveZMQ.
start_relay "$work/curve.capture"
"$bin/animat-master" --config "$work/run.txtpb" --db "$work/curve.db" \
  --bind "tcp://0.0.0.0:$master_port" \
  --curve-secret "$work/keys/master.key" \
  --curve-allow "$work/keys/workers.allow" > "$work/master-curve.log" 2>&1 &
master=$!
pids+=("$master")
"$bin/animat-worker" --connect "tcp://127.0.0.1:$master_port" --threads 1 \
  --curve-server "$work/keys/master.pub" \
  --curve-secret "$work/stranger.key" > "$work/stranger.log" 2>&1 &
stranger=$!
pids+=("$stranger")
"$bin/animat-worker" --connect "tcp://127.0.0.1:$master_port" --threads 1 \
  > "$work/plain.log" 2>&1 &
plain=$!
pids+=("$plain")
for _ in $(seq 100); do
  grep -qF "key $stranger_key is not on the allow-list" \
    "$work/master-curve.log" &&
    break
  sleep 0.1
done
grep -qF "refused a worker from 127.0.0.1: key $stranger_key is not on the" \
  "$work/master-curve.log" || fail "the stranger's key was not logged"
sleep 1
[ "$(generations_done "$work/curve.db")" -eq 0 ] &&
  [ "$(sqlite3 "file:$work/curve.db?mode=ro" \
       "SELECT COUNT(*) FROM individuals WHERE status IS NOT NULL")" -eq 0 ] ||
  fail "a worker without an allowed key was served"
grep -q "joined" "$work/master-curve.log" &&
  fail "a worker without an allowed key joined"
echo "security_test: an unknown key and a plain worker get nothing; logged"

# The cluster worker, through the recording relay.
"$bin/animat-worker" --connect "tcp://127.0.0.1:$relay_port" --threads 1 \
  --curve-server "$work/keys/master.pub" \
  --curve-secret "$work/keys/worker.key" > "$work/known.log" 2>&1 &
pids+=("$!")
status=0
wait "$master" || status=$?
[ "$status" -eq 0 ] || fail "the CurveZMQ master exited $status"
[ "$(run_state "$work/curve.db")" = finished ] || fail "the run did not finish"
[ "$(digest "$work/curve.db")" = "$(digest "$work/reference.db")" ] ||
  fail "the CurveZMQ run differs from the loopback run"
[ -s "$work/curve.capture" ] || fail "nothing passed the relay"
marker=$(build_id "$work/master-curve.log")
[ -n "$marker" ] || fail "the master did not announce its build id"
if grep -qa "$marker" "$work/curve.capture"; then
  fail "plaintext ($marker) on the CurveZMQ wire"
fi
echo "security_test: the allowed worker was served, the run equals the" \
  "loopback run, and $(stat -c %s "$work/curve.capture") bytes on the wire" \
  "hold no plaintext"
# Gone before the next relay takes its port.
kill "$relay" 2>/dev/null || true
wait "$relay" 2>/dev/null || true

# 3. --insecure: warns, serves a worker without keys, plaintext on the wire.
start_relay "$work/plain.capture"
"$bin/animat-master" --config "$work/run.txtpb" --db "$work/insecure.db" \
  --bind "tcp://0.0.0.0:$master_port" --insecure \
  > "$work/master-insecure.log" 2>&1 &
master=$!
pids+=("$master")
"$bin/animat-worker" --connect "tcp://127.0.0.1:$relay_port" --threads 1 \
  > "$work/insecure-worker.log" 2>&1 &
pids+=("$!")
status=0
wait "$master" || status=$?
[ "$status" -eq 0 ] || fail "the --insecure master exited $status"
grep -q "WARNING: listening on tcp://0.0.0.0:$master_port without CurveZMQ" \
  "$work/master-insecure.log" || fail "--insecure did not warn"
[ "$(digest "$work/insecure.db")" = "$(digest "$work/reference.db")" ] ||
  fail "the --insecure run differs from the loopback run"
grep -qa "$marker" "$work/plain.capture" ||
  fail "the unencrypted wire lacks the plaintext marker: the check is blind"
echo "security_test: --insecure warns and serves plain workers (plaintext" \
  "visible on its wire)"
