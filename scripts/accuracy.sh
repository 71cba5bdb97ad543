#!/usr/bin/env bash
# Sets up, builds, and writes the speed-against-error report into
# docs/accuracy/ (docs/accuracy.md explains it). Extra arguments go to
# build/bin/animat-accuracy (e.g. --quick, --repeats 5, --out DIR).
# Takes about 5-10 minutes on 2 cores; run it on an otherwise idle machine,
# since the report times every evaluation.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
build/bin/animat-accuracy "$@"  # writes docs/accuracy/ unless --out
