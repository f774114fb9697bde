#!/usr/bin/env python3
"""Draws a generated dense-clutter scene seen from above, as an SVG: the table, the movable
objects (blockers, as `kautham check` counts them, in orange), the target, the pre-grasp point,
the approach corridor and the goal's free space.

Usage: /usr/bin/python3 scripts/scene-picture.py problems/kuka_clutter_20.xml -o docs/images/kuka_clutter_20.svg
Reads the blocker names from `kautham check` ($KAUTHAM or build/apps/kautham). Needs matplotlib.
"""
import argparse
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Circle, Rectangle  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RADIUS = {"can": 0.033, "box": 0.03, "bottle": 0.035, "cylinder": 0.035, "slim_glass": 0.02}


def numbers(text):
    return [float(v) for v in text.split()]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("problem")
    parser.add_argument("-o", "--output", required=True)
    args = parser.parse_args()
    kautham = os.environ.get("KAUTHAM", os.path.join(ROOT, "build", "apps", "kautham"))
    check = subprocess.run([kautham, "check", args.problem], capture_output=True, text=True)
    if check.returncode != 0:
        sys.exit(f"scene-picture: kautham check failed:\n{check.stderr}")
    match = re.search(r"^blockers .*?: (.*)$", check.stdout, re.M)
    blockers = set(match.group(1).split(", ")) if match else set()
    goal = re.search(r"within [0-9.]+ m of \(([-0-9.e]+), ([-0-9.e]+), ([-0-9.e]+)\)", check.stdout)
    gx, gy = float(goal.group(1)), float(goal.group(2))

    root = ET.parse(args.problem).getroot()
    region = root.find(".//GoalRegion")
    corridor = float(region.get("approachCorridor", "0"))
    free = numbers(region.get("freeSpace", "0 0 0"))
    centre = numbers(region.get("freeSpaceCenter", "0 0 0"))
    level = numbers(region.get("levelAxis", "0 1 0"))
    width = sum(abs(a) * s for a, s in zip(level, free))
    front = centre[2] + free[2] / 2
    behind = centre[2] - free[2] / 2

    fig, ax = plt.subplots(figsize=(6, 4.4))
    ax.add_patch(Rectangle((-0.6, -0.4), 1.2, 0.8, color="#e8dcc8", zorder=0))
    ax.add_patch(Rectangle((gx - width / 2, gy - corridor), width, corridor + front,
                           color="#9ecae1", alpha=0.5, zorder=1, label="approach corridor"))
    ax.add_patch(Rectangle((gx - width / 2, gy + behind), width, front - behind, fill=False,
                           ec="#08519c", lw=1.5, zorder=4, label="free space at the goal"))
    for obstacle in root.findall("Obstacle"):
        name = obstacle.find("KauthamName").get("name")
        home = obstacle.find("Home")
        x, y = float(home.get("X")), float(home.get("Y"))
        kind = os.path.splitext(os.path.basename(obstacle.get("obstacle")))[0]
        role = obstacle.get("role")
        if role == "fixed":
            continue
        r = RADIUS.get(kind, 0.03)
        colour = "#2ca25f" if role == "target" else "#fd8d3c" if name in blockers else "#bdbdbd"
        patch = (Rectangle((x - r, y - r), 2 * r, 2 * r, color=colour, zorder=3) if kind == "box"
                 else Circle((x, y), r, color=colour, zorder=3))
        ax.add_patch(patch)
    ax.plot([gx], [gy], "k+", ms=12, zorder=5, label="pre-grasp (TCP)")
    ax.plot([], [], "o", color="#fd8d3c", label=f"blockers ({len(blockers)})")
    ax.plot([], [], "o", color="#2ca25f", label="target")
    ax.set_xlim(-0.6, 0.6)
    ax.set_ylim(-0.55, 0.4)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m): the robot is at the bottom")
    ax.set_title(os.path.basename(args.problem))
    ax.legend(loc="lower left", fontsize=7)
    fig.tight_layout()
    fig.savefig(args.output)


if __name__ == "__main__":
    main()
