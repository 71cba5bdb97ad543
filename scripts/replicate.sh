#!/usr/bin/env bash
# The replication of docs/results.md: configs/paper.txtpb at three drag
# coefficients (d_N = 0.1, 1, 10, with d_T = d_N / 200) and seeds 1-4, each
# for GENERATIONS generations (default 150), one store per run in OUT
# (default out/replication). Runs go JOBS at a time (default: one per core),
# one worker each. Run it again to continue: each store resumes where it
# stopped, and a finished run is extended to GENERATIONS.
#
#   scripts/replicate.sh [--generations G] [--jobs J] [--out DIR]
#     [--seeds "1 2 3 4"] [--drags "0.1 1 10"]
set -euo pipefail
cd "$(dirname "$0")/.."

generations=150
jobs="$(nproc)"
out=out/replication
seeds="1 2 3 4"
drags="0.1 1 10"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --generations) generations="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --seeds) seeds="$2"; shift 2 ;;
    --drags) drags="$2"; shift 2 ;;
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
    name="dn${drag}-seed${seed}"
    config="$out/$name.txtpb"
    # The paper's setup with this run's seed and drag.
    sed -e "s/^  seed: 1 /  seed: $seed /" \
      -e "s/^model {}/model { physics { drag_normal: $drag drag_tangential: $tangential } }/" \
      configs/paper.txtpb > "$config"
    grep -q "drag_normal: $drag " "$config"
    grep -q "^  seed: $seed " "$config"
    runs+=("$name")
  done
done

run_one() {
  local out="$1" bin="$2" generations="$3" name="$4"
  if [[ -f "$out/$name.db" ]]; then
    "$bin/animat" evolve --db "$out/$name.db" --workers 1 \
      --generations "$generations" >> "$out/$name.log" 2>&1
  else
    "$bin/animat" evolve --config "$out/$name.txtpb" --db "$out/$name.db" \
      --workers 1 --generations "$generations" >> "$out/$name.log" 2>&1
  fi
  echo "$name: $(tail -n 1 "$out/$name.log")"
}
export -f run_one
printf '%s\n' "${runs[@]}" |
  xargs -P "$jobs" -I{} bash -c 'run_one "$@"' _ "$out" "$bin" \
    "$generations" {}
echo "stores in $out; figures: build/bin/animat figure fitness --db $out/dn1-seed1.db ..."
