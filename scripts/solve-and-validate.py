#!/usr/bin/env python3
"""Plans the paper's 10-object scenes with p-KPIECE and o-KPIECE and executes each plan under
uncertainty; writes docs/solve-and-validate.md.

For every problem (kuka_cans_10 and yumi_cans_10 by default), every planner configuration
(p-KPIECE with n_p = 15 particles, p-KPIECE without uncertainty, o-KPIECE) and every seed,
runs `kautham plan` with a time limit (180 s by default: the question here is whether and
how robustly a scene is solved; scripts/benchmark-planners.py measures speed at 60 s), then
`kautham validate --runs R` on the plan it found. A seed without a plan counts as 0 % in the
mean success rate: it executes nowhere.

The raw numbers go to --results (docs/solve-and-validate.json); runs already there for other
problems, planners or seeds are kept, so a later run with --planners adds rows.

Usage: scripts/solve-and-validate.py [--problems kuka_cans_10 yumi_cans_10]
           [--planners NAME ...] [--seeds 1 2 3 4 5] [--time 180] [--threads 2] [--runs 100]
           [--keep DIR] [--results docs/solve-and-validate.json] [-o docs/solve-and-validate.md]
Needs build/apps/kautham (scripts/build.sh) or $KAUTHAM; standard library only.
"""

import argparse
import datetime
import json
import os
import sys
import tempfile

import kautham_runs
from kautham_runs import KAUTHAM, ROOT, run

# name in the tables -> planner and its --set overrides
PLANNERS = [
    ("p-KPIECE, n_p = 15", "p-KPIECE", ["uncertainty=1", "particles=15"]),
    ("p-KPIECE, n_p = 15, goal_confidence 0.75", "p-KPIECE",
     ["uncertainty=1", "particles=15", "goal_confidence=0.75"]),
    ("p-KPIECE, no uncertainty", "p-KPIECE", ["uncertainty=0"]),
    ("o-KPIECE", "o-KPIECE", []),
]
DEFAULT_PLANNERS = ["p-KPIECE, n_p = 15", "p-KPIECE, no uncertainty", "o-KPIECE"]


def plan(problem, planner, sets, seed, limit, threads, out):
    """Returns (solved, planning time, controls, path belief or None)."""
    command = [KAUTHAM, "plan", problem, "--planner", planner, "--seed", str(seed), "--time",
               str(limit), "--threads", str(threads), "-o", out]
    for s in sets:
        command += ["--set", s]
    result = run(command)
    if result.returncode not in (0, 1) or not os.path.exists(out):
        sys.exit(f"solve-and-validate: {' '.join(command)} failed:\n{result.stderr}")
    return read_plan(out)


def read_plan(out):
    """(solved, planning time, controls, path belief or None) of a plan file."""
    with open(out) as f:
        data = json.load(f)
    properties = dict(data["statistics"].get("planner", {}))
    belief = properties.get("solution_path_belief")
    return (data["result"]["solved"], data["timing"]["planning_time"], len(data["controls"]),
            None if belief in (None, "nan") else float(belief))


