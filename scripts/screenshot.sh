#!/usr/bin/env bash
# RViz end to end: saves a PNG of what a user sees.
#   scripts/screenshot.sh OUT.png [SCENE.yaml] [--plane xz|xy] [--settle SECONDS]
#   scripts/screenshot.sh OUT.png --launch robot_demo.launch [--cmd-vel 'V W'] [--settle SECONDS]
# Starts its own ROS master on a free port, `roslaunch impulse2d demo.launch` (the node on SCENE
# and RViz with the package's config for the plane) on a virtual X screen (xvfb-run), waits until
# the world has stepped SECONDS of simulated time (default 3) and RViz has drawn coloured markers,
# then saves the screen with ImageMagick's `import -window root`. Everything it started is stopped
# on exit, also on failure or Ctrl-C. Uses the workspace built by scripts/build.sh
# ($IMPULSE2D_WS, default ~/.cache/impulse2d_ws). SCENE defaults to config/demo.yaml (xz) or
# config/topdown.yaml (xy); without --plane the scene's own world.plane is used. --launch runs
# another launch file of the package instead (with its own scene and RViz config); --cmd-vel
# publishes linear.x V (m/s) and angular.z W (rad/s) on /impulse2d/cmd_vel at 10 Hz from when the
# world steps until the picture is taken (the robot demo drives its robot).
# Exit status: 0 with the PNG written, 1 with one "screenshot.sh: ..." line saying what failed.
set -euo pipefail
REPO="$(cd "$(dirname "$0")/.." && pwd)"
WS="${IMPULSE2D_WS:-${XDG_CACHE_HOME:-$HOME/.cache}/impulse2d_ws}"
export PATH="/usr/bin:$PATH"  # Debian's python3 for the ROS tools
SCREEN_WIDTH=1280             # the RViz configs' window size
SCREEN_HEIGHT=800
# What fills the 3D view where nothing is drawn, to find the view in the picture: the configs'
# background, or a map's free cells (RViz's Map display, rgb 192 grey) where a map covers it.
VIEW_BACKGROUNDS=("rgb(48,48,48)" "rgb(192,192,192)")
STARTUP_TIMEOUT=40            # s, for each of: master, X screen, stepping, RViz subscribing, drawing

die() {
  echo "screenshot.sh: $*" >&2
  exit 1
}
usage() { sed -n '2,4p' "$0" | sed 's/^# *//' >&2; exit 2; }

out="" scene="" plane="" settle=3 launch="" cmd_vel=""
while [ $# -gt 0 ]; do
  case "$1" in
    --plane) [ $# -ge 2 ] || usage; plane="$2"; shift 2 ;;
    --launch) [ $# -ge 2 ] || usage; launch="$2"; shift 2 ;;
    --cmd-vel) [ $# -ge 2 ] || usage; cmd_vel="$2"; shift 2 ;;
    --settle) [ $# -ge 2 ] || usage; settle="$2"; shift 2 ;;
    -h | --help) usage ;;
    -*) echo "screenshot.sh: unknown option $1" >&2; usage ;;
    *) if [ -z "$out" ]; then out="$1"; elif [ -z "$scene" ]; then scene="$1"; else usage; fi; shift ;;
  esac
done
[ -n "$out" ] || usage
case "$out" in *.png) ;; *) die "OUT must end in .png: $out" ;; esac
case "$plane" in "" | xz | xy) ;; *) die "--plane must be xz or xy, not '$plane'" ;; esac
[[ "$settle" =~ ^[0-9]+([.][0-9]+)?$ ]] || die "--settle must be a number of seconds, not '$settle'"
number='-?[0-9]+([.][0-9]+)?'
[ -z "$cmd_vel" ] || [[ "$cmd_vel" =~ ^$number\ $number$ ]] ||
  die "--cmd-vel must be two numbers 'V W', not '$cmd_vel'"
[ -z "$launch" ] || [ -z "$scene$plane" ] || die "--launch takes no SCENE or --plane (the launch file has its own)"
case "$launch" in "" | *.launch) ;; *) die "--launch must name a .launch file of the package, not '$launch'" ;; esac

for tool in xvfb-run xauth import convert rviz roscore roslaunch rostopic; do
  command -v "$tool" >/dev/null ||
    die "'$tool' is missing: install the packages in scripts/deps/rviz.txt (scripts/install_deps.sh)"
done
[ -f "$WS/devel/setup.bash" ] && [ -x "$WS/devel/lib/impulse2d/impulse2d_node" ] ||
  die "no built workspace at $WS: run scripts/build.sh first (or set IMPULSE2D_WS)"
# The workspace first: a scene's package:// paths (maps) resolve through it.
set +u  # catkin's setup script reads unset variables
# shellcheck disable=SC1091
source "$WS/devel/setup.bash"
set -u

