#!/usr/bin/env bash
# Sets up, builds, and runs the main job: develops and simulates the sample
# animat, writes its trace to out/sample-trace.json and prints its fitness.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
mkdir -p out
build/bin/animat simulate --genome configs/sample-genome.json \
  --config configs/default.txtpb --trace out/sample-trace.json "$@"
echo "trace: out/sample-trace.json"
