#!/usr/bin/python3
"""The markdown table of Box2D v3's scenes (v3.1.1's seven, master's washer, compounds and
junkyard) from one impulse2d_bench run (scripts/bench_v3.sh).

    /usr/bin/python3 scripts/v3_table.py bench_v3.csv [--out table.md]

One line per scene and engine setting (impulse2d's default, any --also rows, box2d_v3): ms/step at
each thread count of the run, the speed-up from 1 to 2 threads, the time against box2d_v3's at the
same count, and the error figures that fit the scene (from the 1-thread row; every engine here
gives the same results whatever its thread count). A row the engine refused (impulse2d before it
has threads) reads "refused".
"""
import argparse
import csv
import math
import sys

SCENES = ["v3_joint_grid", "v3_large_pyramid", "v3_many_pyramids", "v3_rain", "v3_smash",
          "v3_spinner", "v3_tumbler", "v3_washer", "v3_compounds", "v3_junkyard"]


def num(row, key):
    value = row.get(key, "")
    return float(value) if value not in ("", None) else math.nan


def fmt(x, digits=3):
    if math.isnan(x):
        return "-"
    return "%.*g" % (digits, x)


def errors(row):
    """The figures that fit the scene's kind (docs/benchmarks.md, v3 scenes)."""
    pen = "penetration %s / %s mm" % (fmt(1e3 * num(row, "penetration_mean"), 2),
                                      fmt(1e3 * num(row, "penetration_max"), 2))
    if row["drift_max"]:
        return "drift %s m, sink %s m, %s" % (fmt(num(row, "drift_max")),
                                              fmt(num(row, "sink_max")), pen)
    if row["momentum_drift"]:
        return "momentum %s, energy %s, %s" % (fmt(num(row, "momentum_drift"), 2),
                                               fmt(num(row, "energy_drift"), 2), pen)
    if row["escaped"]:
        return "escaped %s, %s" % (row["escaped"], pen)
    return "joint gap %s / %s m, %s" % (fmt(num(row, "joint_gap_mean"), 2),
                                        fmt(num(row, "joint_gap_max"), 2), pen)


def setting(row):
    name = row["engine"] if row["sweep"] == "default" else "%s %s %s/%s" % (
        row["engine"], row["solver"], row["velocity_iterations"], row["position_iterations"])
    return name if row["sweep"] != "default" or row["engine"] != "impulse2d" else \
        "impulse2d %s (default)" % row["solver"]


def table(rows):
    counts = sorted({int(r["threads"]) for r in rows})
    head = ["scene (steps)", "engine, settings"] + ["ms/step, %d thread%s" % (
        t, "" if t == 1 else "s") for t in counts]
    if 1 in counts and 2 in counts:
        head.append("speed-up 1 -> 2")
    head += ["/ box2d_v3, %d" % t for t in counts] + ["error figures (1 thread)"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for scene in SCENES:
        mine = [r for r in rows if r["scene"] == scene]
        if not mine:
            continue
        v3 = {int(r["threads"]): num(r, "ms_per_step") for r in mine if r["engine"] == "box2d_v3"}
        keys = []
        for r in mine:
            if (setting(r), r["time_step"]) not in keys:
                keys.append((setting(r), r["time_step"]))
        for key in keys:
            group = [r for r in mine if (setting(r), r["time_step"]) == key]
            by = {int(r["threads"]): r for r in group}
            ms = {t: num(by[t], "ms_per_step") if t in by else math.nan for t in counts}
            cells = ["%s (%s)" % (scene, group[0]["steps"]), key[0]]
            cells += [fmt(ms[t]) if t in by else "refused" for t in counts]
            if 1 in counts and 2 in counts:
                cells.append(fmt(ms[1] / ms[2], 2) + "x" if 1 in by and 2 in by else "-")
            cells += [fmt(ms[t] / v3[t], 2) if t in by and t in v3 else "-" for t in counts]
            first = by.get(1, group[0])
            cells.append(errors(first) + ("" if first["stood"] == "true" else " (did not hold)"))
            lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("csv")
    parser.add_argument("--out", help="write the table here (default: print it)")
    args = parser.parse_args()
    with open(args.csv) as f:
        rows = [r for r in csv.DictReader(f) if r["scene"] in SCENES]
    if not rows:
        sys.exit("v3_table: %s has no v3_ scene rows" % args.csv)
    text = table(rows)
    if args.out:
        with open(args.out, "w") as f:
            f.write(text)
    else:
        sys.stdout.write(text)


if __name__ == "__main__":
    main()
