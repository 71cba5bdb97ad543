#!/usr/bin/env bash
# The replication of docs/results.md: configs/paper.txtpb at three drag
# coefficients (d_N = 0.1, 1, 10, with d_T = d_N / 200) and seeds 1-4, each
# for GENERATIONS generations (default 150), one store per run in OUT
# (default out/replication). Runs go JOBS at a time (default: one per core),
# one worker each. Run it again to continue: each store resumes where it
# stopped, and a finished run is extended to GENERATIONS.
#
# --extend-to G2: a run still improving after GENERATIONS (a new best in
# its last 20 generations) continues to G2 generations.
# An arm of the experiment: --prefix NAME- names its runs NAME-dn...;
# --physics 'FIELDS' adds model.physics fields (e.g. 'contact_rule: ALL')
# and --model 'FIELDS' other model fields (e.g. 'signals { kernel_length:
# 1 }') to every run's configuration.
#
#   scripts/replicate.sh [--generations G] [--extend-to G2] [--jobs J]
#     [--out DIR] [--seeds "1 2 3 4"] [--drags "0.1 1 10"] [--prefix P]
#     [--physics FIELDS] [--model FIELDS]
set -euo pipefail
cd "$(dirname "$0")/.."

generations=150
jobs="$(nproc)"
out=out/replication
seeds="1 2 3 4"
drags="0.1 1 10"
extend_to=0
prefix=""
physics_extra=""
model_extra=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --generations) generations="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --seeds) seeds="$2"; shift 2 ;;
    --drags) drags="$2"; shift 2 ;;
    --extend-to) extend_to="$2"; shift 2 ;;
    --prefix) prefix="$2"; shift 2 ;;
    --physics) physics_extra="$2"; shift 2 ;;
    --model) model_extra="$2"; shift 2 ;;
    *) echo "replicate.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done

scripts/setup.sh
scripts/build.sh
# The runs use a copy of the binaries, made once, so that a rebuild while
# they run (or between sessions of the replication) does not change the
# simulator under them: a resume checks the build. Remove $out/bin to
# continue with a newer build (animat evolve then asks for --force).
bin="$out/bin"
mkdir -p "$out"
if [[ ! -x "$bin/animat" || ! -x "$bin/animat-worker" ]]; then
  mkdir -p "$bin"
  cp build/bin/animat build/bin/animat-worker "$bin/"
fi
echo "replicate.sh: the runs use $bin"

runs=()
# Seeds outer, drags inner: a partial replication covers every drag.
for seed in $seeds; do
  for drag in $drags; do
    tangential="$(awk -v d="$drag" 'BEGIN { printf "%.10g", d / 200 }')"
    name="${prefix}dn${drag}-seed${seed}"
    config="$out/$name.txtpb"
    # The paper's setup with this run's seed and drag (and the arm's
    # fields).
    model_fields="physics { drag_normal: $drag drag_tangential: $tangential"
    model_fields+=" $physics_extra } $model_extra"
    sed -e "s/^  seed: 1 /  seed: $seed /" \
      -e "s/^model {}/model { ${model_fields//\//\\/} }/" \
      configs/paper.txtpb > "$config"
    grep -q "drag_normal: $drag " "$config"
    grep -q "^  seed: $seed " "$config"
    runs+=("$name")
  done
done

# Generations a store holds (0 without one).
held() {
  [[ -f "$1" ]] || { echo 0; return; }
  sqlite3 "$1" "SELECT COALESCE(MAX(generation) + 1, 0) FROM individuals"
}
# 1 when the store's last 20 generations hold a new best.
improving() {
  sqlite3 "$1" "SELECT COALESCE(
    MAX(CASE WHEN generation >= (SELECT MAX(generation) FROM individuals) - 19
        THEN fitness END) >
    MAX(CASE WHEN generation < (SELECT MAX(generation) FROM individuals) - 19
        THEN fitness END), 0) FROM individuals"
}
run_one() {
  local out="$1" bin="$2" generations="$3" extend_to="$4" name="$5"
  local db="$out/$name.db"
  if [[ ! -f "$db" ]]; then
    "$bin/animat" evolve --config "$out/$name.txtpb" --db "$db" \
      --workers 1 --generations "$generations" >> "$out/$name.log" 2>&1
  elif (( $(held "$db") < generations )); then
    "$bin/animat" evolve --db "$db" --workers 1 \
      --generations "$generations" >> "$out/$name.log" 2>&1
  fi
  # Extended once it reached GENERATIONS still improving, or resumed when
  # an extension was under way.
  local n
  n="$(held "$db")"
  if (( extend_to > generations && n >= generations && n < extend_to )) &&
    { (( n > generations )) || [[ "$(improving "$db")" == 1 ]]; }; then
    echo "$name: continuing from $n to $extend_to generations" \
      >> "$out/$name.log"
    "$bin/animat" evolve --db "$db" --workers 1 \
      --generations "$extend_to" >> "$out/$name.log" 2>&1
  fi
  echo "$name: $(tail -n 1 "$out/$name.log")"
}
export -f run_one held improving
printf '%s\n' "${runs[@]}" |
  xargs -P "$jobs" -I{} bash -c 'run_one "$@"' _ "$out" "$bin" \
    "$generations" "$extend_to" {}
echo "stores in $out; figures: build/bin/animat figure fitness --db $out/dn1-seed1.db ..."
