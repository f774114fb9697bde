#!/usr/bin/env bash
# Installs the Debian 12 packages this project builds and tests with (ompl-demos, with
# python3-matplotlib, and sqlite3: `kautham bench` logs become a Planner Arena database; and
# libmujoco-dev for the benchmark that measures ODE against MuJoCo, tests/benchmarks).
# Idempotent: when every package is present it only checks and returns (well under a second).
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config ninja-build clang-format clang libclang-rt-14-dev
  libompl-dev libboost-serialization-dev libboost-filesystem-dev libboost-system-dev
  libode-dev libeigen3-dev liburdfdom-dev liburdfdom-headers-dev
  libassimp-dev libqhull-dev libtinyxml2-dev liboctomap-dev libcoin-dev
  libcli11-dev nlohmann-json3-dev libspdlog-dev libfmt-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libjs-three chromium
  ompl-demos python3-matplotlib sqlite3
  libmujoco-dev
)

missing=()
for pkg in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$pkg")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
