#!/usr/bin/env python3
"""Tests scripts/steering-trees.py on the real kuka_clutter_25 (CTest: steering_trees).

With push_angle_spread 0.4 and seed 2 the first tree's steering alone tips can21 and trees 1 and
2, pushing at angles of their own, reach the goal (docs/planners.md, "The goal steering alone").
Under seed 1 tree 1 draws other angles and tips can21 too.

Run: /usr/bin/python3 tests/scripts/test_steering_trees.py build/apps/kautham
"""

import os
import subprocess
import sys
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "scripts", "steering-trees.py")
KAUTHAM = os.path.join(ROOT, "build", "apps", "kautham")


def trees(*args):
    run = subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True,
                         env=dict(os.environ, KAUTHAM=KAUTHAM))
    return run.returncode, run.stdout + run.stderr


class SteeringTrees(unittest.TestCase):
    def test_the_first_tree_tips_a_can_and_the_next_two_reach_the_goal(self):
        code, text = trees(os.path.join(ROOT, "problems", "kuka_clutter_25.xml"), "--trees", "3",
                           "--seed", "2", "--set", "push_angle_spread=0.4")
        self.assertEqual(code, 0, text)
        lines = text.splitlines()
        self.assertRegex(lines[1], r"^\s+0\s+no\s+[0-9.]+\s+\d+\s+object tilted \(can21\)$")
        self.assertRegex(lines[2], r"^\s+1\s+yes\s+[01]\.\d\s+\d+\s+reached the goal$")
        self.assertRegex(lines[3], r"^\s+2\s+yes\s+[01]\.\d\s+\d+\s+reached the goal$")
        self.assertIn("reached the goal: 2 of 3 trees (1, 2)", text)
        code, text = trees(os.path.join(ROOT, "problems", "kuka_clutter_25.xml"), "--trees", "2",
                           "--first", "1", "--seed", "1", "--set", "push_angle_spread=0.4")
        self.assertEqual(code, 0, text)
        self.assertRegex(text.splitlines()[1],
                         r"^\s+1\s+no\s+[0-9.]+\s+\d+\s+object tilted \(can21\)$")

    def test_a_missing_file_or_a_bad_parameter_is_an_error_that_names_it(self):
        code, text = trees(os.path.join(ROOT, "problems", "no_such.xml"))
        self.assertEqual(code, 2, text)
        self.assertIn("no_such.xml: no such file", text)
        code, text = trees(os.path.join(ROOT, "problems", "kuka_clutter_25.xml"), "--trees", "1",
                           "--set", "push_angle_spread=7")
        self.assertEqual(code, 2, text)
        self.assertIn("push_angle_spread", text)


if __name__ == "__main__":
    if len(sys.argv) > 1:
        KAUTHAM = os.path.abspath(sys.argv.pop(1))
    unittest.main()
