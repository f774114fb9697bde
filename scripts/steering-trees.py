#!/usr/bin/env python3
"""Where the goal steering of each of p-KPIECE's trees gets on its own, tree by tree.

With `push_angle_spread`, every tree from `push_angle_after` on pushes each object at an angle
of its own (docs/planners.md). This follows the steering of trees 0 to N-1 alone, without a
search (`kautham plan FILE --planner goal-steering --set tree=K`), and prints one line per tree:
whether it reached the goal, how far from the goal it ended, after how many motions, and the
rule it broke (by which object) or why else it stopped. Then the trees that reached the goal,
and the distinct ends, most frequent first. The angles depend on the seed, the tree's number
and the object only: under the same `--seed` a tree whose steering alone reaches the goal does
so in every run, and p-KPIECE's search with that seed grows that tree with those pushes.

Usage: python3 scripts/steering-trees.py problems/yumi_clutter_35.xml --trees 100 \\
           --seed 1 --set push_angle_spread=0.8
Runs $KAUTHAM or build/apps/kautham. Exit codes: 0 done, 2 bad input (a missing file, a
`kautham plan` that fails: its message is printed).
"""
import argparse
import collections
import json
import os
import sys
import tempfile

from kautham_runs import KAUTHAM, run


def follow(problem, tree, seed, sets):
    """One tree's steering: (reached, goal distance in cm, motions, how it stopped)."""
    with tempfile.NamedTemporaryFile(suffix=".json", delete=False) as f:
        out = f.name
    command = [KAUTHAM, "plan", problem, "--planner", "goal-steering", "--seed", str(seed),
               "--set", f"tree={tree}", "-o", out]
    for s in sets:
        command += ["--set", s]
    result = run(command)
    try:
        with open(out) as f:
            plan = json.load(f)
    except (OSError, ValueError):
        print(f"steering-trees: tree {tree}: `kautham plan` wrote no plan "
              f"(exit {result.returncode}):\n{result.stderr or result.stdout}", file=sys.stderr)
        sys.exit(2)
    finally:
        if os.path.exists(out):
            os.unlink(out)
    replay = plan["result"]["replay"]
    properties = plan["statistics"]["planner"]
    failures = plan["statistics"]["candidate_failures"]
    if replay["reached_goal"]:
        stop = "reached the goal"
    elif failures:
        stop = f"{failures[0]['reason']} ({failures[0]['object'] or 'the robot'})"
    elif properties.get("no_motion") == "1":
        stop = "no motion to give"
    elif properties.get("stalled") == "1":
        stop = "stalled"
    else:
        stop = "time ran out"
    return (replay["reached_goal"], 100.0 * replay["final_goal_distance"],
            int(properties.get("motions", "0")), stop)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("problem", help="a problem file")
    parser.add_argument("--trees", type=int, default=50, help="trees 0 to N-1 (default 50)")
    parser.add_argument("--first", type=int, default=0, help="the first tree (default 0)")
    parser.add_argument("--seed", type=int, default=1,
                        help="the search's seed, which draws the trees' angles (default 1, as "
                        "`kautham plan`'s)")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                        help="a p-KPIECE parameter, as `kautham plan --set` (repeatable)")
    args = parser.parse_args()
    if not os.path.isfile(args.problem):
        print(f"steering-trees: {args.problem}: no such file", file=sys.stderr)
        return 2
    if args.trees < 1 or args.first < 0 or not 1 <= args.seed <= 4294967295:
        print("steering-trees: --trees must be at least 1, --first at least 0 and --seed in "
              "[1, 4294967295]", file=sys.stderr)
        return 2
    problem = os.path.abspath(args.problem)
    ends = collections.Counter()
    reached = []
    print(f"{'tree':>5}  {'goal':>4}  {'off cm':>6}  {'motions':>7}  stopped")
    for tree in range(args.first, args.first + args.trees):
        at_goal, off, motions, stop = follow(problem, tree, args.seed, args.set)
        print(f"{tree:>5}  {'yes' if at_goal else 'no':>4}  {off:>6.1f}  {motions:>7}  {stop}",
              flush=True)
        if at_goal:
            reached.append(tree)
        ends[stop] += 1
    print(f"\nreached the goal: {len(reached)} of {args.trees} trees"
          + (f" ({', '.join(map(str, reached))})" if reached else ""))
    for stop, count in ends.most_common():
        print(f"  {count:>4}  {stop}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
