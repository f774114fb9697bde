#!/usr/bin/env python3
"""Benchmarks the KPIECE family on the generated clutter scenes and writes docs/benchmarks.md.

For every problem kuka_cans_N (N from --objects) and every planner configuration, plans once
per seed with a time limit (60 s by default, as the paper's comparison needs), one run at a
time, through `kautham bench` (each run in its own process; a run whose result is in --keep
is not run again), and records whether it solved and how long it took. With
--validate R, each solved p-KPIECE and o-KPIECE plan of the --validate-problem scene is also
run R times under the problem's uncertainty (`kautham validate`), and the success rates go in
a second table. The paper's Table I (i7-4500U, 30 runs per scene) is printed beside ours.

Usage: scripts/benchmark-planners.py [--objects 5 10 20 30 40] [--seeds 1 2 3 4 5 (consecutive)]
           [--time 60] [--threads 1] [--validate 100] [--validate-problem kuka_cans_10]
           [--keep DIR] [-o docs/benchmarks.md]
Needs build/apps/kautham (scripts/build.sh) or $KAUTHAM; standard library only.
"""

import argparse
import datetime
import json
import os
import statistics
import subprocess
import sys
import tempfile

import kautham_runs
from kautham_runs import KAUTHAM, ROOT, run

# name in the table -> `kautham bench --config` (NAME=PLANNER[:PARAM=VALUE]...)
PLANNERS = [
    ("p-KPIECE, uncertainty", "pKPU=p-KPIECE:uncertainty=1"),
    ("p-KPIECE, none", "pKP=p-KPIECE:uncertainty=0"),
    ("o-KPIECE", "o-KPIECE=o-KPIECE"),
    ("KPIECE", "KPIECE=KPIECE"),
]

# The paper's Table I: objects -> (pKP success %, pKP time s, pKPU success %, pKPU time s).
PAPER = {5: (100, 2.89, 100, 9.88), 10: (100, 5.96, 100, 14.52), 15: (100, 9.15, 90, 29.43),
         20: (100, 16.78, 86, 47.61), 25: (96, 26.09, 73, 72.28), 30: (90, 41.21, 66, 103.07),
         35: (73, 49.62, 53, 134.94), 40: (60, 71.64, 40, 182.19)}


def bench(args, keep):
    """`kautham bench` of every scene and configuration: run r plans with seed seeds[0] + r."""
    seeds = args.seeds
    if seeds != list(range(seeds[0], seeds[0] + len(seeds))):
        sys.exit("benchmark: --seeds must be consecutive (kautham bench plans seed, seed + 1, ...)")
    command = [KAUTHAM, "bench", *[f"problems/kuka_cans_{n}.xml" for n in args.objects],
               "--runs", str(len(seeds)), "--seed", str(seeds[0]), "--time", str(args.time),
               "--threads", str(args.threads), "-o", keep]
    for _, config in PLANNERS:
        command += ["--config", config]
    # Its progress line and summary go to the terminal; exit 1 means some run crashed, and a
    # crashed run counts as not solved below.
    if subprocess.run(command, cwd=ROOT).returncode not in (0, 1):
        sys.exit(f"benchmark: {' '.join(command)} failed")


def result(keep, n, config, seed_index):
    """(solved, planning time, plan file or None) of one run, from its bench result file."""
    name = config.split("=")[0]
    with open(os.path.join(keep, "runs", f"kuka_cans_{n}", name, f"run-{seed_index}.json")) as f:
        data = json.load(f)
    plan_file = os.path.join(keep, data["plan"]["file"]) if data["solved"] else None
    return data["solved"], float(data["properties"]["time REAL"]), plan_file


