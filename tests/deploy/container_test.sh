#!/usr/bin/env bash
# deploy/container/Dockerfile and deploy/k8s/ in a real container engine
# (podman): the image is built, and its containers run the manifests'
# commands with what the pods have: the master as uid/gid 10001 with a
# named volume at /data, the ConfigMap at /config and its items of the
# Secret (`animat keygen --cluster`, mode 0440, group 10001) at /keys; two
# workers with theirs, finding the master by its Service name
# (animat-master:5555) in a network namespace of their own with loopback
# only. `podman stop` (SIGTERM, as a pod's deletion) leaves a resumable
# store; a new master container on the volume resumes and finishes the run
# identical to an uninterrupted one; a start after the end stays up, and
# `animat lineage best` answers through `podman exec`. No Kubernetes.
#
# The image: by default the Dockerfile's runtime stage (from its last FROM)
# with BIN_DIR's programs in place of the build stage's, about a minute;
# with ANIMAT_CONTAINER_FULL_BUILD=1 the whole Dockerfile as the guide
# builds it, compiling inside: 3 to 5 minutes on 2 cores, too long to add
# to every CI run (its layers stay in podman's build cache). The base
# images (debian:bookworm, bookworm-slim): those podman has, else pulled;
# where no registry is reached, made from Debian's packages with
# debootstrap and imported as localhost/debian:... (kept for the next run,
# as a pulled one would be).
#
# Where crun refuses the machine's cgroups ("cgroups in hybrid mode not
# supported") runc is used, and the rlimits are passed explicitly where
# root cannot raise them to podman's defaults (no CAP_SYS_RESOURCE).
#
#   tests/deploy/container_test.sh BIN_DIR
#
# Exit 77 (skipped) without root, podman, network namespaces or a base
# image.
set -euo pipefail

bin=$(cd "${1:?the directory of animat, animat-master, animat-worker}" && pwd)
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
dockerfile="$source_dir/deploy/container/Dockerfile"
commands="$source_dir/tests/deploy/k8s_commands.py"
tag=$(( $$ % 10000 ))
ns="animat-c$tag"
image="localhost/animat-container-test:$tag"
store="animat-store-$tag"

skip() {
  echo "container_test: SKIPPED: $*"
  exit 77
}
[ "$(id -u)" -eq 0 ] || skip "needs root"
# A sanitizer build's programs need its runtime libraries, which the
# image (as the Dockerfile makes it) does not have.
if ldd "$bin/animat-worker" 2>/dev/null | grep -qE 'lib(asan|ubsan|tsan|lsan)'; then
  skip "a sanitizer build: the image has no sanitizer runtime"
fi
command -v podman >/dev/null || skip "needs podman (and runc, debootstrap)"
python3 -c "import yaml" 2>/dev/null || skip "needs python3-yaml"
ip netns add "$ns" 2>/dev/null || skip "needs iproute2 and network namespaces"

