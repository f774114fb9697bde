#!/usr/bin/env python3
"""Figures and tables of a `kautham bench` campaign, from OMPL benchmark logs or their database.

Input (one of):
  - a Planner Arena SQLite database, as written by Debian's `ompl_benchmark_statistics`
    (package ompl-demos; tables experiments, plannerConfigs, enums, runs, progress);
  - `kautham bench`'s output folder OUT (its logs are OUT/logs/*.log), a folder of .log files,
    or .log files: then `ompl_benchmark_statistics` builds OUTPUT/benchmark.db from them first.

Output, in the folder given by -o (default: INPUT/report for a folder, the database's folder
/report for a database):
  fig_success      planning success rate vs number of objects N, one line per planner, 95 %
                   Wilson intervals, one panel per robot (the problem name without its trailing
                   _N: kuka_clutter, yumi_clutter, ...)
  fig_time         planning time vs N: median with a 95 % order-statistic (binomial) interval
                   of the median, and the mean; unsolved runs count at the time limit
  fig_execution    execution success vs N: median (order-statistic interval) and mean
                   (bootstrap percentile interval) of the validated execution success per run,
                   a run whose planning failed counting 0 %
  fig_calibration  the planner's estimated success vs the measured execution success, one point
                   per solved and validated plan, with the diagonal and the mean gap
  (each as .svg and .png), table.md (a markdown table for the docs), summary.json (every number
  of the tables) and index.html (the figures and the tables); given `kautham bench`'s output
  folder, also failures.md: why the executions of its validated plans failed, per problem and
  configuration (goal missed: the free space not clear, and what was in it, or the gripper off
  the goal pose; objects tipped; the target touched; ...), from its
  plans/PROBLEM/CONFIG/run-R.validation.json.

Definitions:
  - planning success: `solved` is 1 and `approximate solution` is not 1 (OMPL 1.5.2 writes
    solved = 1 for exact solutions only); without a `solved` column, status "Exact solution".
  - N: the trailing integer of the problem name (kuka_clutter_25 -> 25). Problems without one
    are in the tables but not in the figures against N.
  - planner: the log's planner name without OMPL's "control_"/"geometric_" prefix. Runs of one
    problem and planner from several logs (for example shards) are pooled.

Usage:
  /usr/bin/python3 scripts/bench-report.py OUT                     # kautham bench's folder
  /usr/bin/python3 scripts/bench-report.py benchmark.db -o report/
  /usr/bin/python3 scripts/bench-report.py a.log b.log -o report/ --paper

Needs Python 3 with matplotlib (Debian: /usr/bin/python3 and python3-matplotlib). Run with
another python3 lacking matplotlib, it runs itself again with /usr/bin/python3; if that has no
matplotlib either, it writes the tables without figures and says so. Exit codes: 0 written,
2 bad input (a missing file, no runs, a database that is not a benchmark database, ...).
"""

import argparse
import glob
import html
import json
import math
import os
import random
import re
import shutil
import sqlite3
import subprocess
import sys

# The shared statistics sit beside this script (also when a test loads it by its path).
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from kautham_stats import wilson  # noqa: E402


# The paper's Table I (Muhayyuddin et al., RA-L 2018; i7-4500U, 30 runs per scene; the robot is
# not given): N -> (success %, mean planning time s); None where the paper has "-".
# pKP: p-KPIECE without uncertainty, pKPU: with; TP (Srivastava et al. 2014) and TPU
# (Hadfield-Menell et al. 2015) are task-and-motion planners, their numbers from those papers.
PAPER = {
    "pKPU": {5: (100, 9.88), 10: (100, 14.52), 15: (90, 29.43), 20: (86, 47.61),
             25: (73, 72.28), 30: (66, 103.07), 35: (53, 134.94), 40: (40, 182.19)},
    "pKP": {5: (100, 2.89), 10: (100, 5.96), 15: (100, 9.15), 20: (100, 16.78),
            25: (96, 26.09), 30: (90, 41.21), 35: (73, 49.62), 40: (60, 71.64)},
    "TP": {15: (100, 32), 20: (94, 57), 25: (90, 69), 30: (84, 77), 35: (67, 41), 40: (63, 68)},
    "TPU": {5: (95, 89), 10: (95, 162), 15: (83, 135), 20: (70, 229), 25: (68, 166),
            30: (48, 122)},
}


class BadInput(Exception):
    pass


# ----------------------------------------------------------------------------- statistics


