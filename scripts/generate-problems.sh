#!/usr/bin/env bash
# Regenerates the shipped cluttered scenes, problems/kuka_cans_N.xml and problems/yumi_cans_N.xml
# for N = 5, 10, ..., 40, with `kautham generate clutter` and fixed seeds, and checks each one
# with `kautham check` (loads it and checks the start state in the physics). See docs/scenes.md.
# Uses build/apps/kautham (build it with scripts/build.sh), or the program in $KAUTHAM.
set -euo pipefail
cd "$(dirname "$0")/.."
kautham="${KAUTHAM:-build/apps/kautham}"
if [ ! -x "$kautham" ]; then
  echo "error: $kautham not found; build it first (scripts/build.sh)" >&2
  exit 2
fi
seed=1  # the shipped scenes' seed; changing it changes every file
for robot in kuka yumi; do
  for objects in 5 10 15 20 25 30 35 40; do
    file="problems/${robot}_cans_${objects}.xml"
    "$kautham" generate clutter --robot "$robot" --objects "$objects" --seed "$seed" \
      -o "$file" --force
    "$kautham" check "$file" >/dev/null
  done
done
echo "checked   every scene: start state valid, nothing interpenetrates"
