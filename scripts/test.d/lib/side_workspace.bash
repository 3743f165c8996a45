# Sourced by the stages that build the package once more in a catkin workspace of their own
# (35-asan.sh, 40-tsan.sh), so that their instrumented build never touches the release one.
# Needs REPO set.

# side_workspace SUFFIX: sets WS to $IMPULSE2D_WS-SUFFIX, with this checkout linked into its src/.
side_workspace() {
  WS="${IMPULSE2D_WS:-/tmp/impulse2d_ws}-$1"
  mkdir -p "$WS/src"
  ln -sfn "$REPO" "$WS/src/impulse2d"
}

# source_side_workspace: puts $WS's devel space into the environment (-u is off meanwhile: ROS's
# setup scripts read unset variables).
source_side_workspace() {
  set +u
  # shellcheck disable=SC1091
  source "$WS/devel/setup.bash"
  set -u
}
