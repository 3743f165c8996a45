#!/usr/bin/env bash
# One command from a fresh machine to every test: installs what is missing, builds the catkin
# workspace from scratch, runs the unit tests and rostests (catkin run_tests), then the stages of
# scripts/test.d/: catkin_lint, fuzzing (a core-only build without catkin, so it also proves the
# core is ROS-free), the whole package again under AddressSanitizer + UndefinedBehaviorSanitizer
# (unit tests, ROS unit tests, the rostests against the node and the nodelet; 35-asan.sh),
# ThreadSanitizer on the node, the benchmark's smoke run, RViz end to end, and the README's and
# tutorials' shell examples run as written (70-examples.sh).
# Ends with "N passed, N failed" and exits non-zero on any failure or build error.
set -uo pipefail
REPO="$(cd "$(dirname "$0")/.." && pwd)"
export PATH="/usr/bin:$PATH"
export IMPULSE2D_WS="${IMPULSE2D_WS:-${XDG_CACHE_HOME:-$HOME/.cache}/impulse2d_ws}"
WS="$IMPULSE2D_WS"
RESULTS="$WS/results"
failed_steps=0

step() {  # step NAME COMMAND...: runs a stage, counts it as a failure when it fails
  local name="$1"; shift
  local started=$SECONDS
  echo "=== $name" >&2
  if ! "$@"; then
    echo "=== $name FAILED ($((SECONDS - started)) s)" >&2
    failed_steps=$((failed_steps + 1))
    return 1
  fi
  echo "=== $name done ($((SECONDS - started)) s)" >&2  # CI should stay under 30 minutes
}

step "install dependencies" "$REPO/scripts/install_deps.sh" || { echo "0 passed, 1 failed"; exit 1; }
if step "build (catkin)" "$REPO/scripts/build.sh" --clean >/dev/null; then
  # run_tests exits 0 even when tests fail: the XML results below are what counts.
  step "unit tests and rostests" catkin_make -C "$WS" run_tests -DPYTHON_EXECUTABLE=/usr/bin/python3 -j2 >&2
fi
rm -rf "$RESULTS"  # after the clean build, which empties the workspace
mkdir -p "$RESULTS"
if ! cp -r "$WS/build/test_results" "$RESULTS/catkin" 2>/dev/null; then
  echo "=== no catkin test results" >&2
  failed_steps=$((failed_steps + 1))
fi

# Further stages, one file each, in name order: scripts/test.d/NN-name.sh. Each runs with REPO,
# IMPULSE2D_WS (the built catkin workspace) and STAGE_RESULTS (a folder for its JUnit XML, which
# is counted below) set; a non-zero exit counts as one failure.
# But the stages of ALONGSIDE, which run in the background while another one does: started with
# it, waited for when it ends, their output printed then. 70-examples mostly waits (worlds coming
# up, `rostopic pub -1`'s 3 s latch) and checks what commands print, not how fast; 30-fuzz is a
# compile and time-bounded fuzzing, which only does fewer runs when it shares the cores. Nothing
# timed runs beside them (the ROS soak's 1 s bound, the rostests' wall-clock nodes).
declare -A ALONGSIDE=([30-fuzz]=70-examples)
run_stage() {  # run_stage NAME
  mkdir -p "$RESULTS/$1"
  REPO="$REPO" STAGE_RESULTS="$RESULTS/$1" step "$1" bash "$REPO/scripts/test.d/$1.sh"
}
for stage in "$REPO"/scripts/test.d/*.sh; do
  [ -e "$stage" ] || continue
  name="$(basename "$stage" .sh)"
  [[ " ${ALONGSIDE[*]} " == *" $name "* ]] && continue  # runs beside its partner
  partner="${ALONGSIDE[$name]:-}"
  if [ -n "$partner" ]; then
    echo "=== $partner runs alongside $name" >&2
    run_stage "$partner" >"$RESULTS/$partner.out" 2>&1 &
    partner_pid=$!
  fi
  run_stage "$name" >&2
  if [ -n "$partner" ]; then
    wait "$partner_pid" || failed_steps=$((failed_steps + 1))
    cat "$RESULTS/$partner.out" >&2
  fi
done

# Count test cases from every JUnit XML written (gtest and rostest both write them).
read -r total failures < <(python3 - "$RESULTS" <<'PY'
import glob, sys, xml.etree.ElementTree as ET
total = failed = 0
for path in glob.glob(sys.argv[1] + "/**/*.xml", recursive=True):
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError:
        total += 1; failed += 1; continue
    for case in root.iter("testcase"):
        total += 1
        if case.find("failure") is not None or case.find("error") is not None:
            failed += 1
print(total, failed)
PY
)
passed=$((total - failures))
failed=$((failures + failed_steps))
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ] && [ "$total" -gt 0 ]
