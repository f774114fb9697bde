#!/usr/bin/env python3
"""A STUB of `kautham bench`, for testing scripts/bench-slurm.sh before the real one exists.

It plans nothing: it writes made-up OMPL 1.5.2 benchmark logs (control planners, with kautham's
extra run properties) in the layout the real command will use, so that the Slurm job array,
the merge job and scripts/bench-report.py can be run end to end:

  kautham-bench-stub.py bench [PROBLEMS...] --runs R [--seed S] [--time T] [--shard i/n]
                        [--planners pKPU,pKP,...] -o OUT     -> OUT/logs/<problem>.log
  kautham-bench-stub.py bench --merge-only -o OUT DIR1 DIR2 ... -> OUT/logs/<problem>.log

Shard i of n takes the runs whose index (over problems x planners x runs) is i-1 modulo n.
The merge concatenates each planner's runs of a problem over the shards' logs. Other options of
the real command (--threads, --jobs, --validate, --file) are accepted and ignored. Use it as
KAUTHAM=tests/scripts/kautham-bench-stub.py scripts/bench-slurm.sh ...
"""

import argparse
import glob
import os
import random
import sys
import time

PROPS = sorted(["approximate solution BOOLEAN", "cells INTEGER", "correct solution BOOLEAN",
                "estimated success REAL", "execution success REAL", "graph motions INTEGER",
                "graph states INTEGER", "memory REAL", "objects moved INTEGER",
                "particles INTEGER", "seed INTEGER", "solution difference REAL",
                "solution length REAL", "solution segments INTEGER", "solved BOOLEAN",
                "status ENUM", "time REAL"])
ENUM = ("status|Unknown status|Invalid start|Invalid goal|Unrecognized goal type|Timeout|"
        "Approximate solution|Exact solution|Crash|Unknown status")


def header(problem, seed, limit, runs, planners, total):
    return ["OMPL version ", f"Experiment {problem}", "0 experiment properties",
            f"Running on {os.uname().nodename}",
            "Starting at " + time.strftime("%Y-%m-%d %H:%M:%S"),
            "<<<|", "STUB kautham bench: made-up runs, not planning results.", "|>>>",
            "<<<|", "", "|>>>", f"{seed} is the random seed", f"{limit:g} seconds per run",
            "4096 MB per run", f"{runs} runs per planner",
            f"{total:g} seconds spent to collect the data", "1 enum type", ENUM,
            f"{planners} planners"]


def fake_run(problem, planner, r, seed, limit, validate):
    rng = random.Random(f"{problem}/{planner}/{r}/{seed}")
    n = int(problem.rsplit("_", 1)[-1]) if problem.rsplit("_", 1)[-1].isdigit() else 10
    t = rng.expovariate(1 / (0.5 * n * (3 if planner.endswith("U") else 1)))
    solved = t < limit
    est = min(1.0, max(0.0, rng.gauss(0.7, 0.15)))
    row = {"approximate solution BOOLEAN": "0" if solved else "1",
           "cells INTEGER": str(rng.randint(100, 2000)), "correct solution BOOLEAN": "1",
           "estimated success REAL": f"{est:.3f}" if solved and planner.startswith("pKP") else "",
           "execution success REAL": (f"{min(1, max(0, est + rng.gauss(-0.05, 0.1))):.2f}"
                                      if solved and validate else ""),
           "graph motions INTEGER": str(rng.randint(100, 5000)),
           "graph states INTEGER": str(rng.randint(100, 5000)),
           "memory REAL": f"{rng.uniform(20, 90):.1f}", "objects moved INTEGER": str(rng.randint(0, n)),
           "particles INTEGER": str(rng.randint(0, 5000)), "seed INTEGER": str(seed + r),
           "solution difference REAL": "0" if solved else f"{rng.uniform(0.01, 0.2):.4f}",
           "solution length REAL": f"{rng.uniform(0.5, 2):.4f}",
           "solution segments INTEGER": str(rng.randint(3, 20)),
           "solved BOOLEAN": "1" if solved else "0", "status ENUM": "6" if solved else "5",
           "time REAL": f"{t if solved else limit + 0.01:.4f}"}
    return "".join(row[p] + "; " for p in PROPS)


