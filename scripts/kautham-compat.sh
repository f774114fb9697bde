#!/usr/bin/env bash
# Which Kautham problem files of a folder this program loads and plans (issue 14).
#
#   scripts/kautham-compat.sh DIR [--time S] [-o TABLE.md]
#
# For every XML file under DIR (its models/ folder excepted) whose root is <Problem>, runs
# `kautham check` and, where a planner of ours fits (Kautham's geometric OMPL planners run as
# OMPL's geometric planners here, docs/planners.md), `kautham plan --time S` (default 10 s,
# seed 1): with KPIECE for files written for Kautham's ODE planners (omplODE..., ...2DPlanner,
# ...ChainPlanner, ...CarPlanner), with the file's planner otherwise. Writes a Markdown table:
# each problem, its planner, whether it loads and plans (with the rejection counts of a run that
# does not solve), and the first message of a failure (or the first warning). Kautham's
# benchmark files (root <Benchmark>) are run by `kautham bench --file`, one run per planner of
# S seconds. Other XML files (synergy trees) are listed as not problems.
# Extra options for both commands: KAUTHAM_ARGS="--package-path NAME=DIR ...".
# The exit code is 0 when every problem loads and every benchmark file runs, 1 otherwise.
set -uo pipefail

# The header comment above, without its '#'s.
usage() { awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "$0"; exit "${1:-2}"; }
[ $# -ge 1 ] || usage
case $1 in -h | --help) usage 0 ;; esac
dir=$1; shift
time_limit=10
output=""
while [ $# -gt 0 ]; do
  case $1 in
    --time) time_limit=$2; shift 2 ;;
    -o) output=$2; shift 2 ;;
    -h | --help) usage 0 ;;
    *) usage ;;
  esac
done
[ -d "$dir" ] || { echo "kautham-compat: '$dir' is not a folder" >&2; exit 2; }
root=$(cd "$(dirname "$0")/.." && pwd)
kautham=${KAUTHAM:-$root/build/apps/kautham}
[ -x "$kautham" ] || { echo "kautham-compat: $kautham not built (run ./scripts/build.sh)" >&2; exit 2; }
read -r -a extra <<< "${KAUTHAM_ARGS:-}"
dir=$(cd "$dir" && pwd)

# One line of a message for a table cell: no pipes, no line breaks, the folder shortened.
cell() { head -c 400 | tr '\n|' ' /' | sed "s#$dir/##g; s#  *# #g; s# *\$##"; }

rows=()
problems=0; loaded=0; planned=0; solved=0; others=0; benchmarks=0; ran=0
while IFS= read -r file; do
  rel=${file#"$dir"/}
  rootTag=$(grep -v '^\s*<?xml' "$file" | grep -v '^\s*<!--' | grep -o -m1 '<[A-Za-z][A-Za-z]*' | tr -d '<')
  if [ "$rootTag" = "Benchmark" ]; then
    # A Kautham benchmark file: its planners on its first problem, one run each.
    benchmarks=$((benchmarks + 1))
    out_dir=$(mktemp -d)
    bench_out=$(timeout $((time_limit * 20 + 120)) "$kautham" bench --file "$file" --runs 1 --time "$time_limit" -o "$out_dir" 2>&1)
    bench_rc=$?
    rm -rf "$out_dir"
    first_warning=$(printf '%s\n' "$bench_out" | grep -m1 '^warning' | sed 's/^warning: //' | cell)
    if [ $bench_rc -eq 0 ]; then
      ran=$((ran + 1))
      result="runs: $(printf '%s\n' "$bench_out" | grep -m1 '^runs' | sed 's/^runs *//; s/^[0-9]*: [0-9]* made now, 0 resumed; //' | cell)"
    else
      result="**error** (exit $bench_rc): $(printf '%s\n' "$bench_out" | grep -m1 '^error' | cell)"
    fi
    rows+=("| $rel | | benchmark file | \`kautham bench --file --runs 1 --time $time_limit\`: $result | $first_warning |")
    continue
  fi
  if [ "$rootTag" != "Problem" ]; then
    others=$((others + 1))
    rows+=("| $rel | | not a problem file (root <$rootTag>) | | |")
    continue
  fi
  problems=$((problems + 1))
  planner=$(grep -v '^\s*<!--' "$file" | grep -o -m1 '<Name>[^<]*</Name>' | sed 's#</\?Name>##g')
  check_out=$(cd "$(dirname "$file")" && timeout 120 "$kautham" check "$(basename "$file")" "${extra[@]}" 2>&1)
  check_rc=$?
  if [ $check_rc -ne 0 ]; then
    message=$(printf '%s\n' "$check_out" | grep -m1 '^error' | cell)
    rows+=("| $rel | $planner | **fails** (exit $check_rc) | | $message |")
    continue
  fi
  loaded=$((loaded + 1))
  first_warning=$(printf '%s\n' "$check_out" | grep -m1 '^warning' | sed 's/^warning: //' | cell)
  if printf '%s\n' "$check_out" | grep -q "geometric OMPL planners"; then
    rows+=("| $rel | $planner | loads | not run: a geometric planner this program does not have (the message lists those it has) | $first_warning |")
    continue
  fi
  planned=$((planned + 1))
  # Kautham's ODE demos: the issue asks that they plan with KPIECE (docs/kautham-compat.md).
  with=()
  prefix=""
  if printf '%s\n' "$planner" | grep -Eq '^omplODE|2DPlanner$|ChainPlanner$|CarPlanner$'; then
    with=(--planner KPIECE)
    prefix="KPIECE: "
  fi
  plan_out=$(cd "$(dirname "$file")" && timeout $((time_limit * 3 + 60)) "$kautham" plan "$(basename "$file")" --time "$time_limit" --seed 1 "${with[@]}" "${extra[@]}" 2>&1)
  plan_rc=$?
  rejected=$(printf '%s\n' "$plan_out" | grep -m1 '^rejected' | sed 's/^rejected *//' | cell)
  case $plan_rc in
    0) solved=$((solved + 1)); result="${prefix}solved ($(printf '%s\n' "$plan_out" | grep -m1 '^solved' | sed 's/^solved *yes in //'))" ;;
    1)
      # How far the replay got and what the planner rejected, where it says (a geometric
      # planner replays nothing).
      details=$(printf '%s\n' "$plan_out" | grep -m1 '^replay' | sed 's/^replay *//' | cell)
      [ -n "$rejected" ] && details="${details:+$details; }rejected $rejected"
      result="${prefix}not solved in $time_limit s${details:+ ($details)}" ;;
    *) result="**error** (exit $plan_rc): $(printf '%s\n' "$plan_out" | grep -m1 '^error' | cell)" ;;
  esac
  rows+=("| $rel | $planner | loads | $result | $first_warning |")
done < <(find "$dir" -name '*.xml' -not -path '*/models/*' | sort)

{
  echo "| problem | planner in the file | \`kautham check\` | \`kautham plan --time $time_limit --seed 1\` | first message |"
  echo "| --- | --- | --- | --- | --- |"
  printf '%s\n' "${rows[@]}"
  echo
  echo "$problems problem files: $loaded load, $planned planned, $solved solved; $benchmarks benchmark files, $ran run by \`kautham bench\`; $others other XML files."
} > "${output:-/dev/stdout}"
[ -n "$output" ] && echo "kautham-compat: wrote $output ($problems problems, $loaded load, $solved solved)" >&2
[ "$loaded" -eq "$problems" ] && [ "$ran" -eq "$benchmarks" ]
