#!/usr/bin/env python3
"""Tests scripts/bench-report.py on the synthetic OMPL benchmark logs of tests/data/bench.

The logs have the text format of ompl::tools::Benchmark (OMPL 1.5.2, control planners) with
kautham's extra run properties; the real `ompl_benchmark_statistics` (Debian's ompl-demos)
builds the database, and the report's numbers are checked against values worked out by hand:

kuka_clutter_10, pKPU (time limit 30 s): 10 runs, 7 exact solutions, 1 approximate, 2 timeouts.
  success 7/10, Wilson 95 % [0.3968, 0.8922];
  times with the unsolved at 30 s: 2 3 4 6.5 8 12 20 30 30 30 -> median 10, interval of the
  median [x(2), x(9)] = [3, 30] (coverage 1 - 2 * 11/1024), mean 14.55, mean of solved 55.5/7;
  execution: 6 validated plans (0.85 0.7 0.9 0.5 1 0.65; one solved run not validated) and 3
  unsolved runs at 0 -> median 0.65, mean 4.6/9; calibration gap mean (0.1 / 6).
yumi_clutter_5, pKPU: two shard logs of 3 runs each, one naming it control_pKPU as OMPL's
  Benchmark does, one pKPU: pooled, 6/6.
pusher_free, RRT (limit 10 s): no object count in the name, OMPL's properties only; 3 solved,
  1 timeout, 1 crash (status 7, counted as failed and not solved): 3/5, Wilson [0.2307, 0.8824],
  times 0.5 0.7 0.9 10 10 -> median 0.9, mean 4.42; no execution success.
A bench output folder (logs/ and plans/) with two validation reports of kuka_clutter_10's pKPU
  plans, 10 executions each: 6 and 8 successes (70 %); goal missed 3 + 1 (20 %), the free space
  not clear 2 (can20) + 1 (can23) (15 %), the gripper off the goal pose 2 (10 %), 1 of them
  touching nothing there (5 %), a can tipped 1 (5 %), the target touched 1 (5 %); the objects
  named by a broken rule can15 and glass.

Run: /usr/bin/python3 tests/scripts/test_bench_report.py (CTest: bench_report).
"""

import importlib.util
import json
import os
import sqlite3
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "scripts", "bench-report.py")
DATA = os.path.join(ROOT, "tests", "data", "bench")