def validate(problem, planFile, runs, seed):
    data = kautham_runs.validate(problem, planFile, runs, seed, "benchmark")
    return data["successes"] / data["runs"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--objects", type=int, nargs="+", default=[5, 10, 20, 30, 40])
    parser.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3, 4, 5])
    parser.add_argument("--time", type=float, default=60.0)
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--validate", type=int, default=0, metavar="RUNS")
    parser.add_argument("--validate-problem", default="kuka_cans_10")
    parser.add_argument("--keep", help="kautham bench's output folder: results, plans, OMPL logs "
                        "(default: a temporary one)")
    parser.add_argument("-o", "--output", default=os.path.join(ROOT, "docs", "benchmarks.md"))
    args = parser.parse_args()
    keep = args.keep or tempfile.mkdtemp(prefix="kautham-bench-")
    os.makedirs(keep, exist_ok=True)

    bench(args, keep)
    results = {}  # (objects, name) -> list of (solved, time)
    plans = {}    # (name, seed) -> plan file of the validated scene
    for n in args.objects:
        for name, config in PLANNERS:
            for index, seed in enumerate(args.seeds):
                solved, seconds, plan_file = result(keep, n, config, index)
                results.setdefault((n, name), []).append((solved, seconds))
                if f"kuka_cans_{n}" == args.validate_problem:
                    plans[(name, seed)] = plan_file
                print(f"kuka_cans_{n} {name:24} seed {seed}: "
                      f"{'solved' if solved else 'not solved'} in {seconds:.1f} s", flush=True)

    rates = {}
    if args.validate:
        problem = f"problems/{args.validate_problem}.xml"
        for (name, seed), planFile in sorted(plans.items()):
            if name in ("p-KPIECE, uncertainty", "o-KPIECE", "p-KPIECE, none", "KPIECE"):
                # A plan that was not found executes nowhere: it counts as 0 %.
                rate = validate(problem, planFile, args.validate, seed) if planFile else None
                rates.setdefault(name, []).append((seed, rate))
                print(f"validate {name:24} seed {seed}: "
                      f"{'not solved' if rate is None else f'{100 * rate:.0f} %'}", flush=True)
    write(args, results, rates)


def cell(runs):
    solved = [t for ok, t in runs if ok]
    rate = 100.0 * len(solved) / len(runs)
    median = f"{statistics.median(solved):.1f}" if solved else "-"
    return f"{rate:.0f} % / {median}"


def write(args, results, rates):
    commit = run(["git", "rev-parse", "--short", "HEAD"]).stdout.strip()
    lines = [
        "# Benchmarks: the KPIECE family on kuka_cans_N",
        "",
        f"Made by `scripts/benchmark-planners.py` on {datetime.date.today()} (commit {commit}): "
        f"`kautham bench` on `problems/kuka_cans_N.xml`, seeds {' '.join(map(str, args.seeds))}, "
        f"time limit {args.time:g} s, {args.threads} thread(s), one run at a time on a machine "
        "with 2 cores. Each cell: success rate / median planning time of the solved runs (s). "
        "Rerun it with the same command to check; add `--objects 5 10 15 20 25 30 35 40` or more "
        "`--seeds` where time allows.",
        "",
        "| objects | " + " | ".join(name for name, _ in PLANNERS) +
        " | paper pKP | paper pKPU |",
        "| --- | " + " | ".join("---" for _ in PLANNERS) + " | --- | --- |",
    ]
    for n in args.objects:
        row = [cell(results[(n, name)]) for name, _ in PLANNERS]
        paper = PAPER.get(n)
        extra = [f"{paper[0]} % / {paper[1]}", f"{paper[2]} % / {paper[3]}"] if paper else ["", ""]
        lines.append(f"| {n} | " + " | ".join(row + extra) + " |")
    lines += ["", "The paper's columns are its Table I (i7-4500U, 30 runs per scene; pKP without "
              "uncertainty, pKPU with it)."]
    if rates:
        lines += ["", f"## Execution under uncertainty ({args.validate_problem})", "",
                  f"Each plan run {args.validate} times by `kautham validate` with the "
                  "problem's `<Uncertainty>` (sampled object poses, friction, control noise). "
                  "A seed whose plan was not found in the time limit counts as 0 % in the mean.",
                  "", "| planner | seed: success rate | mean |", "| --- | --- | --- |"]
        for name, values in rates.items():
            per = ", ".join(f"{seed}: " + ("not solved" if r is None else f"{100 * r:.0f} %")
                            for seed, r in values)
            mean = 100 * sum(r or 0.0 for _, r in values) / len(values)
            lines.append(f"| {name} | {per} | {mean:.0f} % |")
    with open(args.output, "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
