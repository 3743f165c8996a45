#!/usr/bin/env bash
# The README and the tutorials (docs/tutorial_*.md) as written: scripts/run_examples.py runs their
# shell blocks in order with the stock clients, each document in a shell of its own whose world
# lines (roslaunch, scripts/demo.sh) start on ROS masters of their own (free ports, never another
# roscore of this machine), waits until each world answers, checks every command's output against
# the document (scripts/doc_examples/checks.py), and stops everything it started, also on failure.
# Blocks marked `<!-- ci: not run: REASON -->` are listed with their reason, not run. Before that,
# test/examples/: the runner's unit tests, and docs/ros_api.md against the code (every message
# and service definition verbatim, every launch argument, every advertised service). JUnit: one
# test case per command (examples_<document>.xml) and per unit test. Every command's output is
# kept in $STAGE_RESULTS/logs.
# Bound: 20 minutes (a world may take 5 to come up, a command 3); typically 1.5 to 3 minutes.
set -uo pipefail
REPO="${REPO:-$(cd "$(dirname "$0")/../.." && pwd)}"
export PATH="/usr/bin:$PATH"
results="${STAGE_RESULTS:-$(mktemp -d)}"
mkdir -p "$results"
status=0
python3 "$REPO/test/examples/test_doc_examples.py" --junit "$results/doc_examples_unit.xml" || status=1
python3 "$REPO/test/examples/test_docs_match_code.py" --junit "$results/docs_match_code.xml" || status=1
# SIGTERM from the timeout lets the runner stop what it started before it exits.
timeout -k 60 1200 python3 "$REPO/scripts/run_examples.py" --junit "$results" \
  --log-dir "$results/logs" || status=1
exit "$status"
