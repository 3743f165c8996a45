#!/usr/bin/env bash
# The core soak (test/soak/soak_run.hpp): seeded random edits of a running world through the
# World API (spawn, delete, joints of every type anchored anywhere, teleports, forces, kinematic
# motion, sleep on and off, bad requests), invariants checked after every step, under every
# solver. Runs CORE_SOAK_RUNS seeds (default 50, under a minute) from CORE_SOAK_SEED (default 1),
# then CORE_SOAK_AT_POINTS_RUNS (default 10) of them again with --wrenches-at-points (pushes off
# the centre, as the ROS soak's clients give them): the same seeds on every machine. Longer:
# CORE_SOAK_SECONDS=1800 runs seeds for that much wall time instead (a run is never cut short).
# A failure
# prints the seed, the solver, the violation, the last edits and the command that reproduces it.
# Writes $STAGE_RESULTS/core_soak_N.xml (JUnit, one case per seed and solver) and core_soak_N.log
# for each of its processes (two for CORE_SOAK_RUNS and two for CORE_SOAK_AT_POINTS_RUNS, one
# for CORE_SOAK_SECONDS).
set -uo pipefail
SOAK="$IMPULSE2D_WS/devel/lib/impulse2d/impulse2d_core_soak"
SEED="${CORE_SOAK_SEED:-1}"
# A seeds' run: one soak process, its log, its errors and its JUnit cases in part PART's files.
run_part() {  # run_part PART LIMIT SOAK_ARGS...
  local part="$1" limit="$2"
  shift 2
  timeout "$limit" "$SOAK" "$@" --solver all --junit "$STAGE_RESULTS/core_soak_$part.xml" \
    >"$STAGE_RESULTS/core_soak_$part.log" 2>"$STAGE_RESULTS/core_soak_$part.err"
}
pids=()
parts=()
start_part() {  # start_part PART LIMIT SOAK_ARGS...: run_part in the background
  run_part "$@" &
  pids+=($!)
  parts+=("$1")
}
if [ -n "${CORE_SOAK_SECONDS:-}" ]; then
  echo "core soak: seeds from $SEED for $CORE_SOAK_SECONDS s, every solver" >&2
  start_part 1 $((CORE_SOAK_SECONDS + 600)) --seed "$SEED" --seconds "$CORE_SOAK_SECONDS"
else
  # The seeds in two halves, one process each: each run is one world on one thread, and the
  # halves give the same results as one process (a seed's run depends on its seed alone).
  runs="${CORE_SOAK_RUNS:-50}"
  first=$(((runs + 1) / 2))
  echo "core soak: seeds $SEED-$((SEED + runs - 1)) in two processes, every solver" >&2
  start_part 1 900 --seed "$SEED" --runs "$first"
  if [ "$runs" -gt "$first" ]; then
    start_part 2 900 --seed "$((SEED + first))" --runs "$((runs - first))"
  fi
  at_points="${CORE_SOAK_AT_POINTS_RUNS:-10}"
  if [ "$at_points" -gt 0 ]; then
    half=$(((at_points + 1) / 2))
    echo "core soak: seeds $SEED-$((SEED + at_points - 1)) with wrenches at points" >&2
    start_part 3 900 --seed "$SEED" --runs "$half" --wrenches-at-points
    if [ "$at_points" -gt "$half" ]; then
      start_part 4 900 --seed "$((SEED + half))" --runs "$((at_points - half))" --wrenches-at-points
    fi
  fi
fi
status=0
for i in "${!pids[@]}"; do
  part="${parts[$i]}"
  wait "${pids[$i]}"
  code=$?
  tail -n 1 "$STAGE_RESULTS/core_soak_$part.log" >&2
  if [ "$code" -ne 0 ]; then
    echo "core soak FAILED (part $part, exit $code):" >&2
    grep -v "0 violations" "$STAGE_RESULTS/core_soak_$part.log" | tail -n 5 >&2
    tail -n 40 "$STAGE_RESULTS/core_soak_$part.err" >&2
    status=1
  fi
done
exit "$status"
