#!/usr/bin/env bash
# One command from a fresh machine to the demo: installs what is missing, builds, runs the
# 210-box pyramid headless for 10 simulated seconds and prints where the trajectory CSV went.
set -euo pipefail
REPO="$(cd "$(dirname "$0")/.." && pwd)"
"$REPO/scripts/install_deps.sh"
WS="$("$REPO/scripts/build.sh")"
OUT="${TMPDIR:-/tmp}/impulse2d_pyramid.csv"
"$WS/devel/lib/impulse2d/impulse2d_sim" "$REPO/config/pyramid.yaml" --duration 10 --csv "$OUT" \
  --every 100 --hash
echo "trajectory: $OUT"
