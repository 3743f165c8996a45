#!/usr/bin/env bash
# ThreadSanitizer on the node: builds impulse2d_node with -fsanitize=thread in a separate catkin
# workspace ($IMPULSE2D_WS-tsan), then, with the release workspace's world and robot rostest
# clients (link_release_clients in lib/side_workspace.bash), runs the concurrent service tests
# (test/ros/tsan.test) and the robot tests (test/ros/tsan_robot.test) against it. Any
# ThreadSanitizer report from the node fails the stage; test/ros/tsan.supp lists the
# uninstrumented ROS libraries whose internal synchronisation TSan cannot see. Writes rostest's
# JUnit XML and one case for the reports.
# Bound: build ~3 min on 2 cores (node and its libraries; -O1 -g1, two thirds of the compile time
# of RelWithDebInfo's -O2 -g, and line tables are all reports need), run ~1 min.
set -uo pipefail
REPO="${REPO:-$(cd "$(dirname "$0")/../.." && pwd)}"
STAGE_RESULTS="${STAGE_RESULTS:-$(mktemp -d)}"
export PATH="/usr/bin:$PATH"
# shellcheck source=lib/side_workspace.bash
source "$REPO/scripts/test.d/lib/side_workspace.bash"
side_workspace tsan
mkdir -p "$STAGE_RESULTS"
if ! (cd "$WS" && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DIMPULSE2D_TSAN=ON \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
    -j"$(nproc)" impulse2d_node >"$STAGE_RESULTS/build.log" 2>&1); then
  tail -n 40 "$STAGE_RESULTS/build.log" >&2
  exit 1
fi
link_release_clients impulse2d_world_tests impulse2d_robot_tests || exit 1
rm -f "$STAGE_RESULTS"/tsan.*
source_side_workspace
export TSAN_OPTIONS="suppressions=$REPO/test/ros/tsan.supp log_path=$STAGE_RESULTS/tsan second_deadlock_stack=1"
ROS_TEST_RESULTS_DIR="$STAGE_RESULTS/rostest" rostest impulse2d tsan.test >"$STAGE_RESULTS/rostest.log" 2>&1
rc=$?
# The robot tests: cmd_vel callbacks, devices' topics opened and closed by ~load_scene,
# ~delete_body and ~reset while the world steps and publishes.
ROS_TEST_RESULTS_DIR="$STAGE_RESULTS/rostest" rostest impulse2d tsan_robot.test \
  >"$STAGE_RESULTS/rostest_robot.log" 2>&1
robot_rc=$?
[ "$rc" -ne 0 ] || rc=$robot_rc
reports=$(cat "$STAGE_RESULTS"/tsan.* 2>/dev/null | grep -c "WARNING: ThreadSanitizer")
{
  echo '<?xml version="1.0" encoding="UTF-8"?>'
  echo '<testsuite name="tsan" tests="1" failures="'"$([ "$reports" -eq 0 ] && echo 0 || echo 1)"'">'
  if [ "$reports" -eq 0 ]; then
    echo '  <testcase classname="tsan" name="no_thread_sanitizer_reports"/>'
  else
    echo '  <testcase classname="tsan" name="no_thread_sanitizer_reports"><failure message="'"$reports"' reports"><![CDATA['
    cat "$STAGE_RESULTS"/tsan.* | head -n 200 | sed 's/]]>/]] >/g'
    echo ']]></failure></testcase>'
  fi
  echo '</testsuite>'
} >"$STAGE_RESULTS/tsan.xml"
echo "tsan: rostest exit $rc, $reports ThreadSanitizer reports" >&2
[ "$rc" -eq 0 ] && [ "$reports" -eq 0 ]
