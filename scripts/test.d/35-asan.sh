#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer on the whole package: builds it with
# -DIMPULSE2D_SANITIZE=ON in a separate catkin workspace ($IMPULSE2D_WS-asan), then runs every
# gtest and rostest that catkin registers there (but the ones skipped below, with the reason):
# the unit tests of the engine, the scene loader, the URDF loader and the CLI (which the unit tests
# run as a child process, instrumented too), the ROS unit tests, and the rostests against
# impulse2d_node and against the nodelet in Debian's nodelet manager. What is instrumented is the
# product: the libraries (engine, scene, URDF, devices, ROS layer), the node, the plugin, the CLI
# and the wanderer. The gtest programs' own code is not (cmake/sanitize_tests.cmake): it runs with
# the sanitizers' runtimes and calls instrumented libraries, and compiling it instrumented was half
# of this build. The rostests' clients are the release build's (CLIENTS below).
#
# Fails on a failing test, a test program's non-zero exit, and any sanitizer report from any of
# those processes. Reports do not reach the tests' XML: ASan's and LeakSanitizer's go to
# $STAGE_RESULTS/sanitizer/ (log_path), UBSan's to the output kept in $STAGE_RESULTS; all are
# counted into one extra JUnit case, no_sanitizer_reports. Leak checking is on.
# Bound: build ~8 min on 2 cores (the libraries, node, plugin, CLI and gtest programs; -O1 -g1
# below), run ~3 min (the unit tests alongside the rostests).
set -uo pipefail
REPO="${REPO:-$(cd "$(dirname "$0")/../.." && pwd)}"
STAGE_RESULTS="${STAGE_RESULTS:-$(mktemp -d)}"
export PATH="/usr/bin:$PATH"
# shellcheck source=lib/side_workspace.bash
source "$REPO/scripts/test.d/lib/side_workspace.bash"
side_workspace asan
mkdir -p "$STAGE_RESULTS"

# The gtest programs run directly, and the rostests (test/ros/NAME.test); TARGETS builds the
# gtests, the node, the nodelet plugin, the wanderer and the CLI. The rostests' clients (CLIENTS)
# are the release workspace's (link_release_clients): they call the instrumented node. But the
# hash test's client, built here: it links the package's scene library, which this workspace's
# library path would load instrumented into an uninstrumented program.
GTESTS=(impulse2d_unit_tests impulse2d_ros_unit_tests impulse2d_sim_world_limits_tests)
ROSTESTS=(world_node world_nodelet hash hash_threads urdf recipe robot devices devices_nodelet maps
  maps_nodelet models models_nodelet fleet)
TARGETS=("${GTESTS[@]}" impulse2d_hash_test impulse2d_wanderer impulse2d_node impulse2d_nodelet
  impulse2d_sim)
CLIENTS=(impulse2d_world_tests impulse2d_urdf_tests impulse2d_recipe_test
  impulse2d_robot_tests impulse2d_devices_tests impulse2d_maps_tests impulse2d_models_tests
  impulse2d_fleet_tests)
# Registered with catkin but not run here (they run in the release build of scripts/test.sh):
# - load.test: 60 s of requests at 1 kHz. Under ASan everything else held (0 unanswered, 0
#   unexpected, no report) but its resident-memory bound cannot: the node grew 350 MiB during the
#   storm (ASan's quarantine keeps freed blocks; LeakSanitizer finds real leaks), against 8 MiB.
# - the roslaunch file checks: they only parse launch files; none of our code runs.
SKIPPED=(rostest_test_ros_load.test 'roslaunch-check*')
# The unit tests but three long runs of paths the other tests cover, which run in the release
# build: the 5050-box pyramid (26 s there), the soak seeds that once failed (121 s instrumented)
# and the pinned chain with joints that cannot all hold (39 s instrumented).
UNIT_FILTER=-HardCase.PyramidOfBaseHundredStands:HardCasesRobust.SoakSeedsThatOnceFailedNowHold
UNIT_FILTER+=:HardCasesRobust.APinnedChainGivenJointsThatCannotAllHoldStaysNearItsPin

