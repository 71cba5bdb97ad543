#!/usr/bin/env bash
# Installs every Debian package the build and the tests need; with --run,
# only those the main job (scripts/run.sh: the programs, not the tests and
# benchmarks) needs. Idempotent and non-interactive: it installs only what
# is missing, and does nothing when everything is present.
#
#   scripts/setup.sh [--run]
set -euo pipefail

# The build of the programs, and sqlite3 to ask a store.
packages=(
  g++ cmake ninja-build pkg-config
  protobuf-compiler libprotobuf-dev
  libcli11-dev
  libbullet-dev
  libeigen3-dev
  libzmq3-dev cppzmq-dev
  libsqlite3-dev sqlite3
)
case "${1:-}" in
  --run) ;;
  "")
    # The tests and benchmarks, the format check and fuzzing, the browser
    # tests, the deployment tests (Slurm, containers, systemd), the scripts.
    packages+=(
      libgtest-dev libgmock-dev libbenchmark-dev
      clang-format
      clang-14 libclang-rt-14-dev
      chromium
      slurm-wlm munge systemd
      podman runc debootstrap debian-archive-keyring
      python3 python3-yaml
    )
    ;;
  *) echo "setup: unknown argument $1 (expected --run or nothing)" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then
    sudo="sudo"
  else
    echo "setup: missing packages (${missing[*]}) and not root; install them or run as root" >&2
    exit 1
  fi
fi

echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q
$sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
