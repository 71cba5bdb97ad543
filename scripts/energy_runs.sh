#!/usr/bin/env bash
# The energy-aware runs of docs/results.md ("Energy"): the replication's
# d_N = 1 runs (configs/paper.txtpb, drag_normal 1, drag_tangential 0.005,
# RK4 with one sub-step, the integrator those runs used) with the fitness
# DISTANCE_WITHIN_ENERGY_BUDGET (docs/model.md §10.1), seeds 1-3, each for
# GENERATIONS generations (default 150), one store per run in OUT (default
# out/energy). Everything but the fitness is the replication's, so the
# replication's dn1 runs are the distance-only side of the comparison.
# Run it again to continue: each store resumes where it stopped.
#
#   scripts/energy_runs.sh [--generations G] [--jobs J] [--out DIR]
#     [--seeds "1 2 3"] [--budget B]
set -euo pipefail
cd "$(dirname "$0")/.."

generations=150
jobs="$(nproc)"
out=out/energy
seeds="1 2 3"
budget=10000
while [[ $# -gt 0 ]]; do
  case "$1" in
    --generations) generations="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --seeds) seeds="$2"; shift 2 ;;
    --budget) budget="$2"; shift 2 ;;
    *) echo "energy_runs.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done

scripts/setup.sh
scripts/build.sh
# A copy of the binaries, made once, so that a rebuild does not change the
# simulator under the runs (a resume checks the build).
bin="$out/bin"
mkdir -p "$out"
if [[ ! -x "$bin/animat" || ! -x "$bin/animat-worker" ]]; then
  mkdir -p "$bin"
  cp build/bin/animat build/bin/animat-worker "$bin/"
fi
echo "energy_runs.sh: the runs use $bin"

runs=()
for seed in $seeds; do
  name="energy-dn1-seed${seed}"
  config="$out/$name.txtpb"
  model="model { physics { drag_normal: 1 drag_tangential: 0.005"
  model+=" integrator: RK4 substeps: 1 }"
  model+=" evaluation { fitness: DISTANCE_WITHIN_ENERGY_BUDGET"
  model+=" energy_budget: $budget } }"
  sed -e "s/^  seed: 1 /  seed: $seed /" -e "s/^model {}/$model/" \
    configs/paper.txtpb > "$config"
  grep -q "DISTANCE_WITHIN_ENERGY_BUDGET" "$config"
  grep -q "^  seed: $seed " "$config"
  runs+=("$name")
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
echo "stores in $out"