def load_module():
    spec = importlib.util.spec_from_file_location("bench_report", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def report(*args):
    return subprocess.run([sys.executable, SCRIPT] + list(args), capture_output=True, text=True)


class FromLogs(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.out = os.path.join(cls.tmp.name, "report")
        cls.result = report(DATA, "-o", cls.out, "--paper")
        if cls.result.returncode != 0:
            raise AssertionError(f"bench-report.py failed ({cls.result.returncode}):\n"
                                 f"{cls.result.stdout}\n{cls.result.stderr}")
        with open(os.path.join(cls.out, "summary.json")) as f:
            cls.summary = json.load(f)
        cls.cells = {(c["problem"], c["planner"]): c for c in cls.summary["cells"]}

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_database_built_by_ompl_benchmark_statistics(self):
        db = os.path.join(self.out, "benchmark.db")
        conn = sqlite3.connect(db)
        tables = {r[0] for r in conn.execute("SELECT name FROM sqlite_master WHERE type='table'")}
        self.assertTrue({"experiments", "plannerConfigs", "enums", "runs", "progress"} <= tables)
        self.assertEqual(conn.execute("SELECT count(*) FROM runs").fetchone()[0], 26)
        self.assertEqual(conn.execute("SELECT count(*) FROM experiments").fetchone()[0], 4)
        columns = {r[1] for r in conn.execute("PRAGMA table_info(runs)")}
        self.assertTrue({"estimated_success", "execution_success", "objects_moved"} <= columns)

    def test_success_rate_and_wilson_interval(self):
        c = self.cells[("kuka_clutter_10", "pKPU")]  # the "control_" prefix is dropped
        self.assertEqual((c["runs"], c["solved"], c["objects"]), (10, 7, 10))
        self.assertAlmostEqual(c["success_rate"], 0.7)
        lo, hi = c["success_wilson95"]
        self.assertAlmostEqual(lo, 0.39677, places=4)
        self.assertAlmostEqual(hi, 0.89222, places=4)
        k = self.cells[("kuka_clutter_10", "KPIECE")]  # an approximate solution is no success
        self.assertEqual((k["runs"], k["solved"]), (5, 2))

    def test_times_count_unsolved_at_the_limit(self):
        c = self.cells[("kuka_clutter_10", "pKPU")]
        self.assertEqual(c["time_limit"], 30)
        self.assertAlmostEqual(c["time_median"], 10.0)
        self.assertEqual(c["time_median_interval"], [3.0, 30.0])
        self.assertAlmostEqual(c["time_median_interval_coverage"], 1 - 2 * 11 / 1024)
        self.assertAlmostEqual(c["time_mean"], 14.55)
        self.assertAlmostEqual(c["time_mean_solved"], 55.5 / 7)

    def test_execution_success_and_calibration(self):
        c = self.cells[("kuka_clutter_10", "pKPU")]
        self.assertEqual((c["execution_runs"], c["execution_not_validated"]), (9, 1))
        self.assertAlmostEqual(c["execution_median"], 0.65)
        self.assertEqual(c["execution_median_interval"], [0.0, 0.9])
        self.assertAlmostEqual(c["execution_mean"], 4.6 / 9)
        lo, hi = c["execution_mean_interval"]
        self.assertTrue(0 <= lo < 4.6 / 9 < hi <= 1)
        self.assertEqual(c["calibration_points"], 6)
        self.assertAlmostEqual(c["calibration_mean_gap"], 0.1 / 6)

    def test_shards_pool_and_problem_without_object_count(self):
        y = self.cells[("yumi_clutter_5", "pKPU")]
        self.assertEqual((y["runs"], y["solved"], y["objects"]), (6, 6, 5))
        p = self.cells[("pusher_free", "RRT")]
        self.assertEqual((p["runs"], p["solved"], p["failed"], p["objects"]), (5, 3, 1, None))
        self.assertIsNone(p["execution_median"])
        self.assertEqual(p["time_limit"], 10)
        self.assertAlmostEqual(p["time_median"], 0.9)
        self.assertAlmostEqual(p["time_mean"], 4.42)  # the crash at the limit too
        lo, hi = p["success_wilson95"]
        self.assertAlmostEqual(lo, 0.2307, places=4)
        self.assertAlmostEqual(hi, 0.8824, places=4)

    def test_markdown_table(self):
        with open(os.path.join(self.out, "table.md")) as f:
            text = f.read()
        self.assertIn("| kuka_clutter_10 | pKPU | 10 | 0 | 70.0 | [39.7, 89.2] | 10.00 | "
                      "[3.00, 30.00] | 14.55 | 7.93 | 65.0 | 51.1 | 100, 14.52 |", text)
        self.assertIn("| kuka_clutter_10 | KPIECE | 5 | 0 | 40.0 | [11.8, 76.9] | 30.00 | "
                      "[11.00, 30.00] | 25.20 | 18.00 | 0.0 | 8.0 |  |", text)
        self.assertIn("| pusher_free | RRT | 5 | 1 | 60.0 | [23.1, 88.2] | 0.90 |", text)
        self.assertIn("| 40 | 40 | 182.19 | 60 | 71.64 | 63 | 68 | — | — |", text)  # Table I

    def test_figures_and_index(self):
        with open(os.path.join(self.out, "index.html")) as f:
            page = f.read()
        for name in ("fig_success", "fig_time", "fig_execution", "fig_calibration"):
            for ext in ("svg", "png"):
                path = os.path.join(self.out, f"{name}.{ext}")
                self.assertGreater(os.path.getsize(path), 1000, path)
            self.assertIn(f"{name}.svg", page)
        self.assertIn("<td>kuka_clutter_10</td><td>pKPU</td>", page)
        self.assertIn("time limit", page)
        # printed over all problems: (0.1 + 6 * 0.05) / 12 with yumi_clutter_5's plans
        self.assertIn("calibration pKPU: mean gap (estimated - measured) +0.033 over 12 plan(s)",
                      self.result.stdout)


class FromDatabase(unittest.TestCase):
    def test_same_numbers_from_the_database(self):
        with tempfile.TemporaryDirectory() as tmp:
            first = report(DATA, "-o", os.path.join(tmp, "a"), "--no-figures")
            self.assertEqual(first.returncode, 0, first.stderr)
            second = report(os.path.join(tmp, "a", "benchmark.db"), "-o",
                            os.path.join(tmp, "b"), "--no-figures")
            self.assertEqual(second.returncode, 0, second.stderr)
            with open(os.path.join(tmp, "a", "table.md")) as a, \
                    open(os.path.join(tmp, "b", "table.md")) as b:
                self.assertEqual(a.read(), b.read())


class BadInput(unittest.TestCase):
    def test_exit_2_with_a_message(self):
        with tempfile.TemporaryDirectory() as tmp:
            notlog = os.path.join(tmp, "notes.log")
            with open(notlog, "w") as f:
                f.write("hello\n")
            other = os.path.join(tmp, "other.db")
            sqlite3.connect(other).execute("CREATE TABLE t (x)")
            empty = os.path.join(tmp, "empty")
            os.mkdir(empty)
            cases = {os.path.join(tmp, "missing"): "no such file",
                     notlog: "not an OMPL benchmark log",
                     other: "not a benchmark database",
                     empty: "without .log files"}
            for path, message in cases.items():
                result = report(path, "-o", os.path.join(tmp, "out"))
                self.assertEqual(result.returncode, 2, path)
                self.assertIn(message, result.stderr, path)


def validation(runs, successes, failures, free, free_objects, pose_missed, breakers,
               touching_nothing=None):
    results = [{"violation": v, "object": o, "reached_goal": False} for v, o in breakers]
    results += [{"violation": "none", "reached_goal": True}] * (runs - len(results))
    kinds = {"goal_missed": 0, "object_fell_or_tipped": 0, "target_touched": 0, "too_fast": 0,
             "other": 0}
    kinds.update(failures)
    pose = {"runs": pose_missed, "position": pose_missed, "approach": 0, "level": 0}
    if touching_nothing is not None:
        pose.update(touching={}, touching_nothing=touching_nothing)
    return {"format": "kautham-validation", "runs": runs, "successes": successes,
            "failures": kinds, "free_space_not_clear": {"runs": free, "by_object": free_objects},
            "goal_pose_missed": pose, "results": results}


class FromBenchFolder(unittest.TestCase):
    """failures.md: why the executions failed, from the bench's validation reports."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.bench = os.path.join(self.tmp.name, "out")
        os.makedirs(os.path.join(self.bench, "logs"))
        with open(os.path.join(DATA, "kuka_clutter_10.log")) as src, \
                open(os.path.join(self.bench, "logs", "kuka_clutter_10.log"), "w") as dst:
            dst.write(src.read())
        self.plans = os.path.join(self.bench, "plans", "kuka_clutter_10", "pKPU")
        os.makedirs(self.plans)
        reports = [validation(10, 6, {"goal_missed": 3, "object_fell_or_tipped": 1}, 2,
                              {"can20": 2}, 2, [("object tilted", "can15")], touching_nothing=1),
                   validation(10, 8, {"goal_missed": 1, "target_touched": 1}, 1, {"can23": 1},
                              0, [("target moved", "glass")], touching_nothing=0)]
        for r, content in enumerate(reports):
            with open(os.path.join(self.plans, f"run-{r}.validation.json"), "w") as f:
                json.dump(content, f)

    def tearDown(self):
        self.tmp.cleanup()

    def test_failures_table_and_summary(self):
        result = report(self.bench, "--no-figures")
        self.assertEqual(result.returncode, 0, result.stderr)
        out = os.path.join(self.bench, "report")
        with open(os.path.join(out, "failures.md")) as f:
            text = f.read()
        self.assertIn("| kuka_clutter_10 | pKPU | 2 | 20 | 70.0 | 20.0 | 15.0 | can20 2, can23 1 | "
                      "10.0 | 5.0 | 5.0 | 5.0 | 0.0 | 0.0 | can15 1, glass 1 |", text)
        with open(os.path.join(out, "summary.json")) as f:
            failures = json.load(f)["failures"]
        self.assertEqual(len(failures), 1)
        self.assertEqual(failures[0]["free_space_objects"], {"can20": 2, "can23": 1})
        with open(os.path.join(out, "index.html")) as f:
            self.assertIn("Why the executions failed", f.read())

    def test_off_the_pose_unsplit_where_a_report_does_not_say_what_was_touched(self):
        # A report from before validate said what the robot touched where it ended.
        with open(os.path.join(self.plans, "run-2.validation.json"), "w") as f:
            json.dump(validation(10, 9, {"goal_missed": 1}, 0, {}, 1, []), f)
        result = report(self.bench, "--no-figures")
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(os.path.join(self.bench, "report", "failures.md")) as f:
            self.assertIn("| can20 2, can23 1 | 10.0 | — | 3.3 |", f.read())

    def test_a_broken_validation_report_is_named(self):
        broken = os.path.join(self.plans, "run-2.validation.json")
        with open(broken, "w") as f:
            f.write("{\"format\": \"kautham-validation\", \"runs\": ")
        result = report(self.bench, "--no-figures")
        self.assertEqual(result.returncode, 2)
        self.assertIn(broken, result.stderr)
        self.assertIn("not a readable validation file", result.stderr)
        with open(broken, "w") as f:
            json.dump(dict(validation(10, 6, {}, 0, {}, 0, []), runs="many"), f)
        result = report(self.bench, "--no-figures")
        self.assertEqual(result.returncode, 2)
        self.assertIn(f"{broken}: a validation report with a field of the wrong kind",
                      result.stderr)

    def test_shards_pooled_and_a_run_counted_once(self):
        # A Slurm campaign's shard holds run-1 again (counted once, from OUT's own plans/) and
        # run-2, a new plan with 10 successes of 10.
        shard = os.path.join(self.bench, "shard-1", "plans", "kuka_clutter_10", "pKPU")
        os.makedirs(shard)
        for r, successes in ((1, 0), (2, 10)):
            with open(os.path.join(shard, f"run-{r}.validation.json"), "w") as f:
                json.dump(validation(10, successes, {"goal_missed": 10 - successes}, 0, {}, 0,
                                     []), f)
        result = report(self.bench, "--no-figures")
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(os.path.join(self.bench, "report", "summary.json")) as f:
            failures = json.load(f)["failures"][0]
        self.assertEqual((failures["plans"], failures["executions"], failures["successes"]),
                         (3, 30, 24))

    def test_two_benches_runs_numbered_alike_are_both_counted(self):
        # A second bench (other seeds) numbers its runs from 0 too: its plans are its own, under
        # its folder's name, as the table's cells are, not taken for the first bench's.
        other = os.path.join(self.tmp.name, "other")
        os.makedirs(os.path.join(other, "logs"))
        with open(os.path.join(DATA, "kuka_clutter_10.log")) as src, \
                open(os.path.join(other, "logs", "kuka_clutter_10.log"), "w") as dst:
            dst.write(src.read())
        plans = os.path.join(other, "plans", "kuka_clutter_10", "pKPU")
        os.makedirs(plans)
        with open(os.path.join(plans, "run-0.validation.json"), "w") as f:
            json.dump(validation(10, 10, {}, 0, {}, 0, []), f)
        result = report(self.bench, other, "-o", os.path.join(self.tmp.name, "r"),
                        "--no-figures")
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(os.path.join(self.tmp.name, "r", "summary.json")) as f:
            failures = json.load(f)["failures"]
        counts = {(g["problem"], g["plans"], g["successes"]) for g in failures}
        self.assertEqual(counts, {("out/kuka_clutter_10", 2, 14),
                                  ("other/kuka_clutter_10", 1, 10)})

    def test_logs_alone_write_no_failures_table(self):
        result = report(os.path.join(self.bench, "logs"), "-o", os.path.join(self.tmp.name, "r"),
                        "--no-figures")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertFalse(os.path.exists(os.path.join(self.tmp.name, "r", "failures.md")))


class Statistics(unittest.TestCase):
    def setUp(self):
        self.m = load_module()

    def test_wilson(self):
        lo, hi = self.m.wilson(0, 10)
        self.assertEqual(lo, 0.0)
        self.assertAlmostEqual(hi, 0.27753, places=4)
        lo, hi = self.m.wilson(10, 10)
        self.assertAlmostEqual(lo, 0.72247, places=4)
        self.assertEqual(hi, 1.0)
        self.assertIsNone(self.m.wilson(0, 0))

    def test_median_interval_coverage(self):
        # n = 5: no pair of order statistics reaches 95 %: min-max, coverage 1 - 2/32
        self.assertEqual(self.m.median_interval([5, 1, 4, 2, 3]), (1, 5, 1 - 2 / 32))
        lo, hi, coverage = self.m.median_interval(list(range(1, 31)))  # n = 30: ranks 10, 21
        self.assertEqual((lo, hi), (10, 21))
        self.assertGreaterEqual(coverage, 0.95)

    def test_tmp_stands_for_the_papers_task_planners(self):
        self.assertEqual(self.m.paper_value("TMP", 20), (94, 57))
        self.assertEqual(self.m.paper_value("TMP-U", 20), (70, 229))
        self.assertEqual(self.m.paper_value("tp", 30), (84, 77))
        self.assertIsNone(self.m.paper_value("TMP", 5))  # the paper gives no TP at 5 objects
        self.assertIsNone(self.m.paper_value("o-KPIECE", 20))

    def test_problem_family(self):
        self.assertEqual(self.m.problem_family("yumi_clutter_40"), ("yumi_clutter", 40))
        self.assertEqual(self.m.problem_family("pusher_free"), ("pusher_free", None))


if __name__ == "__main__":
    unittest.main(verbosity=2)
