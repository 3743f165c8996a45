#!/usr/bin/python3
"""Plots impulse2d_bench's CSV (matplotlib from Debian, Agg backend, no display needed).

    /usr/bin/python3 scripts/plot_bench.py bench.csv [--out docs/img] [--table table.md]

Writes docs/img/bench_<scene>.png (error against ms/step, one curve per engine and solver: the
velocity-iteration sweep as a line, position-iteration and time-step sweeps as markers),
docs/img/bench_scaling.png (ms/step against body count) and docs/img/bench_headline.png (the
large pyramid and the stack of 20 side by side). --table writes the markdown table of the
engines' defaults with the ratios impulse2d / peer, then the ratios at equal or lower error: for
each peer at its defaults, the cheapest impulse2d row whose every error figure is at most the
peer's, among the rows timed in the same round robin as the peers (the defaults and the
`--also` settings, sweep "chosen"), all from the same CSV (the same run). A --full sweep shows
which settings to give --also; --candidates lists them.
"""
import argparse
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

# The figure each kind of scene is judged by (column, axis label).
PRIMARY = {
    "pyramid100": ("drift_max", "largest sideways drift (m)"),
    "pyramid20": ("drift_max", "largest sideways drift (m)"),
    "stack20": ("drift_max", "largest sideways drift (m)"),
    "mass_ratio": ("drift_max", "largest sideways drift (m)"),
    "bridge20": ("joint_gap_max", "largest joint gap (m)"),
    "joint_grid": ("joint_gap_max", "largest joint gap (m)"),
    "falling_shapes": ("penetration_max", "largest penetration beyond slop (m)"),
}
ENGINE_COLOURS = {"impulse2d": ["tab:blue", "tab:cyan", "tab:purple", "navy"],
                  "box2d": ["tab:orange"], "chipmunk": ["tab:green", "olive"]}
FLOOR = 1e-6  # log axes: zero error is drawn here


def load(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def num(row, key):
    value = row.get(key, "")
    return float(value) if value not in ("", None) else math.nan


def series(rows):
    """(engine, solver) -> rows, engines in the CSV's order."""
    out = {}
    for r in rows:
        out.setdefault((r["engine"], r["solver"]), []).append(r)
    return out


def colour(engine, solver, solvers_of):
    palette = ENGINE_COLOURS.get(engine, ["tab:gray"])
    return palette[solvers_of[engine].index(solver) % len(palette)]


def solvers_by_engine(rows):
    out = {}
    for r in rows:
        out.setdefault(r["engine"], [])
        if r["solver"] not in out[r["engine"]]:
            out[r["engine"]].append(r["solver"])
    return out


def error_axes(ax, rows, scene, column, label, solvers_of):
    scene_rows = [r for r in rows if r["scene"] == scene]
    for (engine, solver), group in series(scene_rows).items():
        c = colour(engine, solver, solvers_of)
        line = sorted((r for r in group if r["sweep"] in ("default", "velocity")),
                      key=lambda r: int(r["velocity_iterations"]))
        xs = [num(r, "ms_per_step") for r in line]
        ys = [max(num(r, column), FLOOR) for r in line]
        ax.plot(xs, ys, "-o", color=c, markersize=3, linewidth=0.8, alpha=0.8,
                label="%s %s" % (engine, solver))
        for r in line:
            if r["sweep"] == "default":
                ax.plot(num(r, "ms_per_step"), max(num(r, column), FLOOR), "*", color=c,
                        markersize=12, markeredgecolor="black")
        for sweep, marker in (("position", "s"), ("time_step", "^")):
            pts = [r for r in group if r["sweep"] == sweep]
            if pts:
                ax.plot([num(r, "ms_per_step") for r in pts],
                        [max(num(r, column), FLOOR) for r in pts], marker, color=c,
                        markersize=5, linestyle="none", fillstyle="none")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("ms per step (median of repeats)")
    ax.set_ylabel(label + ", 0 drawn at 1e-6")
    ax.set_title(scene)
    ax.grid(True, which="both", alpha=0.3)


def plot_scene(rows, scene, out_dir, solvers_of):
    column, label = PRIMARY[scene]
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    error_axes(axes[0], rows, scene, column, label, solvers_of)
    error_axes(axes[1], rows, scene, "penetration_mean", "mean penetration beyond slop (m)",
               solvers_of)
    axes[0].legend(fontsize=8)
    fig.suptitle("%s: error against time per step (line: velocity iterations 1..20; star: "
                 "defaults; square: position iterations; triangle: time step)" % scene, fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "bench_%s.png" % scene), dpi=90)
    plt.close(fig)


