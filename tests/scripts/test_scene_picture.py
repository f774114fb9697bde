#!/usr/bin/env python3
"""Tests scripts/scene-picture.py on the real kuka_clutter_10 problem and a real plan of it,
made here by `kautham plan` (p-KPIECE without uncertainty, seed 1: it pushes can1 and can7)
(CTest: scene_picture).

Run: /usr/bin/python3 tests/scripts/test_scene_picture.py build/apps/kautham
"""

import json
import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "scripts", "scene-picture.py")
PROBLEM = os.path.join(ROOT, "problems", "kuka_clutter_10.xml")
KAUTHAM = os.path.join(ROOT, "build", "apps", "kautham")


def picture(*args):
    run = subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True,
                         env=dict(os.environ, KAUTHAM=KAUTHAM))
    return run.returncode, run.stdout + run.stderr


class ScenePicture(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.plan = os.path.join(cls.tmp.name, "plan.json")
        # The plan is found in about 0.5 s; the generous limit keeps a loaded machine from
        # failing the test.
        made = subprocess.run([KAUTHAM, "plan", PROBLEM, "--seed", "1", "--set", "uncertainty=0",
                               "--time", "300", "-o", cls.plan], capture_output=True, text=True)
        assert made.returncode == 0, made.stdout + made.stderr

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def svg(self, name):
        with open(os.path.join(self.tmp.name, name), encoding="utf-8") as f:
            return f.read()

    def test_the_scene_alone_names_no_object_and_draws_no_path(self):
        code, out = picture(PROBLEM, "-o", os.path.join(self.tmp.name, "scene.svg"))
        self.assertEqual(code, 0, out)
        text = self.svg("scene.svg")
        self.assertIn("kuka_clutter_10.xml", text)
        self.assertIn("blockers", text)
        self.assertNotIn("can1</text>", text.replace(" <", "<"))

    def test_after_a_plan_the_moved_objects_are_named_and_the_path_drawn(self):
        code, out = picture(PROBLEM, "--plan", self.plan, "-o",
                            os.path.join(self.tmp.name, "after.svg"))
        self.assertEqual(code, 0, out)
        text = self.svg("after.svg")
        self.assertIn("after plan.json", text)
        self.assertIn("goal link", text)
        # The plan moves can1 12 cm and can7 5 cm, as `kautham plan` says; the others stay.
        for moved in ("can1", "can7"):
            self.assertIn(f"{moved} </text>".replace(" <", "<"), text.replace(" <", "<"))
        self.assertNotIn("can2</text>", text.replace(" <", "<"))

    def test_a_plan_of_another_problem_is_refused_naming_both(self):
        other = os.path.join(ROOT, "problems", "kuka_clutter_20.xml")
        code, out = picture(other, "--plan", self.plan, "-o",
                            os.path.join(self.tmp.name, "wrong.svg"))
        self.assertNotEqual(code, 0)
        self.assertIn("kuka_clutter_10.xml", out)
        self.assertIn("kuka_clutter_20.xml", out)
        self.assertFalse(os.path.exists(os.path.join(self.tmp.name, "wrong.svg")))

    def test_a_plan_with_an_object_the_scene_has_not_is_refused(self):
        with open(self.plan, encoding="utf-8") as f:
            plan = json.load(f)
        plan["bodies"][-1]["name"] = "can99"
        odd = os.path.join(self.tmp.name, "odd.json")
        with open(odd, "w", encoding="utf-8") as f:
            json.dump(plan, f)
        code, out = picture(PROBLEM, "--plan", odd, "-o", os.path.join(self.tmp.name, "odd.svg"))
        self.assertNotEqual(code, 0)
        self.assertIn("odd.json", out)
        self.assertFalse(os.path.exists(os.path.join(self.tmp.name, "odd.svg")))

    def test_a_file_that_is_not_a_plan_is_refused_naming_it(self):
        broken = os.path.join(self.tmp.name, "broken.json")
        with open(broken, "w", encoding="utf-8") as f:
            f.write("{\"bodies\": [")
        code, out = picture(PROBLEM, "--plan", broken, "-o",
                            os.path.join(self.tmp.name, "broken.svg"))
        self.assertNotEqual(code, 0)
        self.assertIn("broken.json", out)
        self.assertIn("not a plan file", out)


if __name__ == "__main__":
    if len(sys.argv) > 1:
        KAUTHAM = os.path.abspath(sys.argv.pop(1))
    unittest.main()
