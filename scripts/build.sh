#!/usr/bin/env bash
# Builds impulse2d in a catkin workspace outside the repository (default ~/.cache/impulse2d_ws,
# or $IMPULSE2D_WS) whose src/ links to this checkout. --clean starts from an empty workspace.
set -euo pipefail
REPO="$(cd "$(dirname "$0")/.." && pwd)"
WS="${IMPULSE2D_WS:-${XDG_CACHE_HOME:-$HOME/.cache}/impulse2d_ws}"
# Debian's catkin needs Debian's python3 (another python3 may come first on PATH).
export PATH="/usr/bin:$PATH"
if [ "${1:-}" = "--clean" ]; then rm -rf "$WS"; fi
mkdir -p "$WS/src"
ln -sfn "$REPO" "$WS/src/impulse2d"
cd "$WS"
catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release -j"$(nproc)" >&2
echo "$WS"