def write_log(path, problem, seed, limit, runs, blocks):
    lines = header(problem, seed, limit, runs, len(blocks),
                   sum(float(row.split("; ")[-2]) for _, rows in blocks for row in rows))
    for planner, rows in blocks:
        lines += [f"control_{planner}", "1 common properties", "goal_bias = 0.05",
                  f"{len(PROPS)} properties for each run"] + PROPS + [f"{len(rows)} runs"]
        lines += rows + ["."]
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def bench(args):
    i, n = (int(x) for x in args.shard.split("/")) if args.shard else (1, 1)
    if not 1 <= i <= n:
        sys.exit(f"stub: bad --shard {args.shard}")
    planners = args.planners.split(",")
    problems = args.problems or ["kuka_clutter_5", "kuka_clutter_10"]
    index = 0
    for problem in problems:
        blocks = []
        for planner in planners:
            rows = []
            for r in range(args.runs):
                if index % n == i - 1:
                    rows.append(fake_run(problem, planner, r, args.seed, args.time,
                                         args.validate > 0))
                index += 1
            blocks.append((planner, rows))
        write_log(os.path.join(args.output, "logs", f"{problem}.log"), problem, args.seed,
                  args.time, args.runs, blocks)
    print(f"stub kautham bench: shard {i}/{n}: wrote {len(problems)} log(s) to "
          f"{args.output}/logs")


def parse_log(path):
    with open(path) as f:
        lines = f.read().splitlines()
    problem = lines[1].split(" ", 1)[1]
    seed = int(lines[lines.index("|>>>", lines.index("|>>>") + 1) + 1].split()[0])
    limit = float(next(x for x in lines if x.endswith(" seconds per run")).split()[0])
    at = next(k for k, x in enumerate(lines) if x.endswith(" planners")) + 1
    blocks = []
    while at < len(lines) and lines[at]:
        planner = lines[at].removeprefix("control_")
        at += 1 + int(lines[at + 1].split()[0]) + 1          # name, common properties
        at += int(lines[at].split()[0]) + 1                  # property names
        count = int(lines[at].split()[0])
        blocks.append((planner, lines[at + 1:at + 1 + count]))
        at += 1 + count + 1                                  # runs and "."
    return problem, seed, limit, blocks


def merge(args):
    merged = {}
    for folder in args.problems:
        for path in sorted(glob.glob(os.path.join(folder, "logs", "*.log"))):
            problem, seed, limit, blocks = parse_log(path)
            entry = merged.setdefault(problem, {"seed": seed, "limit": limit, "planners": {}})
            for planner, rows in blocks:
                entry["planners"].setdefault(planner, []).extend(rows)
    if not merged:
        sys.exit("stub: --merge-only found no logs in " + " ".join(args.problems))
    for problem, entry in merged.items():
        blocks = list(entry["planners"].items())
        runs = max(len(rows) for _, rows in blocks)
        write_log(os.path.join(args.output, "logs", f"{problem}.log"), problem, entry["seed"],
                  entry["limit"], runs, blocks)
    print(f"stub kautham bench --merge-only: {len(merged)} problem(s) from "
          f"{len(args.problems)} folder(s) -> {args.output}/logs")


def main():
    if len(sys.argv) < 2 or sys.argv[1] != "bench":
        sys.exit("stub: only 'bench' is implemented (see --help of the script)")
    p = argparse.ArgumentParser(prog="kautham-bench-stub.py bench")
    p.add_argument("problems", nargs="*")
    p.add_argument("--file")
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--time", type=float, default=60)
    p.add_argument("--threads", type=int, default=1)
    p.add_argument("--validate", type=int, default=0)
    p.add_argument("--jobs", type=int, default=1)
    p.add_argument("--shard")
    p.add_argument("--planners", default="pKPU,pKP,o-KPIECE,KPIECE")
    p.add_argument("--merge-only", action="store_true")
    p.add_argument("-o", "--output", required=True)
    args = p.parse_args(sys.argv[2:])
    merge(args) if args.merge_only else bench(args)


if __name__ == "__main__":
    main()