work=$(mktemp -d /tmp/animat-container-test.XXXXXX)
engine=(podman)
cleanup() {
  "${engine[@]}" rm -f -t 0 "animat-master-$tag" "animat-worker1-$tag" \
    "animat-worker2-$tag" > /dev/null 2>&1 || true
  "${engine[@]}" volume rm -f "$store" > /dev/null 2>&1 || true
  "${engine[@]}" rmi -f "$image" > /dev/null 2>&1 || true
  ip netns del "$ns" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
fail() {
  echo "container_test: FAILED: $*" >&2
  for c in master worker1; do
    "${engine[@]}" logs "animat-$c-$tag" > "$work/$c.log" 2>&1 || true
  done
  for f in "$work"/*.log; do
    [ -f "$f" ] && { echo "--- $f"; tail -25 "$f"; } >&2
  done
  exit 1
}
# shellcheck source=tests/deploy/lib.sh
source "$source_dir/tests/deploy/lib.sh"

# The base images.
full=${ANIMAT_CONTAINER_FULL_BUILD:-0}
bases=(debian:bookworm-slim)
[ "$full" = 1 ] && bases+=(debian:bookworm)
for base in "${bases[@]}"; do
  podman image exists "$base" && continue
  timeout 120 podman pull -q "$base" > "$work/pull.log" 2>&1 && continue
  command -v debootstrap >/dev/null ||
    skip "no $base: no registry reached and no debootstrap"
  if [ ! -d "$work/rootfs" ]; then
    echo "container_test: making $base with debootstrap"
    nice -n 10 debootstrap --variant=minbase bookworm "$work/rootfs" \
      > "$work/debootstrap.log" 2>&1 || skip "debootstrap failed"
    rm -rf "$work/rootfs/var/lib/apt/lists/"* \
      "$work/rootfs/var/cache/apt/archives/"*.deb
  fi
  tar -C "$work/rootfs" -c . | podman import -q - "localhost/$base" \
    > /dev/null || fail "podman import of $base failed"
done

# Which runtime and rlimits run a container here.
run_flags=()
for runtime in "" runc; do
  [ -n "$runtime" ] && ! command -v "$runtime" >/dev/null && continue
  for nproc in "$(ulimit -Hu)" 32768; do
    flags=(--ulimit "nofile=$(ulimit -Hn):$(ulimit -Hn)"
           --ulimit "nproc=$nproc:$nproc")
    engine=(podman)
    [ -n "$runtime" ] && engine+=(--runtime "$runtime")
    if "${engine[@]}" run --rm "${flags[@]}" --network none \
         debian:bookworm-slim true > "$work/probe.log" 2>&1; then
      run_flags=("${flags[@]}")
      break 2
    fi
  done
done
[ ${#run_flags[@]} -gt 0 ] ||
  skip "podman cannot run a container here: $(tail -1 "$work/probe.log")"
echo "container_test: ${engine[*]} ${run_flags[*]}"

# The image.
start=$SECONDS
if [ "$full" = 1 ]; then
  context="$source_dir"
  containerfile="$dockerfile"
else
  context="$work/context"
  containerfile="$context/Dockerfile"
  mkdir -p "$context/bin"
  cp "$bin/animat" "$bin/animat-master" "$bin/animat-worker" "$context/bin/"
  copy='COPY --from=build /opt/animat/ /usr/local/'
  grep -qxF "$copy" "$dockerfile" || fail "the Dockerfile lacks '$copy'"
  awk -v copy="$copy" '
    /^FROM / { stage = "" }
    { stage = stage ($0 == copy ? "COPY bin/ /usr/local/bin/" : $0) "\n" }
    END { printf "%s", stage }' "$dockerfile" > "$containerfile"
fi
nice -n 10 "${engine[@]}" build "${run_flags[@]}" --network host \
  -f "$containerfile" -t "$image" "$context" > "$work/build.log" 2>&1 ||
  fail "the image did not build"
echo "container_test: image built in $((SECONDS - start)) s" \
  "($([ "$full" = 1 ] && echo "whole Dockerfile" || echo "runtime stage"))"
run() { "${engine[@]}" run "${run_flags[@]}" "$@"; }
[ "$(run --rm --network none "$image" id -u):$(run --rm --network none \
  "$image" id -g)" = 10001:10001 ] || fail "the image's user is not 10001:10001"

# The pods' files: the ConfigMap, the Secret's items and the volume.
mkdir "$work/config"
cat > "$work/config/run.txtpb" <<'CONF'
model { evaluation { motion_steps: 1200 } }
evolution {
  seed: 7
  population: 40
  generations: 60
  elite: 2
}
CONF
"$bin/animat" keygen --cluster "$work/keys" > /dev/null
mkdir "$work/master-keys" "$work/worker-keys"
cp "$work/keys/master.key" "$work/keys/workers.allow" "$work/master-keys/"
cp "$work/keys/master.pub" "$work/keys/worker.key" "$work/worker-keys/"
chgrp -R 10001 "$work/master-keys" "$work/worker-keys"
chmod 0440 "$work/master-keys/master.key" "$work/worker-keys/worker.key"
chmod 0644 "$work/master-keys/workers.allow" "$work/worker-keys/master.pub"
"${engine[@]}" volume create "$store" > /dev/null
db="$("${engine[@]}" volume inspect "$store" --format '{{.Mountpoint}}')/evolution.db"
ip -n "$ns" link set lo up

python3 "$commands" "$source_dir/deploy/k8s" check > /dev/null ||
  fail "the manifests are inconsistent"
script=$(python3 "$commands" "$source_dir/deploy/k8s" master-script)
mapfile -t worker_args < <(python3 "$commands" "$source_dir/deploy/k8s" worker-args)
pod=(--network "ns:/run/netns/$ns" --add-host animat-master:127.0.0.1
     --user 10001:10001)
start_master() {
  "${engine[@]}" rm -f -t 0 "animat-master-$tag" > /dev/null 2>&1 || true
  run -d --name "animat-master-$tag" "${pod[@]}" -v "$store:/data" \
    -v "$work/config:/config:ro" -v "$work/master-keys:/keys:ro" \
    "$image" /bin/sh -c "$script" > /dev/null || fail "the master did not start"
}
logged() {  # PATTERN: the master's log has it
  "${engine[@]}" logs "animat-master-$tag" > "$work/master.log" 2>&1
  grep -q "$1" "$work/master.log"
}

"$bin/animat" evolve --config "$work/config/run.txtpb" \
  --db "$work/reference.db" --workers 1 > "$work/reference.log" 2>&1 ||
  fail "the reference run failed"

start_master
for n in 1 2; do
  run -d --name "animat-worker$n-$tag" "${pod[@]}" \
    -v "$work/worker-keys:/keys:ro" "$image" "${worker_args[@]}" > /dev/null ||
    fail "worker $n did not start"
done
wait_generations "$db" 3
"${engine[@]}" stop -t 60 "animat-master-$tag" > /dev/null
status=$("${engine[@]}" inspect "animat-master-$tag" --format '{{.State.ExitCode}}')
[ "$status" -eq 0 ] || fail "the master exited $status on SIGTERM"
[ "$(run_state "$db")" = running ] || fail "no resumable run after SIGTERM"
logged "CurveZMQ with 1 allowed worker keys" ||
  fail "the master did not use CurveZMQ"
joined=$(grep -c "joined" "$work/master.log" || true)
[ "$joined" -eq 2 ] || fail "expected both workers to join, saw $joined"
echo "container_test: stopped after $(generations_done "$db") generations"

start_master
status=$(timeout 240 "${engine[@]}" wait "animat-master-$tag") ||
  fail "the resumed master did not end"
[ "$status" -eq 0 ] || fail "the resumed master exited $status"
logged "resuming run 1" || fail "the new master did not resume"
[ "$(run_state "$db")" = finished ] || fail "the run did not finish"
[ "$(digest "$db")" = "$(digest "$work/reference.db")" ] ||
  fail "the run differs from the uninterrupted one"
echo "container_test: resumed and finished identical to an uninterrupted run"

start_master
for _ in $(seq 100); do
  logged "has finished" && break
  sleep 0.1
done
logged "has finished" ||
  fail "a start after the end did not keep the store available"
[ "$("${engine[@]}" inspect "animat-master-$tag" --format '{{.State.Running}}')" = true ] ||
  fail "the finished master's container exited"
"${engine[@]}" exec "animat-master-$tag" animat lineage best \
  --db /data/evolution.db > "$work/best.txt" || fail "lineage best failed"
"$bin/animat" lineage best --db "$work/reference.db" > "$work/reference-best.txt"
cmp -s "$work/best.txt" "$work/reference-best.txt" ||
  fail "lineage best in the container differs from the reference's"
echo "container_test: $(head -1 "$work/best.txt"); the finished master stays up"