def median(values):
    v = sorted(values)
    n = len(v)
    if n == 0:
        return None
    return v[n // 2] if n % 2 else (v[n // 2 - 1] + v[n // 2]) / 2


def mean(values):
    return sum(values) / len(values) if values else None


def binom_half_cdf(k, n):
    """P(B <= k) for B ~ Binomial(n, 1/2), exact."""
    if k < 0:
        return 0.0
    return sum(math.comb(n, i) for i in range(0, min(k, n) + 1)) / 2**n


def median_interval(values, level=0.95):
    """A distribution-free interval of the median from order statistics.

    Returns (low, high, coverage): [x_(l), x_(n+1-l)] with the largest l such that the
    coverage 1 - 2 P(B <= l-1), B ~ Binomial(n, 1/2), is at least `level`. With fewer than 6
    values no such l exists: then it is [min, max] with its (smaller) coverage.
    """
    v = sorted(values)
    n = len(v)
    if n == 0:
        return None
    best = 1
    for low in range(1, n // 2 + 1):
        if 1 - 2 * binom_half_cdf(low - 1, n) >= level:
            best = low
        else:
            break
    coverage = 1 - 2 * binom_half_cdf(best - 1, n)
    return v[best - 1], v[n - best], coverage


def bootstrap_mean_interval(values, level=0.95, resamples=2000, seed=12345):
    """A percentile bootstrap interval of the mean (a fixed seed: the same data, the same
    interval)."""
    n = len(values)
    if n == 0:
        return None
    if n == 1 or min(values) == max(values):
        return values[0], values[0]
    rng = random.Random(seed)
    means = sorted(sum(rng.choice(values) for _ in range(n)) / n for _ in range(resamples))
    a = (1 - level) / 2
    return means[int(math.floor(a * (resamples - 1)))], means[int(math.ceil((1 - a) * (resamples - 1)))]


# ----------------------------------------------------------------------------- input


def find_statistics_program(explicit):
    for candidate in ([explicit] if explicit else []) + [
            shutil.which("ompl_benchmark_statistics"), "/usr/bin/ompl_benchmark_statistics"]:
        if candidate and os.path.isfile(candidate):
            return candidate
    raise BadInput("ompl_benchmark_statistics not found: install Debian's ompl-demos "
                   "(apt-get install ompl-demos) or give --ompl-benchmark-statistics PATH")


def collect_logs(inputs):
    logs = []
    for path in inputs:
        if os.path.isdir(path):
            found = sorted(glob.glob(os.path.join(path, "*.log")))
            if not found:
                found = sorted(glob.glob(os.path.join(path, "logs", "*.log")))
            if not found:
                raise BadInput(f"{path}: a folder without .log files (nor logs/*.log)")
            logs += found
        elif os.path.isfile(path):
            logs.append(path)
        else:
            raise BadInput(f"{path}: no such file or folder")
    return logs


def is_sqlite(path):
    try:
        with open(path, "rb") as f:
            return f.read(16) == b"SQLite format 3\x00"
    except OSError:
        return False


def build_database(logs, db, program):
    os.makedirs(os.path.dirname(os.path.abspath(db)), exist_ok=True)
    if os.path.exists(db):
        os.remove(db)
    # The program runs with its own shebang (/usr/bin/python3), whatever python runs us.
    result = subprocess.run([program, "-d", db] + logs, capture_output=True, text=True)
    if result.returncode != 0 or not os.path.exists(db):
        if os.path.exists(db):
            os.remove(db)
        processing = [line[len("Processing "):] for line in result.stdout.splitlines()
                      if line.startswith("Processing ")]
        culprit = processing[-1] if processing else " ".join(logs[:3])
        last = (result.stderr or result.stdout).strip().splitlines()[-1:]
        raise BadInput(f"{culprit}: not an OMPL benchmark log (ompl_benchmark_statistics: "
                       f"{' '.join(last) or 'exit ' + str(result.returncode)})")


def planner_name(name):
    for prefix in ("control_", "geometric_"):
        if name.startswith(prefix):
            return name[len(prefix):]
    return name


def problem_family(problem):
    """('kuka_clutter', 25) for kuka_clutter_25; (problem, None) without a trailing integer."""
    m = re.match(r"^(.*?)[_-]?(\d+)$", problem)
    if not m or not m.group(1):
        return problem, None
    return m.group(1), int(m.group(2))


def read_database(db):
    """Runs as a list of dicts: problem, planner, timelimit, success, time, execution,
    estimated, plus which optional columns the database has."""
    try:
        conn = sqlite3.connect(f"file:{os.path.abspath(db)}?mode=ro", uri=True)
        tables = {r[0] for r in conn.execute("SELECT name FROM sqlite_master WHERE type='table'")}
    except sqlite3.DatabaseError as e:
        raise BadInput(f"{db}: not an SQLite database ({e})")
    missing = {"experiments", "plannerConfigs", "runs"} - tables
    if missing:
        raise BadInput(f"{db}: not a benchmark database (no table {', '.join(sorted(missing))}); "
                       "make one with ompl_benchmark_statistics")
    columns = {r[1] for r in conn.execute("PRAGMA table_info(runs)")}
    if "solved" not in columns and "status" not in columns:
        raise BadInput(f"{db}: the runs have neither a 'solved' nor a 'status' property")
    status_names = {}
    if "enums" in tables:
        status_names = {int(v): d for v, d in conn.execute(
            "SELECT value, description FROM enums WHERE name='status'")}
    exact_status = None
    if "solved" not in columns:
        row = conn.execute("SELECT value FROM enums WHERE name='status' AND "
                           "description='Exact solution'").fetchone()
        exact_status = row[0] if row else 6

    def col(name):
        return f"runs.{name}" if name in columns else "NULL"

    query = (f"SELECT experiments.name, experiments.timelimit, plannerConfigs.name, "
             f"{col('solved')}, {col('approximate_solution')}, {col('status')}, {col('time')}, "
             f"{col('execution_success')}, {col('estimated_success')}, {col('objects_moved')} "
             "FROM runs JOIN experiments ON runs.experimentid = experiments.id "
             "JOIN plannerConfigs ON runs.plannerid = plannerConfigs.id ORDER BY runs.id")
    runs = []
    for (problem, limit, planner, solved, approx, status, time, execution, estimated,
         moved) in conn.execute(query):
        if "solved" in columns:
            success = _num(solved) == 1 and _num(approx) != 1
        else:
            success = _num(status) == exact_status
        code = _num(status)
        runs.append({"status": status_names.get(int(code), str(int(code)))
                     if code is not None else None,
                     "problem": problem, "planner": planner_name(planner),
                     "timelimit": _num(limit), "success": success, "time": _num(time),
                     "execution": _num(execution), "estimated": _num(estimated),
                     "objects_moved": _num(moved)})
    conn.close()
    if not runs:
        raise BadInput(f"{db}: no runs")
    return runs, columns


def _num(x):
    if x is None or x == "":
        return None
    try:
        v = float(x)
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) else None


# ----------------------------------------------------------------------------- summary


def summarise(runs):
    """One entry per (problem, planner), in the order they first appear."""
    groups = {}
    # a planner is validated in this campaign if any of its runs has an execution success
    validated_planners = {r["planner"] for r in runs if r["execution"] is not None}
    for r in runs:
        groups.setdefault((r["problem"], r["planner"]), []).append(r)
    cells = []
    for (problem, planner), rs in groups.items():
        family, n_objects = problem_family(problem)
        n = len(rs)
        k = sum(1 for r in rs if r["success"])
        limits = [r["timelimit"] for r in rs if r["timelimit"] is not None]
        limit = max(limits) if limits else None
        # planning time: unsolved runs count at the time limit
        times = []
        for r in rs:
            if r["success"] and r["time"] is not None:
                times.append(r["time"])
            elif not r["success"]:
                t = limit if limit is not None else r["time"]
                if t is not None:
                    times.append(t)
        solved_times = [r["time"] for r in rs if r["success"] and r["time"] is not None]
        # execution success: a failed planning counts 0; solved runs without validation are out
        validated = [r["execution"] for r in rs if r["success"] and r["execution"] is not None]
        execution = (validated + [0.0] * (n - k)
                     if validated or (planner in validated_planners and k == 0) else [])
        not_validated = sum(1 for r in rs if r["success"] and r["execution"] is None)
        calibration = [(r["estimated"], r["execution"]) for r in rs
                       if r["success"] and r["estimated"] is not None
                       and r["execution"] is not None]
        # runs that ended neither with a solution nor by the time limit (crashed, aborted, ...)
        failed = sum(1 for r in rs if not r["success"] and r["status"] is not None
                     and r["status"] not in ("Timeout", "Approximate solution"))
        ci = wilson(k, n)
        mi = median_interval(times)
        ei = median_interval(execution)
        cells.append({
            "problem": problem, "family": family, "objects": n_objects, "planner": planner,
            "runs": n, "solved": k, "failed": failed, "success_rate": k / n if n else None,
            "success_wilson95": list(ci) if ci else None,
            "time_limit": limit,
            "time_median": median(times), "time_median_interval": list(mi[:2]) if mi else None,
            "time_median_interval_coverage": mi[2] if mi else None,
            "time_mean": mean(times), "time_mean_solved": mean(solved_times),
            "execution_runs": len(execution), "execution_not_validated": not_validated,
            "execution_median": median(execution),
            "execution_median_interval": list(ei[:2]) if ei else None,
            "execution_median_interval_coverage": ei[2] if ei else None,
            "execution_mean": mean(execution),
            "execution_mean_interval": list(bootstrap_mean_interval(execution) or []) or None,
            "calibration_points": len(calibration),
            "calibration_mean_gap": mean([e - x for e, x in calibration]),
            "calibration": calibration,
        })
    order = {}
    for c in cells:
        order.setdefault(c["planner"], len(order))
    cells.sort(key=lambda c: (c["family"], c["objects"] if c["objects"] is not None else -1,
                              c["problem"], order[c["planner"]]))
    return cells, list(order)


# Our planners that stand for the paper's columns under another name.
PAPER_ALIASES = {"tmp": "tp", "tmp-u": "tpu"}


def is_paper_planner(planner, name):
    """Whether our configuration `planner` is the paper's column `name` (TMP is its TP)."""
    ours = planner.lower()
    return PAPER_ALIASES.get(ours, ours) == name.lower()


def paper_value(planner, n_objects):
    for name, table in PAPER.items():
        if is_paper_planner(planner, name):
            return table.get(n_objects)
    return None


# ----------------------------------------------------------------------------- tables


def pct(x, digits=0):
    return "—" if x is None else f"{100 * x:.{digits}f}"


def secs(x):
    return "—" if x is None else f"{x:.2f}"


def table_rows(cells, with_paper):
    header = ["problem", "planner", "runs", "solved %", "95 % Wilson", "median time s",
              "[95 % interval]", "mean time s", "mean time solved s", "exec. median %",
              "exec. mean %"]
    with_failed = any(c["failed"] for c in cells)
    if with_failed:
        header.insert(3, "failed")
    if with_paper:
        header.append("paper (solved %, mean s)")
    rows = []
    for c in cells:
        ci = c["success_wilson95"]
        mi = c["time_median_interval"]
        row = [c["problem"], c["planner"], str(c["runs"]),
               pct(c["success_rate"], 1),
               f"[{pct(ci[0], 1)}, {pct(ci[1], 1)}]" if ci else "—",
               secs(c["time_median"]),
               f"[{secs(mi[0])}, {secs(mi[1])}]" if mi else "—",
               secs(c["time_mean"]), secs(c["time_mean_solved"]),
               pct(c["execution_median"], 1), pct(c["execution_mean"], 1)]
        if with_failed:
            row.insert(3, str(c["failed"]))
        if with_paper:
            p = paper_value(c["planner"], c["objects"]) if c["objects"] is not None else None
            row.append(f"{p[0]}, {p[1]:.2f}" if p else "")
        rows.append(row)
    return header, rows


def write_markdown(path, cells, with_paper, notes):
    header, rows = table_rows(cells, with_paper)
    lines = ["| " + " | ".join(header) + " |",
             "|" + "|".join("---" if i < 2 else "---:" for i in range(len(header))) + "|"]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    lines.append("")
    lines += notes
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def table_notes(cells):
    limits = sorted({c["time_limit"] for c in cells if c["time_limit"] is not None})
    limit_text = ", ".join(f"{x:g} s" for x in limits) or "unknown"
    notes = [
        "Solved %: plans found within the time limit (exact solutions), with the 95 % Wilson "
        "score interval. Times: unsolved runs count at the time limit "
        f"({limit_text}); the median's interval is distribution-free (order statistics, "
        "binomial), at least 95 % from 6 runs on (below that: min-max). \"Mean time solved\" "
        "averages the solved runs only.",
        "Execution success: the fraction of `kautham validate` executions of a run's plan "
        "that succeeded, a run whose planning failed counting 0 %; solved runs without "
        "validation are left out; \"—\" where no plan was validated.",
    ]
    if any(c["failed"] for c in cells):
        notes.insert(1, "Failed: runs that ended neither with a solution nor by the time limit "
                     "(OMPL status Crash, ...); they count as not solved, at the time limit.")
    return notes


def paper_markdown():
    ns = sorted({n for t in PAPER.values() for n in t})
    lines = ["| N | " + " | ".join(f"{p} solved % | {p} mean s" for p in PAPER) + " |",
             "|---:|" + "---:|" * (2 * len(PAPER))]
    for n in ns:
        cells = []
        for p in PAPER:
            v = PAPER[p].get(n)
            cells += [str(v[0]), f"{v[1]:g}"] if v else ["—", "—"]
        lines.append(f"| {n} | " + " | ".join(cells) + " |")
    return lines


# ----------------------------------------------------------------------------- failures

# The validation's failure kinds (`kautham validate --json`, "failures"), in the table's order.
FAILURE_KINDS = [("goal_missed", "goal missed"), ("object_fell_or_tipped", "object tipped"),
                 ("target_touched", "target touched"), ("too_fast", "too fast"),
                 ("other", "other")]


def plans_folders(inputs):
    """The plans/ folders of `kautham bench` output folders among the inputs, and of their
    shards (a Slurm campaign's OUT/shard-I), the folder's own first; each with its bench's label:
    the output folder's name when several benches are read (their runs are numbered alike, and
    must not be taken for one another), else ""."""
    benches = [p for p in inputs if os.path.isdir(p)]
    folders = []
    for p in benches:
        label = os.path.basename(os.path.normpath(p)) if len(benches) > 1 else ""
        folders += [(label, f) for f in [os.path.join(p, "plans")] if os.path.isdir(f)]
        folders += [(label, f) for f in sorted(glob.glob(os.path.join(p, "shard-*", "plans")))]
    return folders


def read_validation(path):
    try:
        with open(path) as f:
            report = json.load(f)
    except (OSError, ValueError) as e:
        raise BadInput(f"{path}: not a readable validation file ({e}); run `kautham validate "
                       "PROBLEM PLAN --json` again, or move the file away")
    if not isinstance(report, dict) or report.get("format") != "kautham-validation":
        raise BadInput(f"{path}: not a `kautham validate --json` report (no \"format\": "
                       "\"kautham-validation\")")
    return report


def read_failures(folders):
    """Why the executions failed, per problem and configuration, from the validation reports
    `kautham bench` writes beside its plans (OUT/plans/PROBLEM/CONFIG/run-R.validation.json)."""
    groups = {}
    # A run found in two folders of one bench (its shards) counts once, from the first (as
    # bench's merge); two benches' runs are told apart by their labels.
    seen = set()
    for label, folder in folders:
        pattern = os.path.join(folder, "*", "*", "run-*.validation.json")
        for path in sorted(glob.glob(pattern)):
            config_dir = os.path.dirname(path)
            problem = os.path.basename(os.path.dirname(config_dir))
            key = (f"{label}/{problem}" if label else problem, os.path.basename(config_dir))
            if (key, os.path.basename(path)) in seen:
                continue
            seen.add((key, os.path.basename(path)))
            report = read_validation(path)
            g = groups.setdefault(key, {
                "problem": key[0], "configuration": key[1], "plans": 0, "executions": 0,
                "successes": 0, "failures": {k: 0 for k, _ in FAILURE_KINDS},
                "free_space_not_clear": 0, "free_space_objects": {}, "goal_pose_missed": 0,
                "off_pose_touching_nothing": 0, "off_pose_touching_unknown": False,
                "rule_breakers": {}})
            try:
                add_validation(g, report)
            except (AttributeError, KeyError, TypeError, ValueError) as e:
                raise BadInput(f"{path}: a validation report with a field of the wrong kind "
                               f"({type(e).__name__}: {e}); run `kautham validate PROBLEM PLAN "
                               "--json` again, or move the file away")
    return [groups[k] for k in sorted(groups)]


def add_validation(g, report):
    """Adds one plan's validation report to its problem and configuration's counts."""
    g["plans"] += 1
    g["executions"] += int(report.get("runs", 0))
    g["successes"] += int(report.get("successes", 0))
    for kind, _ in FAILURE_KINDS:
        g["failures"][kind] += int(report.get("failures", {}).get(kind, 0))
    free = report.get("free_space_not_clear", {})
    g["free_space_not_clear"] += int(free.get("runs", 0))
    count_into(g["free_space_objects"], free.get("by_object", {}).items())
    pose = report.get("goal_pose_missed", {})
    g["goal_pose_missed"] += int(pose.get("runs", 0))
    # Reports from before validate said what the robot touched there cannot be split.
    if "touching_nothing" in pose:
        g["off_pose_touching_nothing"] += int(pose["touching_nothing"])
    elif int(pose.get("runs", 0)) > 0:
        g["off_pose_touching_unknown"] = True
    count_into(g["rule_breakers"], ((r["object"], 1) for r in report.get("results", [])
                                    if r.get("violation", "none") != "none"
                                    and r.get("object")))


def count_into(counts, items):
    for name, n in items:
        counts[name] = counts.get(name, 0) + int(n)


def most(counts, k=3):
    top = sorted(counts.items(), key=lambda x: (-x[1], x[0]))
    text = ", ".join(f"{name} {n}" for name, n in top[:k])
    return text + (f" (+{len(top) - k} more)" if len(top) > k else "")


def failure_rows(groups):
    header = ["problem", "configuration", "plans", "executions", "success %", "goal missed %",
              "free space not clear %", "in the free space", "gripper off the goal pose %",
              "off the pose touching nothing %"] + \
        [f"{label} %" for kind, label in FAILURE_KINDS if kind != "goal_missed"] + \
        ["objects that broke a rule"]
    rows = []
    for g in groups:
        n = g["executions"]

        def share(count):
            return pct(count / n, 1) if n else "—"

        rows.append([g["problem"], g["configuration"], str(g["plans"]), str(n),
                     share(g["successes"]), share(g["failures"]["goal_missed"]),
                     share(g["free_space_not_clear"]), most(g["free_space_objects"]),
                     share(g["goal_pose_missed"]),
                     "—" if g["off_pose_touching_unknown"]
                     else share(g["off_pose_touching_nothing"])]
                    + [share(g["failures"][kind]) for kind, _ in FAILURE_KINDS
                       if kind != "goal_missed"]
                    + [most(g["rule_breakers"])])
    return header, rows


FAILURE_NOTE = ("Why the executions of the validated plans failed, as shares of all their "
                "executions (`kautham validate`; unsolved runs have no executions). A goal "
                "missed is the free space not clear at the end, the gripper off the goal pose, "
                "or both, so those two columns may add up to more; \"off the pose touching "
                "nothing\": the executions that ended off the goal pose with the robot touching "
                "nothing there (put off its course earlier, not held up at the end; — where a "
                "report is from before validate said so); \"in the free space\": the "
                "objects found there most (executions); \"objects that broke a rule\": the "
                "object named by each execution that broke one (tipped, moved the target, too "
                "fast), most first.")


def write_failures(path, groups):
    header, rows = failure_rows(groups)
    lines = ["| " + " | ".join(header) + " |",
             "|" + "|".join("---" if i < 2 or i == 7 or i == len(header) - 1 else "---:"
                            for i in range(len(header))) + "|"]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    lines += ["", FAILURE_NOTE]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


# ----------------------------------------------------------------------------- figures


def load_matplotlib():
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        matplotlib.rcParams["svg.hashsalt"] = "kautham-bench-report"  # reproducible SVG ids
        return plt
    except ImportError:
        return None


def families_with_n(cells):
    fams = []
    for c in cells:
        if c["objects"] is not None and c["family"] not in fams:
            fams.append(c["family"])
    return fams


def colours(planners):
    palette = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2",
               "#7f7f7f", "#bcbd22", "#17becf"]
    return {p: palette[i % len(palette)] for i, p in enumerate(planners)}