XML="$STAGE_RESULTS/asan.xml"
cases=()     # JUnit <testcase> lines of this script's own checks
failures=0
add_case() {  # add_case NAME [FAILURE_MESSAGE DETAILS_FILE]
  if [ $# -eq 1 ]; then
    cases+=("  <testcase classname=\"asan\" name=\"$1\"/>")
  else
    failures=$((failures + 1))
    local tag="  <testcase classname=\"asan\" name=\"$1\"><failure message=\"$2\">" details
    # Without the terminal's colour codes and other control characters, which XML refuses.
    details="$(head -c 20000 "$3" 2>/dev/null | sed 's/\x1b\[[0-9;]*m//g; s/]]>/]] >/g' |
      tr -d '\000-\010\013\014\016-\037')"
    cases+=("$tag<![CDATA[$details]]></failure></testcase>")
  fi
}
write_xml() {
  {
    echo '<?xml version="1.0" encoding="UTF-8"?>'
    echo "<testsuite name=\"asan\" tests=\"${#cases[@]}\" failures=\"$failures\">"
    printf '%s\n' "${cases[@]}"
    echo '</testsuite>'
  } >"$XML"
}

# -O1 -g1: half the compile time of RelWithDebInfo's -O2 -g (the unit tests then run 10% longer);
# line tables are all the reports need for file:line stacks, inlined frames included.
if ! (cd "$WS" && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DIMPULSE2D_SANITIZE=ON \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
    -j"$(nproc)" "${TARGETS[@]}" >"$STAGE_RESULTS/build.log" 2>&1); then
  tail -n 40 "$STAGE_RESULTS/build.log" >&2
  add_case build "build failed" "$STAGE_RESULTS/build.log"
  write_xml
  exit 1
fi
if ! link_release_clients "${CLIENTS[@]}" 2>"$STAGE_RESULTS/clients.log"; then
  cat "$STAGE_RESULTS/clients.log" >&2
  add_case release_clients "a rostest client is missing" "$STAGE_RESULTS/clients.log"
  write_xml
  exit 1
fi

# Every test catkin registers is run above or skipped on purpose: a new one must be added here.
unlisted="$STAGE_RESULTS/unlisted.txt"
: >"$unlisted"
registered=0
while read -r target; do
  registered=$((registered + 1))
  listed=no
  for name in "${GTESTS[@]}"; do [ "$target" = "gtest_$name" ] && listed=yes; done
  for name in "${ROSTESTS[@]}"; do [ "$target" = "rostest_test_ros_$name.test" ] && listed=yes; done
  for pattern in "${SKIPPED[@]}"; do
    # shellcheck disable=SC2053  # a glob on purpose
    [[ "$target" == $pattern ]] && listed=yes
  done
  [ "$listed" = yes ] || echo "$target" >>"$unlisted"
done < <(make -C "$WS/build" help |
  sed -n 's/^\.\.\. run_tests_impulse2d_\(gtest\|rostest\|roslaunch-check\)_/\1_/p')
[ "$registered" -gt 0 ] || echo "no test targets found in $WS/build" >>"$unlisted"
if [ -s "$unlisted" ]; then
  echo "asan: registered with catkin but neither run nor skipped by $0:" >&2
  cat "$unlisted" >&2
  add_case every_registered_test_listed "not listed" "$unlisted"
else
  add_case every_registered_test_listed
fi

