#!/usr/bin/env bash
# RViz end to end, both planes: scripts/screenshot.sh runs the node and RViz (under Xvfb) on the
# demo scene (side view, xz), on config/topdown.yaml (top-down, xy) and the robot demo (driven;
# its scan, odometry and RobotModel), and
# scripts/check_screenshot.py asserts that the 3D view shows the marker colours of every body
# state, contact points, normals and joints, spread over the view (not the empty grid, not the
# plane seen edge-on). A broken RViz config (a wrong topic, a namespace off, a view that misses
# the plane), launch file or marker code fails it. JUnit XML: one case per screenshot for the run,
# one per colour and one for the spread.
# Bound: 3 x (50 s + 8 s to clean up) < 3 min, twice that if RViz dies each time (run_shot);
# typically 3 x 20 s.
set -uo pipefail
REPO="${REPO:-$(cd "$(dirname "$0")/../.." && pwd)}"
export PATH="/usr/bin:$PATH"
results="${STAGE_RESULTS:-$(mktemp -d)}"
shots="$results/shots"
mkdir -p "$shots"
status=0

junit_case() {  # junit_case FILE SUITE NAME [FAILURE]: one test case in its own file
  python3 - "$@" <<'PY'
import sys, xml.etree.ElementTree as ET
path, suite, name = sys.argv[1:4]
failure = sys.argv[4] if len(sys.argv) > 4 else ""
root = ET.Element("testsuite", name=suite, tests="1", failures="1" if failure else "0")
case = ET.SubElement(root, "testcase", classname=suite, name=name)
if failure:
    ET.SubElement(case, "failure", message=failure).text = failure
ET.ElementTree(root).write(path, encoding="utf-8", xml_declaration=True)
PY
}

run_shot() {  # run_shot LOG SCREENSHOT_ARGS...: screenshot.sh, once more if RViz itself died
  local log="$1"
  shift
  timeout -k 8 50 "$REPO/scripts/screenshot.sh" "$@" >"$log" 2>&1 && return 0
  # RViz itself once died at start-up under Xvfb ("free(): invalid next size", exit -6, before it
  # drew anything; the runs before and after passed). Such a run is shown and made once more; a
  # broken config, launch file or marker code fails the second run as it did the first.
  grep -q 'rviz-[0-9]*\] process has died' "$log" || return 1
  cat "$log" >&2
  echo "RViz died at start-up (above); once more" >&2
  timeout -k 8 50 "$REPO/scripts/screenshot.sh" "$@" >"$log" 2>&1
}

check_shot() {  # check_shot NAME COLOURS SCREENSHOT_ARGS...
  local name="$1" colours="$2" suite="screenshot_$1" started=$SECONDS log
  shift 2
  log="$shots/$name.log"
  if run_shot "$log" "$shots/$name.png" "$@"; then
    junit_case "$results/${suite}_run.xml" "$suite" run
    echo "$name: screenshot in $((SECONDS - started)) s: $(tail -n 1 "$log")"
    python3 "$REPO/scripts/check_screenshot.py" "$shots/$name.png" --expect "$colours" \
      --junit "$results/${suite}_colours.xml" --name "$suite" || status=1
  else
    cat "$log" >&2
    junit_case "$results/${suite}_run.xml" "$suite" run "screenshot.sh failed: $(tail -n 1 "$log")"
    status=1
  fi
}

check_shot xz static,awake,asleep,contact_point,contact_normal,joint "$REPO/config/demo.yaml" --plane xz
check_shot xy static,kinematic,awake,asleep,contact_point,contact_normal,joint \
  "$REPO/config/topdown.yaml" --plane xy
# The robot demo, driven: its scan, its odometry arrows and the robot drawn by RobotModel.
check_shot robot static,asleep,scan,odometry,robot --launch robot_demo.launch --cmd-vel '0.5 0.03' \
  --settle 5
exit "$status"
