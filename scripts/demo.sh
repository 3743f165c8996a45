#!/usr/bin/env bash
# One command from a fresh machine to the demo: installs what is missing, builds, then runs
# `roslaunch impulse2d demo.launch` (the node on config/demo.yaml, with RViz when there is a
# display; extra arguments go to roslaunch, e.g. rviz:=false). --headless instead runs the
# 210-box pyramid with impulse2d_sim for 10 simulated seconds, without ROS.
set -euo pipefail
REPO="$(cd "$(dirname "$0")/.." && pwd)"
"$REPO/scripts/install_deps.sh"
WS="$("$REPO/scripts/build.sh")"
if [ "${1:-}" = "--headless" ]; then
  OUT="${TMPDIR:-/tmp}/impulse2d_pyramid.csv"
  "$WS/devel/lib/impulse2d/impulse2d_sim" "$REPO/config/pyramid.yaml" --duration 10 \
    --csv "$OUT" --every 100 --hash
  echo "trajectory: $OUT"
  exit 0
fi
rviz_arg="rviz:=false"
case " $* " in *" rviz:="*) rviz_arg="" ;; esac  # the caller chose
if [ -n "$rviz_arg" ] && [ -n "${DISPLAY:-}" ]; then
  if ! command -v rviz >/dev/null; then
    SUDO=""
    [ "$(id -u)" -eq 0 ] || SUDO="sudo"
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends rviz
  fi
  rviz_arg="rviz:=true"
fi
export PATH="/usr/bin:$PATH"
set +u  # catkin's setup script reads unset variables
# shellcheck disable=SC1091
source "$WS/devel/setup.bash"
set -u
exec roslaunch impulse2d demo.launch ${rviz_arg:+"$rviz_arg"} "$@"