def plot_headline(rows, out_dir, solvers_of):
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    for ax, scene in zip(axes, ("pyramid100", "stack20")):
        column, label = PRIMARY[scene]
        error_axes(ax, rows, scene, column, label, solvers_of)
    axes[0].legend(fontsize=8)
    fig.suptitle("Speed against error, same run, same machine (lower left is better; "
                 "stars: each engine's defaults at 60 Hz)", fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "bench_headline.png"), dpi=90)
    plt.close(fig)


def plot_scaling(rows, out_dir, solvers_of):
    scaling = [r for r in rows if r["scene"].startswith("scaling_") and r["sweep"] == "default"]
    if not scaling:
        return
    fig, ax = plt.subplots(figsize=(7, 5))
    for (engine, solver), group in series(scaling).items():
        group = sorted(group, key=lambda r: int(r["bodies"]))
        ax.plot([int(r["bodies"]) for r in group], [num(r, "ms_per_step") for r in group], "-o",
                color=colour(engine, solver, solvers_of), markersize=4,
                label="%s %s" % (engine, solver))
    bodies = sorted({int(r["bodies"]) for r in scaling})
    first = min(num(r, "ms_per_step") for r in scaling if int(r["bodies"]) == bodies[0])
    ax.plot(bodies, [first * b / bodies[0] for b in bodies], "k--", linewidth=0.8,
            label="linear in body count")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("bodies (pyramids, awake, sleeping off)")
    ax.set_ylabel("ms per step")
    ax.set_title("Scaling: pyramids of 105 to 20,100 boxes, 60 Hz, each engine's defaults")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "bench_scaling.png"), dpi=90)
    plt.close(fig)


def fmt(x, digits=3):
    return "-" if math.isnan(x) else ("%.*g" % (digits, x))


def table(rows):
    """Markdown: each engine and solver at its defaults on the headline scenes, with ratios."""
    lines = ["| scene | engine | solver | ms/step | drift (m) | sink (m) | penetration mean / max (m) "
             "| stood | ms/step ratio impulse2d / this |",
             "|---|---|---|---|---|---|---|---|---|"]
    for scene in ("pyramid100", "stack20", "pyramid20", "mass_ratio", "bridge20", "joint_grid",
                  "falling_shapes"):
        defaults = [r for r in rows if r["scene"] == scene and r["sweep"] == "default"]
        mine = [r for r in defaults if r["engine"] == "impulse2d"]
        if not mine:
            continue
        reference = num(mine[0], "ms_per_step")  # impulse2d's default solver
        for r in defaults:
            error = "drift %s" % fmt(num(r, "drift_max"))
            if r["joint_gap_max"]:
                error = "gap %s" % fmt(num(r, "joint_gap_max"))
            lines.append("| %s | %s | %s | %s | %s | %s | %s / %s | %s | %s |" % (
                scene, r["engine"], r["solver"], fmt(num(r, "ms_per_step")),
                error if r["drift_max"] or r["joint_gap_max"] else "-",
                fmt(num(r, "sink_max")), fmt(num(r, "penetration_mean")),
                fmt(num(r, "penetration_max")), r["stood"],
                "%.2f" % (reference / num(r, "ms_per_step")) if r["engine"] != "impulse2d" else "-"))
    return "\n".join(lines) + "\n"


# Error figures a row must not exceed to count as "equal or lower error" (absolute values).
ERROR_COLUMNS = ("penetration_mean", "penetration_max", "drift_max", "sink_max", "joint_gap_mean",
                 "joint_gap_max", "energy_drift")


def cost(row):
    """Wall time per simulated second: rows at other time steps take more or fewer steps."""
    return num(row, "ms_per_step") / num(row, "time_step")


def no_worse(mine, peer):
    """mine's every error figure is at most peer's, and it stood wherever peer stood."""
    if peer["stood"] == "true" and mine["stood"] != "true":
        return False
    for column in ERROR_COLUMNS:
        if column == "energy_drift" and PRIMARY.get(mine["scene"], ("",))[0] == "penetration_max":
            continue  # falling scenes lose energy by design: losing less is not more accurate
        a, b = abs(num(mine, column)), abs(num(peer, column))
        if math.isnan(b):
            continue
        if math.isnan(a) or a > b:
            return False
    return True


