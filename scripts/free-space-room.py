#!/usr/bin/env python3
"""How much room a dense scene's goal free space has, and how often the objects' pose
uncertainty alone fills it: a ceiling on the execution success of any plan that leaves the
objects beside the free space where they stand.

Seen from above, the objects are discs at their homes (the radii of scene-picture.py; a box as
the disc of its half width, its corners left out) and the goal's free space is its rectangle,
moved with the gripper. The gripper may end anywhere within --shift of the goal point, turned up to --yaw
about the vertical (p-KPIECE's `goal_shift` and GoalEnd's turns): the end that leaves the most
room to the nearest object is found on a 0.5 mm and 0.01 rad grid. Then --samples worlds are
drawn from the problem's <Uncertainty x y> (each object's position, normal, independent), and
the share in which some object reaches into the free space at that end is counted, with the arm
exactly there: what the objects' uncertainty alone costs the best possible end.

Objects whose centre lies inside the free space at the goal point are left out (they are the
blockers a plan pushes away), as are the target and the objects named by --ignore (those the
plans push away anyway: `kautham plan`'s "moved" line names them). Only a horizontal approach
is handled (the side pre-grasps of the dense suite).

Usage: /usr/bin/python3 scripts/free-space-room.py problems/kuka_clutter_25.xml --ignore can16
       /usr/bin/python3 scripts/free-space-room.py problems/yumi_clutter_30.xml --shift 0.01
Reads the goal point from `kautham check` ($KAUTHAM or build/apps/kautham). Exit codes: 0
done, 2 bad input (a missing file, no goal free space, a vertical approach).
"""
import argparse
import math
import random
import sys
import xml.etree.ElementTree as ET

import kautham_scene
from kautham_scene import RADIUS, numbers
from kautham_stats import wilson