def series(cells, family, planner, value):
    pts = [c for c in cells if c["family"] == family and c["planner"] == planner
           and c["objects"] is not None]
    pts.sort(key=lambda c: c["objects"])
    out = []
    for c in pts:
        v = value(c)
        if v is not None:
            out.append((c["objects"], v))
    return out


def dodge(planners, planner, width):
    i = planners.index(planner)
    return (i - (len(planners) - 1) / 2) * width


def errorbar(ax, pts, offset, colour, label, style="-", marker="o"):
    xs = [x + offset for x, (y, lo, hi) in pts]
    ys = [y for _, (y, lo, hi) in pts]
    low = [max(0.0, y - lo) if lo is not None else 0 for _, (y, lo, hi) in pts]
    high = [max(0.0, hi - y) if hi is not None else 0 for _, (y, lo, hi) in pts]
    ax.errorbar(xs, ys, yerr=[low, high], color=colour, label=label, linestyle=style,
                marker=marker, markersize=4, capsize=3, linewidth=1.3)


def save(fig, outdir, name, written):
    for ext in ("svg", "png"):
        path = os.path.join(outdir, f"{name}.{ext}")
        fig.savefig(path, dpi=130, bbox_inches="tight",
                    metadata={"Date": None} if ext == "svg" else None)
        written.append(path)