def validate(problem, plan_file, runs, seed):
    """Returns (success rate, failure counts)."""
    data = kautham_runs.validate(problem, plan_file, runs, seed, "solve-and-validate")
    return data["successes"] / data["runs"], data["failures"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--problems", nargs="+", default=["kuka_cans_10", "yumi_cans_10"])
    parser.add_argument("--planners", nargs="+", default=DEFAULT_PLANNERS,
                        choices=[name for name, _, _ in PLANNERS])
    parser.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3, 4, 5])
    parser.add_argument("--time", type=float, default=180.0)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--runs", type=int, default=100)
    parser.add_argument("--keep", help="folder for the plan files (default: a temporary one)")
    parser.add_argument("--reuse-plans", action="store_true",
                        help="validate the plan files already in --keep instead of planning")
    parser.add_argument("--results", default=os.path.join(ROOT, "docs", "solve-and-validate.json"))
    parser.add_argument("-o", "--output",
                        default=os.path.join(ROOT, "docs", "solve-and-validate.md"))
    args = parser.parse_args()
    keep = args.keep or tempfile.mkdtemp(prefix="kautham-solve-")
    os.makedirs(keep, exist_ok=True)

    results = []
    if os.path.exists(args.results):
        with open(args.results) as f:
            results = json.load(f)["runs"]
    for name_problem in args.problems:
        problem = f"problems/{name_problem}.xml"
        for name, planner, sets in PLANNERS:
            if name not in args.planners:
                continue
            for seed in args.seeds:
                out = os.path.join(keep, f"{name_problem}_{planner}_{'_'.join(sets)}_s{seed}.json")
                if args.reuse_plans and os.path.exists(out):
                    solved, seconds, controls, belief = read_plan(out)
                else:
                    solved, seconds, controls, belief = plan(problem, planner, sets, seed,
                                                             args.time, args.threads, out)
                rate, failures = validate(problem, out, args.runs, seed) if solved else (None, {})
                results = [r for r in results if (r["problem"], r["planner"], r["seed"]) !=
                           (name_problem, name, seed)]
                results.append({"problem": name_problem, "planner": name, "seed": seed,
                                "time_limit": args.time, "solved": solved, "time": seconds,
                                "controls": controls, "belief": belief, "rate": rate,
                                "failures": failures})
                shown = "-" if rate is None else f"{100 * rate:.0f} %"
                print(f"{name_problem} {name:26} seed {seed}: "
                      f"{'solved' if solved else 'not solved'} in {seconds:.1f} s, "
                      f"executions {shown}", flush=True)
    commit = run(["git", "rev-parse", "--short", "HEAD"]).stdout.strip()
    with open(args.results, "w") as f:
        json.dump({"commit": commit, "date": str(datetime.date.today()), "runs": results}, f,
                  indent=1)
    rows = {}  # (problem, name) -> per-seed dicts, in seed order
    for r in sorted(results, key=lambda r: r["seed"]):
        rows.setdefault((r["problem"], r["planner"]), []).append(r)
    write(args, rows, commit)


def write(args, rows, commit):
    lines = [
        "# Solving the 10-object scenes and executing the plans under uncertainty",
        "",
        f"Made by `scripts/solve-and-validate.py` (last run {datetime.date.today()}, commit "
        f"{commit}; raw numbers in `{os.path.relpath(args.results, ROOT)}`): `kautham plan` "
        f"with a {args.time:g} s limit and `--threads {args.threads}` on a machine with 2 "
        f"cores; each plan found is executed {args.runs} times by `kautham validate` (object "
        "poses, friction and control "
        "noise drawn from the problem's `<Uncertainty>`, every constraint checked). A seed "
        "without a plan counts as 0 % in the mean. Each seed cell: planning time (s), controls, "
        "the planner's path belief where it has one, and the execution success rate.",
        "",
    ]
    problems = sorted({problem for problem, _ in rows})
    for name_problem in problems:
        seeds = sorted({r["seed"] for (p, _), runs in rows.items() if p == name_problem
                        for r in runs})
        lines += [f"## {name_problem}", "",
                  "| planner | solved | " + " | ".join(f"seed {s}" for s in seeds) +
                  " | mean success |",
                  "| --- | --- | " + " | ".join("---" for _ in seeds) + " | --- |"]
        names = [name for name, _, _ in PLANNERS if (name_problem, name) in rows]
        for name in names:
            runs = rows[(name_problem, name)]
            cells = []
            for r in runs:
                if not r["solved"]:
                    cells.append(f"not solved ({r['time']:.0f} s)")
                    continue
                belief = "" if r["belief"] is None else f", b {r['belief']:.2f}"
                cells.append(f"{r['time']:.1f} s, {r['controls']} ctl{belief}: "
                             f"**{100 * r['rate']:.0f} %**")
            solved = sum(r["solved"] for r in runs)
            mean = 100 * sum(r["rate"] or 0.0 for r in runs) / len(runs)
            lines.append(f"| {name} | {solved}/{len(runs)} | " + " | ".join(cells) +
                         f" | {mean:.0f} % |")
        lines += ["", "Failures of the executions, summed over the seeds:", ""]
        for name in names:
            total = {}
            for r in rows[(name_problem, name)]:
                for reason, count in r["failures"].items():
                    total[reason] = total.get(reason, 0) + count
            shown = ", ".join(f"{k.replace('_', ' ')} {v}" for k, v in sorted(total.items()) if v)
            lines.append(f"- {name}: {shown or 'none'}")
        lines.append("")
    with open(args.output, "w") as f:
        f.write("\n".join(lines))
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