class Scene:
    """The free space's rectangle from above, in the frame of the approach: `along` the approach,
    `across` it."""

    def __init__(self, problem, ignore=()):
        root = ET.parse(problem).getroot()
        region = root.find(".//GoalRegion")
        if region is None or region.get("freeSpace") is None:
            raise ValueError(f"{problem}: its goal has no free space (GoalRegion freeSpace)")
        approach = numbers(region.get("approach", "0 0 1"))
        norm = math.hypot(approach[0], approach[1])
        if norm < 1e-9:
            raise ValueError(f"{problem}: a vertical approach; only side pre-grasps are handled")
        self.along = (approach[0] / norm, approach[1] / norm)
        size = numbers(region.get("freeSpace"))
        level = numbers(region.get("levelAxis", "0 1 0"))
        # In the goal link's frame +z is the approach and the level axis is across it.
        self.half_across = 0.5 * sum(abs(a) * s for a, s in zip(level, size))
        self.half_along = 0.5 * size[2]
        self.ahead = numbers(region.get("freeSpaceCenter", "0 0 0"))[2]
        (gx, gy, _), _ = kautham_scene.check(problem)
        self.goal = (gx, gy)
        uncertainty = root.find("Uncertainty")
        self.sd = (float(uncertainty.get("x", "0")), float(uncertainty.get("y", "0"))) \
            if uncertainty is not None else (0.0, 0.0)
        self.objects = []
        self.left_out = []
        found = kautham_scene.objects(root)
        unknown = set(ignore) - {name for name, _, _, _, _ in found}
        if unknown:
            raise ValueError(f"{problem} has no object {', '.join(sorted(unknown))} (--ignore)")
        for name, model, role, x, y in found:
            if role == "target":
                continue
            if name in ignore:
                self.left_out.append(name)
                continue
            disc = (name, x, y, RADIUS.get(model, 0.03))
            if self.depth(0.0, 0.0, 0.0, x, y, 0.0) < -1e-12:
                self.left_out.append(name)  # its centre is inside: a blocker, pushed away
            else:
                self.objects.append(disc)

    def depth(self, dx, dy, yaw, x, y, r):
        """The room (m) between a disc and the free space with the gripper ended (dx, dy) from
        the goal point, turned by yaw; negative when they overlap."""
        c, s = math.cos(yaw), math.sin(yaw)
        ax, ay = c * self.along[0] - s * self.along[1], s * self.along[0] + c * self.along[1]
        bx = self.goal[0] + dx + self.ahead * ax
        by = self.goal[1] + dy + self.ahead * ay
        u = abs((x - bx) * ay - (y - by) * ax) - self.half_across  # across: the approach turned
        v = abs((x - bx) * ax + (y - by) * ay) - self.half_along
        outside = math.hypot(max(u, 0.0), max(v, 0.0))
        return (outside if outside > 0.0 else max(u, v)) - r

    def room(self, dx, dy, yaw, discs):
        return min(self.depth(dx, dy, yaw, x, y, r) for _, x, y, r in discs)

    def best_end(self, shift, max_yaw):
        best = (-math.inf, (0.0, 0.0, 0.0))
        steps = int(round(shift / 0.0005))
        yaws = [k * 0.01 for k in range(-int(round(max_yaw / 0.01)), int(round(max_yaw / 0.01)) + 1)]
        for i in range(-steps, steps + 1):
            for j in range(-steps, steps + 1):
                dx, dy = i * 0.0005, j * 0.0005
                if math.hypot(dx, dy) > shift + 1e-9:
                    continue
                for yaw in yaws:
                    here = self.room(dx, dy, yaw, self.objects)
                    if here > best[0]:
                        best = (here, (dx, dy, yaw))
        return best


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     epilog="Exit codes: 0 done, 2 bad input.")
    parser.add_argument("problem")
    parser.add_argument("--shift", type=float, default=0.0075,
                        help="m from the goal point the gripper may end (default 0.0075, the "
                             "dense suite's goal_shift)")
    parser.add_argument("--yaw", type=float, default=0.15,
                        help="rad the gripper may end turned about the vertical (default 0.15)")
    parser.add_argument("--ignore", default="", metavar="NAMES",
                        help="objects to leave out, comma-separated (those the plans move away)")
    parser.add_argument("--samples", type=int, default=20000, help="sampled worlds (20000)")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args(argv)
    if args.shift < 0 or args.yaw < 0 or args.samples < 1:
        parser.error("--shift and --yaw must be >= 0, --samples >= 1")
    try:
        scene = Scene(args.problem, [n for n in args.ignore.split(",") if n])
    except (OSError, ET.ParseError, ValueError, RuntimeError) as e:
        print(f"free-space-room: {e}", file=sys.stderr)
        return 2
    at_goal = scene.room(0.0, 0.0, 0.0, scene.objects)
    room, (dx, dy, yaw) = scene.best_end(args.shift, args.yaw)
    nearest = sorted(scene.objects, key=lambda d: scene.depth(dx, dy, yaw, d[1], d[2], d[3]))[:3]
    rng = random.Random(args.seed)
    filled, by_object = 0, {}
    for _ in range(args.samples):
        inside = [name for name, x, y, r in scene.objects
                  if scene.depth(dx, dy, yaw, x + rng.gauss(0.0, scene.sd[0]),
                                 y + rng.gauss(0.0, scene.sd[1]), r) < 0.0]
        filled += 1 if inside else 0
        for name in inside:
            by_object[name] = by_object.get(name, 0) + 1
    low, high = wilson(filled, args.samples)
    print(f"problem     {args.problem}")
    print(f"left out    {', '.join(scene.left_out) or 'none'} (centre inside the free space, "
          "or --ignore: moved away by the plans)")
    print(f"goal point  room {1000 * at_goal:.1f} mm to the nearest object (negative: overlap)")
    print(f"best end    room {1000 * room:.1f} mm, {1000 * dx:.1f} mm across x, {1000 * dy:.1f} mm "
          f"along y, turned {yaw:+.2f} rad (within {1000 * args.shift:.1f} mm and "
          f"{args.yaw:.2f} rad); nearest there: "
          + ", ".join(f"{n} {1000 * scene.depth(dx, dy, yaw, x, y, r):.1f} mm"
                      for n, x, y, r in nearest))
    print(f"pose noise  sd {1000 * scene.sd[0]:.1f} mm x, {1000 * scene.sd[1]:.1f} mm y: an object "
          f"in the free space at the best end in {filled} of {args.samples} worlds = "
          f"{100 * filled / args.samples:.1f} % (95 % Wilson {100 * low:.1f}-{100 * high:.1f} %)"
          + ("; " + ", ".join(f"{n} {k}" for n, k in sorted(by_object.items(),
                                                            key=lambda x: -x[1]))
             if by_object else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
