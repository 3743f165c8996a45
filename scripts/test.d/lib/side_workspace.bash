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

# link_release_clients PROGRAM...: the rostests' gtest clients come from the release workspace
# ($IMPULSE2D_WS, built by scripts/build.sh and `catkin_make run_tests`), linked into $WS's devel
# space where rostest looks for them. They only call the node's services and read its topics;
# the node under test is the instrumented one, and compiling the clients again took about a
# quarter of a sanitizer build. Only for clients that link none of the package's shared libraries
# (ldd shows none): $WS's library path would load its instrumented ones into them. Fails, naming
# the missing program, when the release one is absent.
link_release_clients() {
  local release="${IMPULSE2D_WS:-/tmp/impulse2d_ws}/devel/lib/impulse2d" program
  mkdir -p "$WS/devel/lib/impulse2d"
  for program in "$@"; do
    if [ ! -x "$release/$program" ]; then
      echo "$release/$program is missing: build the release workspace's tests first" \
        "(scripts/build.sh, then catkin_make -C \$IMPULSE2D_WS tests)" >&2
      return 1
    fi
    ln -sfn "$release/$program" "$WS/devel/lib/impulse2d/$program"
  done
}
