#!/usr/bin/env bash
# Quick start, part 2: install, build, and run every test.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh
ctest --test-dir build --output-on-failure --parallel "$(nproc)"
