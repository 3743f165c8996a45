#!/usr/bin/env bash
# CI smoke test of impulse2d_bench: runs `--quick` (about 10 s here, bounded at 120 s by a
# timeout) and checks its CSVs: the header, every scene and engine present, no NaN, sane values.
# Its times are never checked. Writes $STAGE_RESULTS/bench_quick.xml (JUnit).
set -uo pipefail
BENCH="$IMPULSE2D_WS/devel/lib/impulse2d/impulse2d_bench"
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT
status=0
timeout 120 "$BENCH" --quick --csv "$OUT/bench.csv" >"$OUT/stdout.txt" 2>"$OUT/stderr.txt" || status=$?
tail -n 3 "$OUT/stderr.txt" >&2
/usr/bin/python3 - "$OUT" "$status" "$STAGE_RESULTS/bench_quick.xml" <<'PY'
import csv, math, os, sys
from xml.sax.saxutils import escape

out, status, xml_path = sys.argv[1], int(sys.argv[2]), sys.argv[3]
cases = []  # (name, failure message or None)

def check(name, ok, why=""):
    cases.append((name, None if ok else why))

HEADER = ("engine,solver,scene,sweep,time_step,velocity_iterations,position_iterations,threads,"
          "bodies,joints,steps,ms_per_step,contacts,penetration_mean,penetration_max,drift_max,"
          "sink_max,joint_gap_mean,joint_gap_max,energy_drift,escaped,momentum_drift,"
          "stood").split(",")
SCENES = ["pyramid100", "pyramid20", "stack20", "mass_ratio", "bridge20", "joint_grid",
          "falling_shapes", "scaling_105", "scaling_528", "v3_joint_grid", "v3_large_pyramid",
          "v3_many_pyramids", "v3_rain", "v3_smash", "v3_spinner", "v3_tumbler", "v3_washer",
          "v3_compounds", "v3_junkyard"]
ENGINES = ["impulse2d", "box2d", "chipmunk"]

check("runs within 120 s and exits 0", status == 0, "exit status %d" % status)
rows, header = [], []
path = os.path.join(out, "bench.csv")
if os.path.exists(path):
    with open(path) as f:
        reader = csv.reader(f)
        header = next(reader, [])
        rows = [dict(zip(header, r)) for r in reader]
check("csv header", header == HEADER, "got %s" % header)
for scene in SCENES:
    for engine in ENGINES:
        check("row for %s on %s" % (engine, scene),
              any(r["engine"] == engine and r["scene"] == scene for r in rows) if rows else False,
              "missing")

bad = []
for r in rows:
    for key in HEADER[4:22]:
        value = r.get(key, "")
        if value == "":
            continue
        try:
            x = float(value)
        except ValueError:
            bad.append("%s/%s/%s %s=%r" % (r["engine"], r["solver"], r["scene"], key, value)); continue
        if not math.isfinite(x):
            bad.append("%s/%s/%s %s=%s" % (r["engine"], r["solver"], r["scene"], key, value))
check("no NaN or inf", not bad, "; ".join(bad[:5]))

insane = []
for r in rows:
    tag = "%s/%s/%s" % (r["engine"], r["solver"], r["scene"])
    try:
        if not float(r["ms_per_step"]) > 0.0: insane.append(tag + " ms_per_step <= 0")
        if int(r["steps"]) < 1 or int(r["bodies"]) < 1: insane.append(tag + " no steps or bodies")
        for key in ("penetration_mean", "penetration_max"):
            if not 0.0 <= float(r[key]) < 1.0: insane.append(tag + " " + key)
        if r["joint_gap_max"] and not 0.0 <= float(r["joint_gap_max"]) < 1.0: insane.append(tag + " joint gap")
        if int(r["threads"]) != 1: insane.append(tag + " threads")
        if r["escaped"] and int(r["escaped"]) < 0: insane.append(tag + " escaped")
        if r["momentum_drift"] and not 0.0 <= float(r["momentum_drift"]) < 1.0: insane.append(tag + " momentum")
        if r["stood"] not in ("true", "false"): insane.append(tag + " stood")
    except (KeyError, ValueError) as e:
        insane.append("%s: %s" % (tag, e))
check("values in range", not insane, "; ".join(insane[:5]))
for scene in ("stack20", "pyramid20", "bridge20", "v3_large_pyramid", "v3_tumbler"):
    mine = [r for r in rows if r["engine"] == "impulse2d" and r["scene"] == scene and r["solver"] == "substep"]
    check("impulse2d substep stands on " + scene, bool(mine) and all(r["stood"] == "true" for r in mine),
          "did not stand" if mine else "missing")

memory_path = os.path.join(out, "bench_memory.csv")
memory = []
if os.path.exists(memory_path):
    with open(memory_path) as f:
        memory = list(csv.DictReader(f))
for engine in ENGINES:
    m = [r for r in memory if r["engine"] == engine]
    check("memory figures for " + engine,
          bool(m) and float(m[0]["bytes_per_body"]) > 0 and float(m[0]["bytes_per_contact"]) >= 0,
          "missing or zero")

failures = sum(1 for _, why in cases if why is not None)
with open(xml_path, "w") as f:
    f.write('<?xml version="1.0" encoding="UTF-8"?>\n')
    f.write('<testsuite name="bench_quick" tests="%d" failures="%d">\n' % (len(cases), failures))
    for name, why in cases:
        f.write('  <testcase classname="bench_quick" name="%s"' % escape(name, {'"': "&quot;"}))
        if why is None:
            f.write("/>\n")
        else:
            f.write('>\n    <failure message="%s"/>\n  </testcase>\n' % escape(why, {'"': "&quot;"}))
    f.write("</testsuite>\n")
for name, why in cases:
    if why is not None:
        print("bench quick: FAILED %s: %s" % (name, why), file=sys.stderr)
print("bench quick: %d checks, %d failed" % (len(cases), failures), file=sys.stderr)
sys.exit(1 if failures else 0)
PY
