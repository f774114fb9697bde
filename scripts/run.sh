#!/usr/bin/env bash
# Quick start, part 1: install, build, and plan the default problem (a pusher among cans).
# The plan is written to out/plan.json, its animated replay to out/plan.html (open it in a
# browser). Extra arguments go to `kautham plan`.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh
mkdir -p out
./build/apps/kautham plan problems/pusher_cans_5.xml --seed 1 -o out/plan.json \
  --html out/plan.html "$@"
