"""What the scene scripts share: a problem file's objects and goal, read from its XML.

Standard library only; imported by scripts/scene-picture.py and scripts/free-space-room.py
(Python puts a script's own folder on its import path).
"""

import os
import re
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
KAUTHAM = os.environ.get("KAUTHAM", os.path.join(ROOT, "build", "apps", "kautham"))
# Footprint radius (m) of the shipped objects, by model name; a box is drawn as its square.
RADIUS = {"can": 0.033, "box": 0.03, "bottle": 0.035, "cylinder": 0.035, "slim_glass": 0.02}


def numbers(text):
    return [float(v) for v in text.split()]


def check(problem):
    """`kautham check PROBLEM`: the goal point (x, y, z) and the blockers' names. Raises
    RuntimeError with check's message when it fails."""
    result = subprocess.run([KAUTHAM, "check", problem], capture_output=True, text=True)
    if result.returncode != 0:
        raise RuntimeError(f"kautham check failed:\n{result.stderr}")
    match = re.search(r"^blockers .*?: (.*)$", result.stdout, re.M)
    blockers = set(match.group(1).split(", ")) if match else set()
    goal = re.search(r"within [0-9.]+ m of \(([-0-9.e]+), ([-0-9.e]+), ([-0-9.e]+)\)",
                     result.stdout)
    if not goal:
        raise RuntimeError(f"kautham check names no goal point for {problem}")
    return tuple(float(goal.group(i)) for i in (1, 2, 3)), blockers


def objects(root):
    """The problem's movable objects and target: (name, model, role, x, y) at their homes."""
    found = []
    for obstacle in root.findall("Obstacle"):
        role = obstacle.get("role")
        if role == "fixed":
            continue
        home = obstacle.find("Home")
        found.append((obstacle.find("KauthamName").get("name"),
                      os.path.splitext(os.path.basename(obstacle.get("obstacle")))[0], role,
                      float(home.get("X")), float(home.get("Y"))))
    return found
