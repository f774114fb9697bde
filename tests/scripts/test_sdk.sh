#!/usr/bin/env bash
# The SDK as an outside project uses it: install kautham into a fresh prefix, build the example
# plugin (examples/greedy_plugin) out of the tree against that prefix with find_package(kautham),
# then the installed kautham lists it (--plugin and its own plugin folder) and plans a shipped
# problem with it.  Usage: test_sdk.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
source=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cmake --install "$build" --prefix "$work/prefix" >/dev/null
kautham="$work/prefix/bin/kautham"
generator=()
if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
cmake -S "$source/examples/greedy_plugin" -B "$work/greedy" "${generator[@]}" \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/greedy" >/dev/null
plugin="$work/greedy/libkautham_greedy.so"

# The installed program runs on the installed libraries, not the build tree's.
ldd "$kautham" >"$work/ldd.txt"
grep "$work/prefix/.*libkautham_planners.so" "$work/ldd.txt"
"$kautham" --version | grep -E "^kautham [0-9]+\.[0-9]+\.[0-9]+ \(planner plugin ABI [0-9]+\)$"

# (grep reads all: with -q it would stop early and kautham would die of SIGPIPE)
"$kautham" planners --plugin "$plugin" >"$work/planners.txt"
grep "^Greedy: example plugin" "$work/planners.txt"
cd "$source"
"$kautham" plan problems/pusher_cans_5.xml --planner Greedy --seed 1 --plugin "$plugin" \
  -o "$work/plan.json" | tee "$work/plan.txt"
grep -q "^solved    yes" "$work/plan.txt"
grep -q "^replay    reaches the goal" "$work/plan.txt"

# Dropped into PREFIX/lib/kautham/plugins, the plugin loads without being named.
cp "$plugin" "$work/prefix/lib/kautham/plugins/"
"$kautham" planners >"$work/planners.txt"
grep -A1 "^Greedy: example plugin" "$work/planners.txt"
echo "SDK ok: out-of-tree plugin built against $work/prefix, listed and planned"
