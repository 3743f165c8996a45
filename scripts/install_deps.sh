#!/usr/bin/env bash
# Installs the Debian 12 packages impulse2d needs to build, run and test (skips what is there).
set -euo pipefail
PACKAGES=(
  build-essential cmake clang-format
  catkin python3-catkin-pkg ros-core-dev python3-rostest python3-rosunit
  libeigen3-dev libhwy-dev libtbb-dev libyaml-cpp-dev libgtest-dev googletest
  libnodeletlib-dev libnodeletlib-tools pluginlib-dev libtf2-ros-dev libtf2-msgs-dev
  libdiagnostic-updater-dev libdiagnostic-msgs-dev libstd-msgs-dev libstd-srvs-dev
  libgeometry-msgs-dev libsensor-msgs-dev libvisualization-msgs-dev libros-rosgraph-msgs-dev
  ros-message-generation python3-roslaunch rosbash
)
# Further lists, one per feature: scripts/deps/*.txt, a package per line, # starts a comment.
for list in "$(dirname "$0")"/deps/*.txt; do
  [ -e "$list" ] || continue
  while read -r p _; do
    case "$p" in "" | "#"*) ;; *) PACKAGES+=("$p") ;; esac
  done <"$list"
done
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then exit 0; fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "impulse2d: installing ${missing[*]}" >&2
$SUDO apt-get update -q
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