# The scene's plane and frame_id decide the RViz config and its fixed frame.
if [ -n "$launch" ]; then
  [ -f "$REPO/launch/$launch" ] || die "no launch file launch/$launch"
else
  if [ -z "$scene" ]; then
    if [ "$plane" = xy ]; then scene="$REPO/config/topdown.yaml"; else scene="$REPO/config/demo.yaml"; fi
  fi
  [ -f "$scene" ] || die "no scene file $scene"
  scene="$(cd "$(dirname "$scene")" && pwd)/$(basename "$scene")"
  # A scene the node would refuse would only show an empty grid: say why instead.
  sim_error="$("$WS/devel/lib/impulse2d/impulse2d_sim" "$scene" --steps 1 2>&1 >/dev/null)" ||
    die "the scene is refused: ${sim_error#impulse2d_sim: }"
  read -r scene_plane frame_id < <(python3 - "$scene" 2>/dev/null <<'PY' || echo "? ?"
import sys, yaml
world = (yaml.safe_load(open(sys.argv[1])) or {}).get("world") or {}
print(world.get("plane", "xz"), world.get("frame_id", "world"))
PY
  )
  [ "$scene_plane" != "?" ] || die "cannot read $scene as YAML"
  plane="${plane:-$scene_plane}"
  case "$plane" in xz | xy) ;; *) die "$scene: world.plane must be xz or xy, not '$plane'" ;; esac
fi

