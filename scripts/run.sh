#!/usr/bin/env bash
# Quick start, part 1: install, build, plan the default problem and validate the plan.
# The default problem is a KUKA LWR 4 reaching a pre-grasp pose of a glass among five cans
# whose poses, friction and controls are uncertain; p-KPIECE plans for that uncertainty
# (particles on every core), then `kautham validate` executes the plan 100 times under
# sampled uncertainty. The plan is written to out/plan.json and its animated replay to
# out/plan.html (open it in a browser). Extra arguments go to `kautham plan`.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh
mkdir -p out
problem=problems/kuka_cans_10.xml
./build/apps/kautham plan "$problem" --planner p-KPIECE --seed 1 --threads "$(nproc)" \
  -o out/plan.json --html out/plan.html "$@"
./build/apps/kautham validate "$problem" out/plan.json --runs 100 --seed 1