def paper_overlay(ax, planners, cols, index, with_paper, family_n):
    """The paper's Table I as hollow markers; index 0 = success %, 1 = mean time."""
    if not with_paper:
        return
    extra = ["#555555", "#999999"]
    for name, table in PAPER.items():
        ours = [p for p in planners if is_paper_planner(p, name)]
        colour = cols[ours[0]] if ours else extra[0 if name == "TP" else 1]
        pts = sorted((n, v[index]) for n, v in table.items() if n in family_n)
        if not pts:
            continue
        ys = [y / 100 if index == 0 else y for _, y in pts]
        ax.plot([x for x, _ in pts], ys, linestyle=":", marker="s", markersize=5,
                markerfacecolor="none", color=colour, linewidth=1, label=f"paper {name}")


def figures(plt, cells, planners, outdir, with_paper, written):
    fams = families_with_n(cells)
    cols = colours(planners)
    if not fams:
        return ["No problem name ends with its number of objects: no figure against N."]
    notes = []
    limits = sorted({c["time_limit"] for c in cells if c["time_limit"] is not None})
    limit_text = "/".join(f"{x:g}" for x in limits) or "?"
    width = 0.35

    def family_ns(f):
        return sorted({c["objects"] for c in cells if c["family"] == f and c["objects"] is not None})

    # (a) planning success
    fig, axes = plt.subplots(1, len(fams), figsize=(5.2 * len(fams), 4.0), squeeze=False)
    for ax, fam in zip(axes[0], fams):
        for p in planners:
            pts = series(cells, fam, p, lambda c: (c["success_rate"], *c["success_wilson95"])
                         if c["success_wilson95"] else None)
            if pts:
                errorbar(ax, pts, dodge(planners, p, width), cols[p], p)
        paper_overlay(ax, planners, cols, 0, with_paper, family_ns(fam))
        ax.set_title(fam)
        ax.set_xlabel("number of objects N")
        ax.set_ylabel("planning success rate")
        ax.set_ylim(-0.03, 1.05)
        ax.set_xticks(family_ns(fam))
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.text(0.01, -0.02, "Error bars: 95 % Wilson score intervals."
             + (" Hollow squares: the paper's Table I (robot not given)." if with_paper else ""),
             fontsize=8, ha="left")
    save(fig, outdir, "fig_success", written)
    plt.close(fig)

    # (b) planning time
    fig, axes = plt.subplots(2, len(fams), figsize=(5.2 * len(fams), 7.6), squeeze=False)
    for j, fam in enumerate(fams):
        for p in planners:
            pts = series(cells, fam, p, lambda c: (c["time_median"], *c["time_median_interval"])
                         if c["time_median_interval"] else None)
            if pts:
                errorbar(axes[0][j], pts, dodge(planners, p, width), cols[p], p)
            pts = series(cells, fam, p, lambda c: c["time_mean"])
            if pts:
                axes[1][j].plot([x + dodge(planners, p, width) for x, _ in pts],
                                [y for _, y in pts], color=cols[p], marker="o", markersize=4,
                                label=p)
        paper_overlay(axes[1][j], planners, cols, 1, with_paper, family_ns(fam))
        for i, what in enumerate(("median", "mean")):
            ax = axes[i][j]
            ax.set_title(f"{fam}: {what} planning time")
            ax.set_xlabel("number of objects N")
            ax.set_ylabel(f"{what} planning time (s)")
            ax.set_xticks(family_ns(fam))
            ax.set_ylim(bottom=0)
            for lim in limits:
                ax.axhline(lim, color="grey", linestyle="--", linewidth=0.8)
            ax.grid(alpha=0.3)
            ax.legend(fontsize=8)
    fig.text(0.01, -0.01, f"Unsolved runs count at the time limit ({limit_text} s, dashed). "
             "Median error bars: 95 % distribution-free interval of the median "
             "(order statistics; min-max below 6 runs)."
             + (" Hollow squares: the paper's Table I mean times." if with_paper else ""),
             fontsize=8, ha="left")
    fig.tight_layout()
    save(fig, outdir, "fig_time", written)
    plt.close(fig)

    # (c) execution success
    if any(c["execution_runs"] for c in cells):
        fig, axes = plt.subplots(2, len(fams), figsize=(5.2 * len(fams), 7.6), squeeze=False)
        for j, fam in enumerate(fams):
            for p in planners:
                pts = series(cells, fam, p, lambda c: (c["execution_median"],
                                                       *c["execution_median_interval"])
                             if c["execution_median_interval"] else None)
                if pts:
                    errorbar(axes[0][j], pts, dodge(planners, p, width), cols[p], p)
                pts = series(cells, fam, p, lambda c: (c["execution_mean"],
                                                       *c["execution_mean_interval"])
                             if c["execution_mean_interval"] else None)
                if pts:
                    errorbar(axes[1][j], pts, dodge(planners, p, width), cols[p], p)
            for i, what in enumerate(("median", "mean")):
                ax = axes[i][j]
                ax.set_title(f"{fam}: {what} execution success")
                ax.set_xlabel("number of objects N")
                ax.set_ylabel(f"{what} execution success")
                ax.set_ylim(-0.03, 1.05)
                ax.set_xticks(family_ns(fam))
                ax.grid(alpha=0.3)
                ax.legend(fontsize=8)
        fig.text(0.01, -0.01, "Per run: the fraction of validated executions that succeeded; a "
                 "run whose planning failed counts 0. Median: 95 % order-statistic interval; "
                 "mean: 95 % percentile bootstrap interval.", fontsize=8, ha="left")
        fig.tight_layout()
        save(fig, outdir, "fig_execution", written)
        plt.close(fig)
    else:
        notes.append("No run has an execution success (not validated): no execution figure.")

    # (d) calibration
    if any(c["calibration"] for c in cells):
        fig, ax = plt.subplots(figsize=(5.6, 5.2))
        markers = ["o", "^", "s", "D", "v", "P"]
        all_fams = sorted({c["family"] for c in cells})
        gaps = []
        for p in planners:
            pts = [(e, x, c["family"]) for c in cells if c["planner"] == p
                   for e, x in c["calibration"]]
            if not pts:
                continue
            gap = mean([e - x for e, x, _ in pts])
            gaps.append(f"{p}: {gap:+.3f} (n={len(pts)})")
            for fam in all_fams:
                fp = [(e, x) for e, x, f in pts if f == fam]
                if fp:
                    ax.scatter([e for e, _ in fp], [x for _, x in fp], s=14, alpha=0.6,
                               color=cols[p], marker=markers[all_fams.index(fam) % len(markers)],
                               label=f"{p}, {fam}" if len(all_fams) > 1 else
                               f"{p}: mean gap {gap:+.3f}")
        ax.plot([0, 1], [0, 1], color="black", linewidth=0.8, label="estimate = measured")
        ax.set_xlim(-0.02, 1.02)
        ax.set_ylim(-0.02, 1.02)
        ax.set_xlabel("planner's estimated success")
        ax.set_ylabel("measured execution success")
        ax.set_title("Calibration: one point per solved, validated plan")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
        fig.text(0.01, -0.04, "Mean gap (estimated - measured): " + "; ".join(gaps),
                 fontsize=8, ha="left", wrap=True)
        save(fig, outdir, "fig_calibration", written)
        plt.close(fig)
    else:
        notes.append("No solved run has both an estimated and a measured execution success: "
                     "no calibration figure.")
    return notes


