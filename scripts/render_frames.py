#!/usr/bin/python3
"""Draws a scene at several moments side by side, from impulse2d_sim's --csv output.

  render_frames.py SCENE.yaml OUT.png [--times 0,0.5,1,2] [--sim PATH] [--columns N]
                   [--title TEXT] [--xlim X0,X1] [--ylim Y0,Y1]

Runs impulse2d_sim (default: $IMPULSE2D_WS/devel/lib/impulse2d/impulse2d_sim, the workspace of
scripts/build.sh) on SCENE up to the last time, reads the poses of the moving bodies from its
CSV, takes the shapes and the static bodies from SCENE, and draws one panel per time with
matplotlib (no display needed). Times are rounded to whole steps.
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Circle, Polygon  # noqa: E402
import yaml  # noqa: E402

STATIC = "#8c8c8c"
DYNAMIC = "#2ca02c"
KINEMATIC = "#ff9a1a"


def default_sim():
    ws = os.environ.get("IMPULSE2D_WS") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"), "impulse2d_ws")
    return os.path.join(ws, "devel", "lib", "impulse2d", "impulse2d_sim")


def rotate(point, angle):
    c, s = math.cos(angle), math.sin(angle)
    return (c * point[0] - s * point[1], s * point[0] + c * point[1])


def outline(shape):
    """('circle', centre, radius) or ('polygon', vertices), in the body frame."""
    offset = shape.get("offset", [0.0, 0.0])
    angle = shape.get("angle", 0.0)
    kind = shape.get("type", "box")
    if kind == "circle":
        return ("circle", tuple(offset), shape.get("radius", 0.5))
    if kind == "box":
        w, h = shape.get("size", [1.0, 1.0])
        local = [(-w / 2, -h / 2), (w / 2, -h / 2), (w / 2, h / 2), (-w / 2, h / 2)]
    else:
        local = [tuple(v) for v in shape["vertices"]]
    return ("polygon", [tuple(a + b for a, b in zip(rotate(v, angle), offset)) for v in local])


def place(shape, x, y, angle):
    """A matplotlib patch of the outline at the body pose (x, y, angle)."""
    if shape[0] == "circle":
        cx, cy = rotate(shape[1], angle)
        return "circle", (x + cx, y + cy), shape[2]
    return "polygon", [(x + px, y + py) for px, py in (rotate(v, angle) for v in shape[1])]


def load_scene(path):
    with open(path) as f:
        scene = yaml.safe_load(f) or {}
    world = scene.get("world") or {}
    bodies = []
    for body in scene.get("bodies") or []:
        bodies.append({
            "name": body["name"],
            "type": body.get("type", "dynamic"),
            "pose": (*body.get("position", [0.0, 0.0]), body.get("angle", 0.0)),
            "shapes": [outline(s) for s in body.get("shapes") or []],
        })
    return world.get("time_step", 0.01), bodies


def run_sim(sim, scene, steps, every):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "poses.csv")
        cmd = [sim, scene, "--steps", str(steps), "--every", str(every), "--csv", out]
        done = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if done.returncode != 0:
            sys.exit("render_frames: %s failed: %s" % (" ".join(cmd), done.stderr.strip()))
        poses = {}  # step -> name -> (x, y, angle)
        with open(out) as f:
            for row in csv.DictReader(f):
                poses.setdefault(int(row["step"]), {})[row["body"]] = (
                    float(row["x"]), float(row["y"]), float(row["angle"]))
        return poses


def draw(axes, bodies, poses, title, xlim, ylim):
    for body in bodies:
        pose = poses.get(body["name"], body["pose"])
        colour = {"static": STATIC, "kinematic": KINEMATIC}.get(body["type"], DYNAMIC)
        for shape in body["shapes"]:
            placed = place(shape, *pose)
            if placed[0] == "circle":
                patch = Circle(placed[1], placed[2])
            else:
                patch = Polygon(placed[1], closed=True)
            patch.set_facecolor(colour)
            patch.set_alpha(0.35 if body["type"] != "static" else 0.6)
            patch.set_edgecolor(colour)
            patch.set_linewidth(1.5)
            axes.add_patch(patch)
    axes.set_title(title, fontsize=10)
    axes.set_aspect("equal")
    axes.set_xlim(*xlim)
    axes.set_ylim(*ylim)
    axes.set_xticks([])
    axes.set_yticks([])


def pair(text):
    low, high = (float(v) for v in text.split(","))
    return low, high


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene")
    parser.add_argument("out")
    parser.add_argument("--times", default="0,0.5,1,2", help="seconds, comma-separated")
    parser.add_argument("--sim", default=default_sim(), help="the impulse2d_sim executable")
    parser.add_argument("--columns", type=int, default=0, help="panels per row (default: all)")
    parser.add_argument("--title", default="")
    parser.add_argument("--xlim", type=pair, help="x0,x1 in metres (default: fit the bodies)")
    parser.add_argument("--ylim", type=pair, help="y0,y1 in metres")
    args = parser.parse_args()

    if not os.access(args.sim, os.X_OK):
        sys.exit("render_frames: no impulse2d_sim at %s (build with scripts/build.sh, or --sim)"
                 % args.sim)
    time_step, bodies = load_scene(args.scene)
    times = [float(t) for t in args.times.split(",")]
    steps = [round(t / time_step) for t in times]
    every = math.gcd(*[s for s in steps if s > 0]) if any(steps) else 1
    poses = run_sim(args.sim, args.scene, max(max(steps), 1), every)
    missing = [s for s in steps if s not in poses]
    if missing:
        sys.exit("render_frames: the simulation wrote no step %s" % missing)

    xlim, ylim = args.xlim, args.ylim
    if not xlim or not ylim:  # fit the moving bodies over all frames, with a margin
        xs = [p[0] for s in steps for p in poses[s].values()]
        ys = [p[1] for s in steps for p in poses[s].values()]
        margin = 0.1 * max(max(xs) - min(xs), max(ys) - min(ys), 1.0)
        xlim = xlim or (min(xs) - margin, max(xs) + margin)
        ylim = ylim or (min(ys) - margin, max(ys) + margin)

    columns = args.columns or len(steps)
    rows = math.ceil(len(steps) / columns)
    aspect = (ylim[1] - ylim[0]) / (xlim[1] - xlim[0])
    figure, axes = plt.subplots(rows, columns, squeeze=False,
                                figsize=(3.2 * columns, 3.2 * aspect * rows + 0.6))
    for i, (t, s) in enumerate(zip(times, steps)):
        draw(axes[i // columns][i % columns], bodies, poses[s], "t = %g s" % t, xlim, ylim)
    for i in range(len(steps), rows * columns):
        axes[i // columns][i % columns].axis("off")
    if args.title:
        figure.suptitle(args.title, fontsize=11)
    figure.tight_layout(h_pad=1.5)
    figure.savefig(args.out, dpi=100)
    print("render_frames: %s (%d frames)" % (args.out, len(steps)))


if __name__ == "__main__":
    main()
