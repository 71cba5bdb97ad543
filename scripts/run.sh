#!/usr/bin/env bash
# Sets up, builds, and runs the main job: an evolution on this machine
# (a master and one worker per core on loopback) recorded in
# out/evolution.db. Run it again to continue an interrupted run; Ctrl-C
# leaves the store resumable. Extra arguments go to animat evolve (e.g.
# --generations 40 to run longer).
set -euo pipefail
cd "$(dirname "$0")/.."
# Only the packages and programs the main job needs, not the tests and
# benchmarks (scripts/test.sh installs and builds those into the same tree).
scripts/setup.sh --run
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DANIMAT_BUILD_TESTS=OFF -DANIMAT_BUILD_BENCH=OFF
cmake --build build --target animat animat-worker animat-master
mkdir -p out
# Progress goes to standard error; the closing line (the best, or how to
# resume) to standard output.
build/bin/animat evolve --config configs/quickstart.txtpb \
  --db out/evolution.db "$@"
