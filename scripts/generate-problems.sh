#!/usr/bin/env bash
# Regenerates the shipped generated scenes with `kautham generate clutter` and fixed seeds, and
# checks each one with `kautham check` (loads it and checks the start state in the physics):
#   - the dense suite (side pre-grasp): problems/kuka_clutter_N.xml and yumi_clutter_N.xml for
#     N = 5, 10, ..., 40, and the paper's two demo scenes laid out the same way,
#     kuka_clutter_demo.xml (a bottle, boxes and cans) and yumi_clutter_demo.xml;
#   - the earlier top-down scenes kuka_cans_5/10 and yumi_cans_5/10, kept for the tests.
# See docs/scenes.md. Uses build/apps/kautham (scripts/build.sh), or the program in $KAUTHAM.
set -euo pipefail
cd "$(dirname "$0")/.."
kautham="${KAUTHAM:-build/apps/kautham}"
if [ ! -x "$kautham" ]; then
  echo "error: $kautham not found; build it first (scripts/build.sh)" >&2
  exit 2
fi
seed=1  # the shipped scenes' seed; changing it changes every file

generate() {  # FILE ARGS...: write FILE and check it
  local file="$1"
  shift
  "$kautham" generate clutter "$@" --seed "$seed" -o "$file" --force
  "$kautham" check "$file" >/dev/null
}

for robot in kuka yumi; do
  for objects in 5 10 15 20 25 30 35 40; do
    gap=()
    # 40 cans with 8 blockers fill the YuMi's short corridor only 5 mm apart (docs/scenes.md)
    if [ "$robot" = yumi ] && [ "$objects" -ge 35 ]; then gap=(--gap 0.005); fi
    generate "problems/${robot}_clutter_${objects}.xml" --robot "$robot" --objects "$objects" \
      "${gap[@]}"
  done
done
generate problems/kuka_clutter_demo.xml --robot kuka --objects 8 --mix
generate problems/yumi_clutter_demo.xml --robot yumi --objects 12
for robot in kuka yumi; do
  for objects in 5 10; do
    generate "problems/${robot}_cans_${objects}.xml" --layout top --robot "$robot" \
      --objects "$objects"
  done
done
echo "checked   every scene: start state valid, nothing interpenetrates"
