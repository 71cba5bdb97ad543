#!/usr/bin/env bash
# Several hosts on one machine: the master and two workers each in a
# network namespace of its own, joined by veth pairs (10.77.X.0/24), the
# master listening on its addresses with CurveZMQ. Mid-run one worker's
# link is cut; its leases must go back to the queue and be served by the
# other worker, and the run must end with exactly the individuals of an
# uninterrupted run on one host.
#
#   tests/deploy/netns_test.sh BIN_DIR
#
# Exit 77 (skipped) without root or the right to make namespaces.
set -euo pipefail

bin=$(cd "${1:?the directory of animat, animat-master, animat-worker}" && pwd)
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
tag=$(( $$ % 10000 ))
ns_master="animat-m$tag" ns_w1="animat-a$tag" ns_w2="animat-b$tag"

if [ "$(id -u)" -ne 0 ] || ! command -v ip >/dev/null ||
   ! ip netns add "$ns_master" 2>/dev/null; then
  echo "netns_test: SKIPPED: needs root, iproute2 and network namespaces"
  exit 77
fi

work=$(mktemp -d /tmp/animat-netns-test.XXXXXX)
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill -9 "$pid" 2>/dev/null || true; done
  for ns in "$ns_master" "$ns_w1" "$ns_w2"; do
    ip netns del "$ns" 2>/dev/null || true
  done
  rm -rf "$work"
}
trap cleanup EXIT
set +m
fail() {
  echo "netns_test: FAILED: $*" >&2
  for f in "$work"/*.log; do
    [ -f "$f" ] && { echo "--- $f"; tail -25 "$f"; } >&2
  done
  exit 1
}
# shellcheck source=tests/deploy/lib.sh
source "$source_dir/tests/deploy/lib.sh"

# The network: master <-> worker 1 on 10.77.1.0/24, master <-> worker 2
# on 10.77.2.0/24; the master's ends are m1-TAG and m2-TAG.
ip netns add "$ns_w1"
ip netns add "$ns_w2"
link() {  # NS_WORKER SUBNET MASTER_END WORKER_END
  ip link add "$3" netns "$ns_master" type veth peer name "$4" netns "$1"
  ip -n "$ns_master" addr add "10.77.$2.1/24" dev "$3"
  ip -n "$1" addr add "10.77.$2.2/24" dev "$4"
  ip -n "$ns_master" link set "$3" up
  ip -n "$1" link set "$4" up
  ip -n "$1" link set lo up
}
ip -n "$ns_master" link set lo up
link "$ns_w1" 1 "m1-$tag" "w1-$tag"
link "$ns_w2" 2 "m2-$tag" "w2-$tag"

# Long enough for the cut to land mid-run.
cat > "$work/run.txtpb" <<'CONF'
model { evaluation { motion_steps: 1200 } }
evolution {
  seed: 11
  population: 60
  generations: 16
  elite: 2
}
CONF
"$bin/animat" keygen --cluster "$work/keys" > /dev/null
"$bin/animat" evolve --config "$work/run.txtpb" --db "$work/reference.db" \
  --workers 1 > "$work/reference.log" 2>&1 || fail "the reference run failed"

ip netns exec "$ns_master" "$bin/animat-master" --config "$work/run.txtpb" \
  --db "$work/run.db" --bind "tcp://*:5555" --heartbeat-ms 500 \
  --curve-secret "$work/keys/master.key" \
  --curve-allow "$work/keys/workers.allow" > "$work/master.log" 2>&1 &
master=$!
pids+=("$master")
for n in 1 2; do
  ns_var="ns_w$n"
  ip netns exec "${!ns_var}" "$bin/animat-worker" \
    --connect "tcp://10.77.$n.1:5555" --threads 1 \
    --curve-server "$work/keys/master.pub" \
    --curve-secret "$work/keys/worker.key" > "$work/worker$n.log" 2>&1 &
  pids+=("$!")
done

wait_generations "$work/run.db" 2
joined=$(grep -c "joined" "$work/master.log" || true)
[ "$joined" -eq 2 ] || fail "expected both workers to join, saw $joined"
# Cut worker 1's link while it holds work.
ip -n "$ns_master" link set "m1-$tag" down
cut_at=$(generations_done "$work/run.db")
echo "netns_test: cut worker 1's link after $cut_at generations"

status=0
wait "$master" || status=$?
[ "$status" -eq 0 ] || fail "the master exited $status"
grep -q "silent for .* leases back in the queue" "$work/master.log" ||
  fail "the master did not notice the lost worker"
[ "$cut_at" -lt 16 ] || fail "the run ended before the cut"
[ "$(run_state "$work/run.db")" = finished ] || fail "the run did not finish"
[ "$(digest "$work/run.db")" = "$(digest "$work/reference.db")" ] ||
  fail "the run over namespaces differs from the one-host run"
echo "netns_test: $(grep -o "silent for .* leases back in the queue" \
  "$work/master.log" | head -1); the run equals the one-host run"
