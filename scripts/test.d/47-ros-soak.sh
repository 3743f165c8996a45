#!/usr/bin/env bash
# The ROS soak (test/soak/ros_soak.py): four client processes call every service of the world at
# random, against impulse2d_node stepping at ~rate 0 and then against impulse2d/WorldNodelet in a
# manager, each on a ROS master of its own (ports 11471 and 11472), with ~reset and ~load_scene
# mid-run. ROS_SOAK_SECONDS per mode (default 20), seed ROS_SOAK_SEED (default 1). Checks: every
# call answered within 1 s, bad requests refused, no body removed, every body held present and
# each dynamic one inside the arena, RSS bounded, the world alive at the end, topics flowing.
# Writes $STAGE_RESULTS/ros_soak.xml.
# Bound: about 2 x (ROS_SOAK_SECONDS + 20) s.
set -uo pipefail
REPO="${REPO:-$(cd "$(dirname "$0")/../.." && pwd)}"
export PATH="/usr/bin:$PATH"
set +u
# shellcheck disable=SC1091
source "$IMPULSE2D_WS/devel/setup.bash"
set -u
SECONDS_EACH="${ROS_SOAK_SECONDS:-20}"
timeout -k 30 $((4 * SECONDS_EACH + 300)) python3 "$REPO/test/soak/ros_soak.py" \
  --seconds "$SECONDS_EACH" --seed "${ROS_SOAK_SEED:-1}" --junit "$STAGE_RESULTS/ros_soak.xml"