# ----------------------------------------------------------------------------- html


CAPTIONS = {
    "fig_success": "Planning success rate against the number of objects, one line per planner, "
                   "with 95 % Wilson score intervals.",
    "fig_time": "Planning time against the number of objects: median with a 95 % interval of "
                "the median (order statistics), and the mean. Unsolved runs count at the "
                "time limit.",
    "fig_execution": "Execution success against the number of objects: per run, the fraction of "
                     "validated executions of its plan that succeeded, a run whose planning "
                     "failed counting 0 %.",
    "fig_calibration": "The planner's estimated success against the measured execution success, "
                       "one point per solved and validated plan; on the diagonal the estimate "
                       "is exact.",
}


def write_html(path, cells, planners, with_paper, notes, figure_names, source, figures_note,
               failures=()):
    header, rows = table_rows(cells, with_paper)
    esc = html.escape
    out = ["<!DOCTYPE html>", "<html><head><meta charset='utf-8'>",
           "<title>kautham bench report</title>",
           "<style>body{font-family:sans-serif;max-width:1200px;margin:1em auto;}"
           "table{border-collapse:collapse;font-size:13px;}td,th{border:1px solid #ccc;"
           "padding:2px 6px;}td.n{text-align:right;}figure{margin:1.5em 0;}"
           "img{max-width:100%;}</style></head><body>",
           "<h1>kautham bench report</h1>", f"<p>Source: <code>{esc(source)}</code>; "
           f"{sum(c['runs'] for c in cells)} runs, {len(planners)} planner(s): "
           f"{esc(', '.join(planners))}.</p>"]
    if figures_note:
        out.append(f"<p><strong>{esc(figures_note)}</strong></p>")
    for name in figure_names:
        out.append(f"<figure><img src='{name}.svg' alt='{name}'><figcaption>"
                   f"{esc(CAPTIONS.get(name, ''))} (<a href='{name}.png'>PNG</a>)"
                   "</figcaption></figure>")
    gaps = [(p, [e - x for c in cells if c["planner"] == p for e, x in c["calibration"]])
            for p in planners]
    gaps = [(p, g) for p, g in gaps if g]
    if gaps:
        out.append("<h2>Calibration</h2><ul>")
        for p, g in gaps:
            out.append(f"<li>{esc(p)}: mean gap (estimated - measured) {mean(g):+.3f}, "
                       f"mean |gap| {mean([abs(x) for x in g]):.3f}, {len(g)} plans</li>")
        out.append("</ul>")
    out.append("<h2>Table</h2><table><tr>" + "".join(f"<th>{esc(h)}</th>" for h in header)
               + "</tr>")
    for r in rows:
        out.append("<tr>" + "".join(f"<td{'' if i < 2 else ' class=n'}>{esc(v)}</td>"
                                    for i, v in enumerate(r)) + "</tr>")
    out.append("</table>")
    for note in notes:
        out.append(f"<p>{esc(note)}</p>")
    if failures:
        header, rows = failure_rows(failures)
        out.append("<h2>Why the executions failed</h2><table><tr>"
                   + "".join(f"<th>{esc(h)}</th>" for h in header) + "</tr>")
        for r in rows:
            out.append("<tr>" + "".join(f"<td>{esc(v)}</td>" for v in r) + "</tr>")
        out.append(f"</table><p>{esc(FAILURE_NOTE)}</p>")
    if with_paper:
        out.append("<h2>The paper's Table I</h2><p>Muhayyuddin et al., RA-L 2018 (i7-4500U, "
                   "30 runs per scene, robot not given): pKP and pKPU are p-KPIECE without and "
                   "with uncertainty, TP and TPU the task-and-motion planners it compares "
                   "with.</p><table>")
        for i, line in enumerate(paper_markdown()):
            if i == 1:
                continue
            tag = "th" if i == 0 else "td"
            parts = [x.strip() for x in line.strip("|").split("|")]
            out.append("<tr>" + "".join(f"<{tag}>{esc(x)}</{tag}>" for x in parts) + "</tr>")
        out.append("</table>")
    out.append("</body></html>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


# ----------------------------------------------------------------------------- main


def parse_args(argv):
    parser = argparse.ArgumentParser(
        prog="bench-report.py",
        description="Figures (success, time, execution success vs number of objects; "
                    "calibration) and tables (table.md, summary.json, index.html) of a "
                    "`kautham bench` campaign, from its OMPL benchmark logs or from a Planner "
                    "Arena database.",
        epilog="Examples:\n"
               "  /usr/bin/python3 scripts/bench-report.py OUT            # OUT/logs/*.log\n"
               "  /usr/bin/python3 scripts/bench-report.py bench.db -o report --paper\n"
               "Definitions: planning success = solved (exact; OMPL's 'solved' and not "
               "'approximate solution');\nN = the trailing integer of the problem name "
               "(kuka_clutter_25); planning times count unsolved runs at the\ntime limit; "
               "execution success per run = its 'execution success' property, 0 for a run "
               "that did\nnot solve, solved runs without one are left out. Runs of a "
               "problem and planner in several logs are pooled.\n"
               "Writes fig_success, fig_time, fig_execution, fig_calibration (.svg, .png), "
               "table.md, summary.json,\nindex.html (and benchmark.db when given logs; "
               "failures.md, why the executions failed, when given\nkautham bench's output "
               "folder with its plans/).\n"
               "Exit codes: 0 report written, 2 bad input.",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("inputs", nargs="+", metavar="INPUT",
                        help="a benchmark database (.db, from ompl_benchmark_statistics), or "
                             "kautham bench's output folder, folders of .log files, .log files")
    parser.add_argument("-o", "--output", metavar="DIR",
                        help="output folder (default: INPUT/report for a folder, "
                             "the database's folder/report for a database, ./report for logs)")
    parser.add_argument("--paper", action="store_true",
                        help="add the paper's Table I (pKP, pKPU, TP, TPU) to the figures and "
                             "a column beside pKP and pKPU in the table")
    parser.add_argument("--ompl-benchmark-statistics", metavar="PATH",
                        help="the program that builds the database from logs (default: found "
                             "in PATH, else /usr/bin/ompl_benchmark_statistics)")
    parser.add_argument("--no-figures", action="store_true", help="tables only")
    return parser.parse_args(argv)


def main(argv):
    args = parse_args(argv)
    if len(args.inputs) == 1 and os.path.isfile(args.inputs[0]) and is_sqlite(args.inputs[0]):
        db = args.inputs[0]
        outdir = args.output or os.path.join(os.path.dirname(os.path.abspath(db)), "report")
        source = db
    else:
        for path in args.inputs:
            if os.path.isfile(path) and is_sqlite(path):
                raise BadInput(f"{path}: give one database alone, or log files and folders")
        logs = collect_logs(args.inputs)
        if args.output:
            outdir = args.output
        elif len(args.inputs) == 1 and os.path.isdir(args.inputs[0]):
            outdir = os.path.join(args.inputs[0], "report")
        else:
            outdir = "report"
        os.makedirs(outdir, exist_ok=True)
        db = os.path.join(outdir, "benchmark.db")
        build_database(logs, db, find_statistics_program(args.ompl_benchmark_statistics))
        source = f"{len(logs)} log(s): " + ", ".join(os.path.basename(x) for x in logs[:8]) + \
            (" ..." if len(logs) > 8 else "") + f" -> {db}"

    runs, _ = read_database(db)
    cells, planners = summarise(runs)
    failures = read_failures(plans_folders(args.inputs))
    plt = None
    figures_note = ""
    if not args.no_figures:
        plt = load_matplotlib()
        if plt is None:
            fallback = "/usr/bin/python3"
            if (os.path.realpath(sys.executable) != os.path.realpath(fallback)
                    and os.path.exists(fallback) and not os.environ.get("BENCH_REPORT_REEXEC")):
                print(f"bench-report: {sys.executable} has no matplotlib; running again with "
                      f"{fallback}", file=sys.stderr)
                os.environ["BENCH_REPORT_REEXEC"] = "1"
                os.execv(fallback, [fallback, os.path.abspath(__file__)] + argv)
            figures_note = ("Figures not drawn: matplotlib is missing (Debian: apt-get install "
                            "python3-matplotlib, then run with /usr/bin/python3).")
            print(f"bench-report: {figures_note} Writing the tables only.", file=sys.stderr)

    os.makedirs(outdir, exist_ok=True)
    notes = table_notes(cells)
    without_n = sorted({c["problem"] for c in cells if c["objects"] is None})
    if without_n:
        notes.append("Not in the figures against N (no trailing object count in the name): "
                     + ", ".join(without_n) + ".")

    written = []
    if plt is not None:
        notes += figures(plt, cells, planners, outdir, args.paper, written)
    figure_names = []
    for path in written:
        name = os.path.splitext(os.path.basename(path))[0]
        if name not in figure_names:
            figure_names.append(name)

    md = os.path.join(outdir, "table.md")
    md_notes = list(notes)
    if args.paper:
        md_notes += ["", "The paper's Table I (Muhayyuddin et al., RA-L 2018; pKP/pKPU: "
                     "p-KPIECE without/with uncertainty; TP, TPU: task-and-motion planners):",
                     ""] + paper_markdown()
    write_markdown(md, cells, args.paper, md_notes)
    if failures:
        write_failures(os.path.join(outdir, "failures.md"), failures)
        written.append(os.path.join(outdir, "failures.md"))
    with open(os.path.join(outdir, "summary.json"), "w") as f:
        json.dump({"source": source, "planners": planners, "cells": cells,
                   "failures": failures}, f, indent=1)
    write_html(os.path.join(outdir, "index.html"), cells, planners, args.paper, notes,
               figure_names, source, figures_note, failures)
    written += [md, os.path.join(outdir, "summary.json"), os.path.join(outdir, "index.html")]
    for p in planners:
        gaps = [e - x for c in cells if c["planner"] == p for e, x in c["calibration"]]
        if gaps:
            print(f"bench-report: calibration {p}: mean gap (estimated - measured) "
                  f"{mean(gaps):+.3f} over {len(gaps)} plan(s)")
    print(f"bench-report: {sum(c['runs'] for c in cells)} runs, {len(cells)} problem x planner "
          f"cells, {len(planners)} planner(s); wrote {len(written)} files to {outdir}/ "
          f"(open {os.path.join(outdir, 'index.html')})")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except BadInput as e:
        print(f"bench-report: {e}", file=sys.stderr)
        sys.exit(2)