LOGS="$STAGE_RESULTS/sanitizer"
rm -rf "$LOGS" "$STAGE_RESULTS/gtest" "$STAGE_RESULTS/rostest" "$STAGE_RESULTS/roslog"
mkdir -p "$LOGS" "$STAGE_RESULTS/gtest" "$STAGE_RESULTS/rostest" "$STAGE_RESULTS/roslog"
source_side_workspace
# log_path: each process writes its ASan and LeakSanitizer reports to $LOGS/asan.PID; nothing is
# written when there is nothing to report. UBSan ignores log_path next to ASan (GCC 12's
# separate libubsan): its reports go to stderr, which is kept for every process: the gtests' and
# rostests' logs below, and $ROS_LOG_DIR for nodes whose output goes to a log file.
export ASAN_OPTIONS="detect_leaks=1:log_path=$LOGS/asan"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export ROS_LOG_DIR="$STAGE_RESULTS/roslog"
# Debian's nodelet manager is not instrumented: it loads the ASan-built plugin only with the ASan
# runtime preloaded (it must come first in the process's library list).
MANAGER_PREFIX="env LD_PRELOAD=$(gcc -print-file-name=libasan.so)"

run_gtest() {  # run_gtest NAME: runs devel/lib/impulse2d/NAME, leaves its exit code in NAME.rc
  local name="$1" filter="*"
  [ "$name" = impulse2d_unit_tests ] && filter="$UNIT_FILTER"
  "$WS/devel/lib/impulse2d/$name" --gtest_filter="$filter" \
    --gtest_output="xml:$STAGE_RESULTS/gtest/$name.xml" >"$STAGE_RESULTS/gtest/$name.log" 2>&1
  echo $? >"$STAGE_RESULTS/gtest/$name.rc"
}
run_rostest() {  # run_rostest NAME: runs test/ros/NAME.test, leaves its exit code in NAME.rc
  local name="$1" args=()
  case "$name" in *_nodelet) args=("manager_prefix:=$MANAGER_PREFIX") ;; esac
  ROS_TEST_RESULTS_DIR="$STAGE_RESULTS/rostest" rostest impulse2d "$name.test" "${args[@]}" \
    >"$STAGE_RESULTS/rostest/$name.log" 2>&1
  echo $? >"$STAGE_RESULTS/rostest/$name.rc"
}

# The gtests (the unit tests take about a minute, on one core) alongside the rostests, one after
# the other (their nodes step on wall-clock timers; each rostest has its own master).
(for name in "${GTESTS[@]}"; do run_gtest "$name"; done) &
gtests=$!
for name in "${ROSTESTS[@]}"; do run_rostest "$name"; done
wait "$gtests"

for entry in "${GTESTS[@]/#/gtest/}" "${ROSTESTS[@]/#/rostest/}"; do
  rc="$(cat "$STAGE_RESULTS/$entry.rc" 2>/dev/null || echo missing)"
  echo "asan: $entry exit $rc" >&2
  if [ "$rc" = 0 ]; then
    add_case "${entry//\//_}_exit_status"
  else
    tail -n 30 "$STAGE_RESULTS/$entry.log" >&2
    add_case "${entry//\//_}_exit_status" "exit $rc" "$STAGE_RESULTS/$entry.log"
  fi
done

# Reports from any process: ASan's errors and LeakSanitizer's leaks in $LOGS, UBSan's runtime
# errors in the captured output.
report_file="$STAGE_RESULTS/sanitizer_reports.txt"
cat "$LOGS"/* >"$report_file" 2>/dev/null
grep -r -h -E -B1 -A20 ':[0-9]+:[0-9]+: runtime error: ' "$STAGE_RESULTS/gtest" \
  "$STAGE_RESULTS/rostest" "$STAGE_RESULTS/roslog" --include='*.log' >>"$report_file"
reports=$(grep -c -E 'ERROR: (Address|Leak)Sanitizer|: runtime error: ' "$report_file")
if [ "$reports" -eq 0 ] && [ ! -s "$report_file" ]; then
  add_case no_sanitizer_reports
else
  head -n 100 "$report_file" >&2
  add_case no_sanitizer_reports "$reports reports" "$report_file"
fi
write_xml
echo "asan: $reports sanitizer reports; $failures of ${#cases[@]} checks failed" >&2
[ "$failures" -eq 0 ]
