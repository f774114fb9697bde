#!/usr/bin/env bash
# Plans a list of problems with KPIECE for several seeds and writes a markdown table of the
# results: per run whether it solved, the planning time, the tree size, the plan's length, whether
# the replayed plan reached the goal, whether the target stayed untouched and which objects moved;
# per problem the success rate and the median planning time of the solved runs. See docs/demos.md.
#
# Usage: scripts/solve-table.sh [-p "PROBLEM ..."] [-s "SEED ..."] [-t SECONDS] [-k DIR] [OUTPUT.md]
#   -p  problems, as names in problems/ (kuka_cans_5) or paths to XML files
#       (default: kuka_cans_5 yumi_cans_5 yumi_demo_wine_glass kuka_demo_bottle)
#   -s  seeds (default: 1 2 3 4 5)
#   -t  planning time limit per run, seconds (default: 60)
#   -k  keep the plan files (PROBLEM_sSEED.json) and the program's output (.log) in DIR
#   OUTPUT.md  where to write the table (default: docs/solve-table.md)
# Uses build/apps/kautham (build it with scripts/build.sh), or the program in $KAUTHAM; needs
# python3 (standard library only). Runs one plan at a time, so the times are comparable.
set -euo pipefail

problems="kuka_cans_5 yumi_cans_5 yumi_demo_wine_glass kuka_demo_bottle"
seeds="1 2 3 4 5"
limit=60
keep=""
usage() { sed -n '7,13p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
while getopts "p:s:t:k:h" option; do
  case "$option" in
    p) problems="$OPTARG" ;;
    s) seeds="$OPTARG" ;;
    t) limit="$OPTARG" ;;
    k) keep="$OPTARG" ;;
    *) usage ;;
  esac
done
shift $((OPTIND - 1))
[ $# -le 1 ] || usage
output="${1:-docs/solve-table.md}"

# Paths given by the user are relative to where they ran the script; the rest to the repository.
absolute() { case "$1" in /*) echo "$1" ;; *) echo "$PWD/$1" ;; esac; }
[ $# -eq 1 ] && output="$(absolute "$output")"
[ -n "$keep" ] && keep="$(absolute "$keep")"
files=()
for problem in $problems; do
  if [ -f "$problem" ]; then files+=("$(absolute "$problem")")
  else files+=("$problem"); fi
done
cd "$(dirname "$0")/.."
kautham="${KAUTHAM:-build/apps/kautham}"
if [ ! -x "$kautham" ]; then
  echo "error: $kautham not found; build it first (scripts/build.sh)" >&2
  exit 2
fi
for i in "${!files[@]}"; do
  case "${files[$i]}" in
    /*) ;;
    *) files[$i]="problems/${files[$i]%.xml}.xml" ;;
  esac
  if [ ! -f "${files[$i]}" ]; then
    echo "error: problem ${files[$i]} not found" >&2
    exit 2
  fi
done

runs="$(mktemp -d)"
trap 'rm -rf "$runs"' EXIT
for file in "${files[@]}"; do
  name="$(basename "$file" .xml)"
  for seed in $seeds; do
    echo "plan      $name seed $seed" >&2
    status=0
    "$kautham" plan "$file" --planner KPIECE --seed "$seed" --time "$limit" \
      -o "$runs/${name}_s${seed}.json" >"$runs/${name}_s${seed}.log" 2>&1 || status=$?
    echo "$name $seed $status" >>"$runs/index"
    if [ "$status" -gt 1 ]; then
      echo "error: kautham plan $file failed (exit $status):" >&2
      cat "$runs/${name}_s${seed}.log" >&2
      exit "$status"
    fi
  done
done
if [ -n "$keep" ]; then
  mkdir -p "$keep"
  cp "$runs"/*.json "$runs"/*.log "$keep"/ 2>/dev/null || true
fi

mkdir -p "$(dirname "$output")"
python3 - "$runs" "$output" "$limit" "$("$kautham" --version 2>/dev/null || echo unknown)" \
  "$(git rev-parse --short HEAD 2>/dev/null || echo unknown)" "$(nproc)" <<'PYTHON'
import datetime
import json
import os
import statistics
import sys

runs, output, limit, version, commit, cores = sys.argv[1:7]


def load(name, seed):
    path = os.path.join(runs, f"{name}_s{seed}.json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


def target_untouched(plan):
    """The robot never touched the target in the replay, and the replay broke no rule about it."""
    targets = {i for i, body in enumerate(plan["bodies"]) if body["role"] == "target"}
    touched = any(i in targets for frame in plan["frames"] for i in frame["touched"])
    violation = plan["result"]["replay"]["violation"]
    return not touched and violation not in ("robot touched the target", "target moved")


rows, summary, order = [], {}, []
with open(os.path.join(runs, "index")) as index:
    for line in index:
        name, seed, status = line.split()
        if name not in summary:
            summary[name] = []
            order.append(name)
        plan = load(name, seed)
        if plan is None:
            rows.append(f"| {name} | {seed} | no (no plan file, exit {status}) | | | | | | |")
            summary[name].append((False, None))
            continue
        result, replay = plan["result"], plan["result"]["replay"]
        solved = bool(result["solved"])
        seconds = plan["timing"]["planning_time"]
        moved = ", ".join(f"{m['name']} {100 * m['distance']:.1f} cm"
                          for m in replay["moved_objects"]) or "none"
        reached = "yes" if replay["reached_goal"] else "no"
        if replay["violation"] != "none":
            reached += f" ({replay['violation']})"
        reached += f", {100 * replay['final_goal_distance']:.1f} cm"
        solved_text = "yes" if solved else (
            f"no (closest {100 * result['goal_distance']:.1f} cm)" if result["approximate"] else "no")
        rows.append(f"| {name} | {seed} | {solved_text} | {seconds:.1f} | "
                    f"{plan['statistics']['tree_states']} | {len(plan['controls'])} | {reached} | "
                    f"{'yes' if target_untouched(plan) else 'no'} | {moved} |")
        summary[name].append((solved, seconds))

lines = [
    "# KPIECE on the table scenes",
    "",
    f"Made by `scripts/solve-table.sh` on {datetime.date.today().isoformat()}: `kautham plan` "
    f"with KPIECE and each problem's own parameters, time limit {limit} s, one run at a time "
    f"on a machine with {cores} cores; {version.strip()}, commit {commit}.",
    "",
    "| problem | solved | success rate | median time of the solved runs (s) |",
    "| --- | --- | --- | --- |",
]
for name in order:
    results = summary[name]
    solved_times = [seconds for solved, seconds in results if solved]
    median = f"{statistics.median(solved_times):.1f}" if solved_times else "-"
    lines.append(f"| {name} | {len(solved_times)} of {len(results)} | "
                 f"{100 * len(solved_times) / len(results):.0f} % | {median} |")
lines += [
    "",
    "Per run: *time* is the planning time; *states* the planner's tree states; *controls* the "
    "plan's length; *replay* whether the plan, replayed in the physics from the start, ends "
    "within the goal region (with the first rule it broke, if any, and the final distance to "
    "the goal's centre); *target untouched*: the robot never touched the target during the "
    "replay and it did not drift; *objects moved*: movable objects displaced more than 5 mm "
    "(start to end of the replay). An unsolved run reports its approximate plan.",
    "",
    "| problem | seed | solved | time (s) | states | controls | replay reached goal | "
    "target untouched | objects moved |",
    "| --- | --- | --- | --- | --- | --- | --- | --- | --- |",
] + rows
with open(output, "w") as f:
    f.write("\n".join(lines) + "\n")
print(f"wrote     {output}", file=sys.stderr)
PYTHON