def describe(row):
    return "%s %s/%s, dt 1/%.0f" % (row["solver"], row["velocity_iterations"],
                                    row["position_iterations"] or "-",
                                    1.0 / num(row, "time_step"))


def equal_error_table(rows):
    """Markdown: for each peer at its defaults, the cheapest impulse2d rows with no worse errors:
    at the peer's time step (ms/step compared), and at any time step (time per simulated second
    compared, as a coarser step with more iterations may be both cheaper and more accurate)."""
    lines = ["| scene | peer at its defaults | peer ms/step | impulse2d at the same time step: "
             "cheapest row with every error at most the peer's (solver velocity/position "
             "iterations) | its ms/step | ratio | at any time step: cheapest such row | "
             "time per simulated second, ratio |",
             "|---|---|---|---|---|---|---|---|"]
    for scene in ("pyramid100", "stack20", "pyramid20", "mass_ratio", "bridge20", "joint_grid",
                  "falling_shapes"):
        peers = [r for r in rows if r["scene"] == scene and r["sweep"] == "default"
                 and r["engine"] != "impulse2d"]
        # Only rows timed beside the peers: a swept row ran alone, at another moment's load.
        mine = [r for r in rows if r["scene"] == scene and r["engine"] == "impulse2d"
                and r["sweep"] in ("default", "chosen")]
        for peer in peers:
            name = "%s %s" % (peer["engine"], peer["solver"])
            cells = ["%s" % scene, name, fmt(num(peer, "ms_per_step"))]
            candidates = [r for r in mine if no_worse(r, peer)]
            same_step = [r for r in candidates if r["time_step"] == peer["time_step"]]
            if same_step:
                best = min(same_step, key=cost)
                cells += [describe(best), fmt(num(best, "ms_per_step")),
                          "**%.2f**" % (num(best, "ms_per_step") / num(peer, "ms_per_step"))]
            else:
                cells += ["none", "-", "-"]
            if candidates:
                best = min(candidates, key=cost)
                cells += [describe(best), "%.2f" % (cost(best) / cost(peer))]
            else:
                cells += ["none", "-"]
            lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def candidates(rows):
    """Text: per peer at its defaults, the impulse2d rows of the sweep with no worse errors,
    cheapest first (their times are single runs at different moments: a guide for --also)."""
    out = []
    for peer in [r for r in rows if r["sweep"] == "default" and r["engine"] != "impulse2d"]:
        mine = [r for r in rows if r["scene"] == peer["scene"] and r["engine"] == "impulse2d"
                and no_worse(r, peer)]
        mine.sort(key=cost)
        out.append("%s %s %s: %s" % (peer["scene"], peer["engine"], peer["solver"], ", ".join(
            "%s:%s:%s:%.0f (%s ms/step)" % (r["solver"], r["velocity_iterations"],
                                            r["position_iterations"] or 0,
                                            1.0 / num(r, "time_step"), fmt(num(r, "ms_per_step")))
            for r in mine[:6]) or "none"))
    return "\n".join(out)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("csv")
    parser.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                      "..", "docs", "img"))
    parser.add_argument("--table", help="write the markdown table of defaults and ratios here")
    parser.add_argument("--candidates", action="store_true",
                        help="print, per peer, the sweep's impulse2d settings with no worse "
                        "errors (for impulse2d_bench --also), and plot nothing")
    args = parser.parse_args()
    rows = load(args.csv)
    if not rows:
        sys.exit("plot_bench: %s has no rows" % args.csv)
    if args.candidates:
        print(candidates(rows))
        return
    os.makedirs(args.out, exist_ok=True)
    solvers_of = solvers_by_engine(rows)
    scenes = [s for s in PRIMARY if any(r["scene"] == s for r in rows)]
    for scene in scenes:
        plot_scene(rows, scene, args.out, solvers_of)
    if "pyramid100" in scenes and "stack20" in scenes:
        plot_headline(rows, args.out, solvers_of)
    plot_scaling(rows, args.out, solvers_of)
    if args.table:
        with open(args.table, "w") as f:
            f.write(table(rows))
            f.write("\n")
            f.write(equal_error_table(rows))
    print("plot_bench: %d scenes plotted into %s" % (len(scenes), os.path.normpath(args.out)))


if __name__ == "__main__":
    main()
