#!/usr/bin/env python3
"""Draws a generated dense-clutter scene seen from above, as an SVG: the table, the movable
objects (blockers, as `kautham check` counts them, in orange), the target, the pre-grasp point,
the approach corridor and the goal's free space.

With --plan PLAN.json (a plan of this problem, from `kautham plan -o`), the objects stand where
the plan leaves them, their start poses dashed, the ones it moved named (more than 5 mm from the
first frame to the last, as `kautham plan`'s "moved" line counts them), and the goal link's
path drawn: what a plan did to the scene, at a glance.

Usage: /usr/bin/python3 scripts/scene-picture.py problems/kuka_clutter_20.xml -o docs/images/kuka_clutter_20.svg
       /usr/bin/python3 scripts/scene-picture.py problems/kuka_clutter_30.xml --plan out/plan.json -o out/after.svg
Reads the blocker names from `kautham check` ($KAUTHAM or build/apps/kautham). Needs matplotlib;
run by another python3 without it, it runs itself again with /usr/bin/python3 (Debian's, with
python3-matplotlib).
"""
import argparse
import json
import math
import os
import sys
import xml.etree.ElementTree as ET

try:
    import matplotlib
except ImportError:
    # Another python3 (a virtual environment, pyenv) may lack Debian's matplotlib: run again
    # with Debian's own, once; without it, say what to install instead of a traceback.
    FALLBACK = "/usr/bin/python3"
    if (os.path.realpath(sys.executable) != os.path.realpath(FALLBACK)
            and os.path.exists(FALLBACK) and not os.environ.get("SCENE_PICTURE_REEXEC")):
        os.environ["SCENE_PICTURE_REEXEC"] = "1"
        os.execv(FALLBACK, [FALLBACK, os.path.abspath(__file__)] + sys.argv[1:])
    sys.exit("scene-picture: matplotlib is missing (Debian: apt-get install python3-matplotlib, "
             "then run with /usr/bin/python3)")

matplotlib.use("Agg")
# Text stays text in the SVG: searchable, and smaller than glyphs drawn as paths.
matplotlib.rcParams["svg.fonttype"] = "none"
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Circle, Rectangle  # noqa: E402

import kautham_scene  # noqa: E402
from kautham_scene import RADIUS, numbers  # noqa: E402


def shape(kind, x, y, r, **style):
    return (Rectangle((x - r, y - r), 2 * r, 2 * r, **style) if kind == "box"
            else Circle((x, y), r, **style))


# A plan names an object as moved beyond this (m), as `kautham plan` does.
MOVED = 0.005


def same_file(planned, problem, plan_path):
    """Whether the plan's problem file (as recorded, relative to where it was planned) is
    `problem`: the same file where both can be found, else the same name."""
    candidates = [planned, os.path.join(os.path.dirname(plan_path), planned)]
    found = [c for c in candidates if os.path.exists(c)]
    if found and os.path.exists(problem):
        return any(os.path.samefile(c, problem) for c in found)
    return os.path.basename(planned) == os.path.basename(problem)


def plan_poses(path, problem):
    """Each object's (x, y, z) in the plan's first and last frames, by name, and the goal link's
    path; exits with a message naming the file when it is not a plan of `problem`."""
    try:
        with open(path, encoding="utf-8") as f:
            plan = json.load(f)
        bodies = [(body["name"], body["role"]) for body in plan["bodies"]]
        frames = plan["frames"]
        path_xy = [(p[0], p[1]) for p in plan["goal"]["link_path"]]
        planned = plan["problem"]["file"]
    except (OSError, ValueError, KeyError, IndexError, TypeError) as error:
        sys.exit(f"scene-picture: {path}: not a plan file from `kautham plan -o` ({error})")
    if not frames:
        sys.exit(f"scene-picture: {path} has no frames: the plan has no motion to draw")
    if not same_file(planned, problem, path):
        sys.exit(f"scene-picture: {path} is a plan of {planned}, not of {problem}")
    objects = [i for i, (_, role) in enumerate(bodies) if role in ("movable", "target")]

    def at(frame):
        return {bodies[i][0]: tuple(frame["poses"][i][:3]) for i in objects}

    return at(frames[0]), at(frames[-1]), path_xy


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("problem")
    parser.add_argument("-o", "--output", required=True)
    parser.add_argument("--plan", help="a plan of this problem (JSON): draw the scene as it leaves it")
    args = parser.parse_args()
    before, after, link_path = (plan_poses(args.plan, args.problem) if args.plan
                                else ({}, {}, []))
    try:
        (gx, gy, _), blockers = kautham_scene.check(args.problem)
    except RuntimeError as e:
        sys.exit(f"scene-picture: {e}")

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
    in_scene = set()
    for name, kind, role, x, y in kautham_scene.objects(root):
        r = RADIUS.get(kind, 0.03)
        colour = "#2ca25f" if role == "target" else "#fd8d3c" if name in blockers else "#bdbdbd"
        in_scene.add(name)
        if args.plan:
            if name not in after:
                sys.exit(f"scene-picture: {args.plan} has no object {name} of {args.problem}")
            x, y = before[name][0], before[name][1]
            ax.add_patch(shape(kind, x, y, r, fill=False, ec="#636363", ls="--", lw=0.8, zorder=2))
            if math.dist(before[name], after[name]) > MOVED:
                ax.annotate(name, after[name][:2], ha="center", va="center", fontsize=6, zorder=6)
            x, y = after[name][0], after[name][1]
        ax.add_patch(shape(kind, x, y, r, color=colour, zorder=3))
    unknown = sorted(set(after) - in_scene)
    if unknown:
        sys.exit(f"scene-picture: {args.plan} has objects {args.problem} has not: "
                 f"{', '.join(unknown)}")
    if link_path:
        ax.plot([p[0] for p in link_path], [p[1] for p in link_path], "-", color="#cb181d",
                lw=0.8, zorder=5, label="goal link's path")
    ax.plot([gx], [gy], "k+", ms=12, zorder=5, label="pre-grasp (TCP)")
    ax.plot([], [], "o", color="#fd8d3c", label=f"blockers ({len(blockers)})")
    ax.plot([], [], "o", color="#2ca25f", label="target")
    ax.set_xlim(-0.6, 0.6)
    ax.set_ylim(-0.55, 0.4)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m): the robot is at the bottom")
    ax.set_title(os.path.basename(args.problem) +
                 (f" after {os.path.basename(args.plan)} (dashed: start)" if args.plan else ""))
    ax.legend(loc="lower left", fontsize=7)
    fig.tight_layout()
    fig.savefig(args.output)


if __name__ == "__main__":
    main()