tmp="$(mktemp -d "${TMPDIR:-/tmp}/impulse2d_screenshot.XXXXXX")"
started=()  # pids of what we started, stopped in reverse order
descendants() {  # every process below $1, depth first
  local child
  for child in $(ps -o pid= --ppid "$1" 2>/dev/null); do
    echo "$child"
    descendants "$child"
  done
}
xvfb_run_pid=""
stop() {
  # roslaunch (and roscore) get SIGINT, which makes them stop their nodes, which they keep in
  # sessions of their own. xvfb-run's command (the sleep) is killed, again until it is there in
  # case xvfb-run was still starting, so that xvfb-run ends normally: it stops Xvfb and removes
  # its cookie file (its own clean-up commands must not be signalled). Whatever is left after
  # 10 s is killed.
  local pid="$1" i child
  [ "$pid" = "$xvfb_run_pid" ] || kill -INT "$pid" 2>/dev/null
  for i in $(seq 50); do
    kill -0 "$pid" 2>/dev/null || break
    if [ "$pid" = "$xvfb_run_pid" ]; then
      for child in $(ps -o pid= -o comm= --ppid "$pid" | awk '$2 == "sleep" { print $1 }'); do
        kill -KILL "$child" 2>/dev/null
      done
    fi
    sleep 0.2
  done
  for child in "$pid" $(descendants "$pid"); do kill -KILL "$child" 2>/dev/null; done
  wait "$pid" 2>/dev/null || true
}
cleanup() {
  set +e  # a process that is already gone must not end the clean-up half way
  local i
  for ((i = ${#started[@]} - 1; i >= 0; i--)); do stop "${started[i]}"; done
  rm -rf "$tmp"
}
trap cleanup EXIT
trap 'exit 130' INT TERM HUP

log_tail() { [ -f "$1" ] && tail -n 15 "$1" | sed 's/^/    /' >&2 || true; }

# wait_for DESCRIPTION LOG COMMAND...: polls COMMAND every 0.5 s until it succeeds, failing after
# STARTUP_TIMEOUT seconds or as soon as one of the processes we started has died.
wait_for() {
  local what="$1" log="$2" deadline=$((SECONDS + STARTUP_TIMEOUT)) pid
  shift 2
  until "$@" >/dev/null 2>&1; do
    for pid in "${started[@]}"; do
      kill -0 "$pid" 2>/dev/null || { log_tail "$log"; die "$what: a process ended early (log above)"; }
    done
    [ "$SECONDS" -lt "$deadline" ] || { log_tail "$log"; die "$what: timed out after ${STARTUP_TIMEOUT} s"; }
    sleep 0.5
  done
}

# A master of our own on a free port; logs stay in $tmp.
port="$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')"
export ROS_MASTER_URI="http://127.0.0.1:$port" ROS_IP=127.0.0.1 ROS_HOME="$tmp/ros" ROS_LOG_DIR="$tmp/log"
export XDG_RUNTIME_DIR="$tmp/xdg"  # RViz (Qt) would otherwise leave /tmp/runtime-$USER behind
mkdir -m 700 "$XDG_RUNTIME_DIR"
unset ROS_HOSTNAME
roscore -p "$port" >"$tmp/roscore.log" 2>&1 &
started+=($!)
wait_for "ROS master on port $port" "$tmp/roscore.log" rosparam get /run_id

# A virtual screen; xvfb-run stays up as long as the sleep it runs, and ending that sleep lets
# xvfb-run stop Xvfb and remove its cookie file. xvfb-run (a POSIX shell script) would die of a
# signal sent to our whole process group (Ctrl-C, `timeout`) without removing it, so it and its
# sleep ignore them; stop() kills the sleep.
(trap '' INT TERM HUP; exec xvfb-run -a -s "-screen 0 ${SCREEN_WIDTH}x${SCREEN_HEIGHT}x24 -nolisten tcp" \
  bash -c 'echo "$DISPLAY $XAUTHORITY" >"$1.part" && mv "$1.part" "$1" && exec sleep 100000' \
  _ "$tmp/display" >"$tmp/xvfb.log" 2>&1) &
xvfb_run_pid=$!
started+=("$xvfb_run_pid")
wait_for "virtual X screen" "$tmp/xvfb.log" test -s "$tmp/display"
read -r DISPLAY XAUTHORITY <"$tmp/display"
export DISPLAY XAUTHORITY

launch_log="$tmp/launch.log"
if [ -n "$launch" ]; then
  roslaunch impulse2d "$launch" >"$launch_log" 2>&1 &
else
  roslaunch impulse2d demo.launch scene:="$scene" plane:="$plane" fixed_frame:="$frame_id" \
    >"$launch_log" 2>&1 &
fi
started+=($!)

simulated_time() {  # the node's "simulated time (s)" from /diagnostics
  timeout 10 rostopic echo -n 1 /diagnostics 2>/dev/null |
    awk '/key: "simulated time \(s\)"/ { getline; gsub(/[^0-9.e+-]/, "", $2); print $2; exit }'
}
has_stepped() { python3 -c 'import sys; sys.exit(float(sys.argv[1] or 0) < float(sys.argv[2]))' "$(simulated_time)" "$settle"; }
if [ -n "$cmd_vel" ]; then
  read -r linear angular <<<"$cmd_vel"
  steps_at_all() { python3 -c 'import sys; sys.exit(not float(sys.argv[1] or 0) > 0)' "$(simulated_time)"; }
  wait_for "the world stepping" "$launch_log" steps_at_all
  rostopic pub -r 10 /impulse2d/cmd_vel geometry_msgs/Twist \
    "{linear: {x: $linear}, angular: {z: $angular}}" >"$tmp/cmd_vel.log" 2>&1 &
  started+=($!)
fi
wait_for "the world stepping ${settle} s of simulated time" "$launch_log" has_stepped
rviz_listens() { rostopic info /impulse2d/markers | grep -q '^ \* /rviz'; }
wait_for "RViz subscribing to /impulse2d/markers" "$launch_log" rviz_listens

# Drawn: the 3D view (the pixels of its background colour) shows coloured pixels (greys are the
# grid and static bodies; any moving, sleeping or touching body is coloured).
shot="$tmp/shot.png"
view_geometry() {  # WxH+X+Y of the 3D view in $1: the columns and rows mostly of its background
  local background mask x0 x1 y0 y1
  for background in "${VIEW_BACKGROUNDS[@]}"; do
    mask=(convert "$1" -fill black +opaque "$background" -fill white -opaque "$background")
    read -r x0 x1 < <("${mask[@]}" -scale "${SCREEN_WIDTH}x1!" -threshold 50% txt:- |
      awk -F'[,:]' '/#FFFFFF/ { if (first == "") first = $1; last = $1 } END { print first, last }')
    read -r y0 y1 < <("${mask[@]}" -scale "1x${SCREEN_HEIGHT}!" -threshold 25% txt:- |
      awk -F'[,:]' '/#FFFFFF/ { if (first == "") first = $2; last = $2 } END { print first, last }')
    if [ -n "$x0" ] && [ -n "$y0" ]; then
      echo "$((x1 - x0 + 1))x$((y1 - y0 + 1))+$x0+$y0"
      return 0
    fi
  done
  return 1
}
coloured_pixels() {  # pixels of saturation > 40% in the 3D view of $1
  local view
  view="$(view_geometry "$1")" || { echo 0; return; }
  convert "$1" -crop "$view" +repage -colorspace HSL -channel G -separate +channel \
    -threshold 40% -format '%[fx:round(mean*w*h)]' info:
}
drawn() {
  import -window root "$shot" && [ "$(coloured_pixels "$shot")" -ge 50 ]
}
wait_for "RViz drawing the markers" "$launch_log" drawn
sleep 1  # one more frame, so that nothing is half drawn
import -window root "$shot" || die "import could not capture the screen"
mkdir -p "$(dirname "$out")"
cp "$shot" "$out"
what="${launch:+launch $launch}"
echo "screenshot: $out (${SCREEN_WIDTH}x${SCREEN_HEIGHT}, ${what:-plane $plane, scene $scene}, 3D view $(view_geometry "$out"))"
