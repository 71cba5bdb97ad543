#!/usr/bin/env bash
# Configures and builds into build/ (Release; binaries in build/bin/).
# Extra arguments go to CMake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
# Tests and benchmarks on, whatever scripts/run.sh left in the cache.
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DANIMAT_BUILD_TESTS=ON -DANIMAT_BUILD_BENCH=ON "$@"
cmake --build build
