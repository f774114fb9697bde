#!/bin/bash
# Every benchmark file in bench/ still runs: `kautham bench --check` loads its problems and
# checks its configurations (planner, parameters, physics) without running anything. A bench
# file is the recipe of the results under bench/results/ of the same name; one that names a
# removed parameter or a problem file not in the repository cannot be run again. Files that
# run only at an old commit live in bench/retired/ and say which in their "description".
#
# Usage: scripts/check-bench-files.sh KAUTHAM [BENCH_DIR]   (exit 0: all good, 1: some failed)
set -u
kautham=${1:?usage: check-bench-files.sh KAUTHAM [BENCH_DIR]}
bench=${2:-$(dirname "$0")/../bench}
checked=0
failed=0
for file in "$bench"/*.json; do
  [ -e "$file" ] || continue
  checked=$((checked + 1))
  if ! output=$("$kautham" bench --check --file "$file" 2>&1); then
    failed=$((failed + 1))
    echo "FAILED $file: $(echo "$output" | grep -m1 '^error: ' || echo "$output" | tail -1)"
  fi
done
if [ "$checked" -eq 0 ]; then
  echo "no benchmark file (*.json) in $bench: nothing checked"
  exit 1
fi
echo "$checked benchmark files checked, $failed failed"
[ "$failed" -eq 0 ]
