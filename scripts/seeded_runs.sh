#!/usr/bin/env bash
# One run configuration evolved with several seeds: for each seed S, the
# configuration with its `seed:` line set to S, one store NAME-seedS.db per
# run in OUT (default out/NAME), JOBS runs at a time (default: one per
# core), one worker each, for the configuration's generations or
# GENERATIONS. Run it again to continue: each store resumes where it
# stopped, and a finished run is extended to GENERATIONS.
#
#   scripts/seeded_runs.sh --config FILE --name NAME [--generations G]
#     [--jobs J] [--out DIR] [--seeds "1 2 3"]
#
# The runs of docs/results.md "Energy" and "Active guidance":
#   scripts/seeded_runs.sh --config configs/energy.txtpb --name energy-dn1
#   scripts/seeded_runs.sh --config configs/guidance.txtpb --name guidance
set -euo pipefail
cd "$(dirname "$0")/.."

config=""
name=""
generations=""
jobs="$(nproc)"
out=""
seeds="1 2 3"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --config) config="$2"; shift 2 ;;
    --name) name="$2"; shift 2 ;;
    --generations) generations="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --seeds) seeds="$2"; shift 2 ;;
    *) echo "seeded_runs.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
if [[ -z "$config" || -z "$name" ]]; then
  echo "seeded_runs.sh: --config FILE and --name NAME are needed" >&2
  exit 2
fi
if [[ "$(grep -c '^  seed: [0-9]*\b' "$config")" != 1 ]]; then
  echo "seeded_runs.sh: $config needs exactly one line '  seed: N'" >&2
  exit 2
fi
out="${out:-out/$name}"

scripts/setup.sh
scripts/build.sh
# The runs use a copy of the binaries, made once, so that a rebuild while
# they run (or between sessions) does not change the simulator under them:
# a resume checks the build. Remove $out/bin to continue with a newer
# build (animat evolve then asks for --force).
bin="$out/bin"
mkdir -p "$out"
if [[ ! -x "$bin/animat" || ! -x "$bin/animat-worker" ]]; then
  mkdir -p "$bin"
  cp build/bin/animat build/bin/animat-worker "$bin/"
fi
echo "seeded_runs.sh: the runs use $bin"

runs=()
for seed in $seeds; do
  run="${name}-seed${seed}"
  sed -e "s/^  seed: [0-9]*\b/  seed: $seed/" "$config" > "$out/$run.txtpb"
  grep -q "^  seed: $seed\b" "$out/$run.txtpb"
  runs+=("$run")
done

run_one() {
  local out="$1" bin="$2" generations="$3" run="$4"
  local extra=()
  if [[ -n "$generations" ]]; then extra=(--generations "$generations"); fi
  if [[ -f "$out/$run.db" ]]; then
    "$bin/animat" evolve --db "$out/$run.db" --workers 1 "${extra[@]}" \
      >> "$out/$run.log" 2>&1
  else
    "$bin/animat" evolve --config "$out/$run.txtpb" --db "$out/$run.db" \
      --workers 1 "${extra[@]}" >> "$out/$run.log" 2>&1
  fi
  echo "$run: $(tail -n 1 "$out/$run.log")"
}
export -f run_one
printf '%s\n' "${runs[@]}" |
  xargs -P "$jobs" -I{} bash -c 'run_one "$@"' _ "$out" "$bin" \
    "$generations" {}
echo "stores in $out"
