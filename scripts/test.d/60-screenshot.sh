#!/usr/bin/env bash
# RViz end to end, both planes: scripts/screenshot.sh runs the node and RViz (under Xvfb) on the
# demo scene (side view, xz) and on config/topdown.yaml (top-down, xy), and
# scripts/check_screenshot.py asserts that the 3D view shows the marker colours of every body
# state, contact points, normals and joints, spread over the view (not the empty grid, not the
# plane seen edge-on). A broken RViz config (a wrong topic, a namespace off, a view that misses
# the plane), launch file or marker code fails it. JUnit XML: one case per plane for the run,
# one per colour and one for the spread.
# Bound: 2 x (50 s + 8 s to clean up) < 2 min; typically 2 x 20 s.
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

check_plane() {  # check_plane PLANE SCENE COLOURS
  local plane="$1" scene="$2" colours="$3" suite="screenshot_$1" started=$SECONDS log
  log="$shots/$plane.log"
  if timeout -k 8 50 "$REPO/scripts/screenshot.sh" "$shots/$plane.png" "$scene" --plane "$plane" >"$log" 2>&1; then
    junit_case "$results/${suite}_run.xml" "$suite" run
    echo "$plane: screenshot in $((SECONDS - started)) s: $(tail -n 1 "$log")"
    python3 "$REPO/scripts/check_screenshot.py" "$shots/$plane.png" --expect "$colours" \
      --junit "$results/${suite}_colours.xml" --name "$suite" || status=1
  else
    cat "$log" >&2
    junit_case "$results/${suite}_run.xml" "$suite" run "screenshot.sh failed: $(tail -n 1 "$log")"
    status=1
  fi
}

check_plane xz "$REPO/config/demo.yaml" static,awake,asleep,contact_point,contact_normal,joint
check_plane xy "$REPO/config/topdown.yaml" static,kinematic,awake,asleep,contact_point,contact_normal,joint
exit "$status"
