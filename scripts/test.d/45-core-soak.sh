#!/usr/bin/env bash
# The core soak (test/soak/soak_run.hpp): seeded random edits of a running world through the
# World API (spawn, delete, joints of every type anchored anywhere, teleports, forces, kinematic
# motion, sleep on and off, bad requests), invariants checked after every step, under every
# solver. Runs CORE_SOAK_RUNS seeds (default 50, under a minute) from CORE_SOAK_SEED (default 1):
# the same seeds on every machine. Longer: CORE_SOAK_SECONDS=1800 runs seeds for that much wall
# time instead (a run is never cut short). A failure
# prints the seed, the solver, the violation, the last edits and the command that reproduces it.
# Writes $STAGE_RESULTS/core_soak.xml (JUnit, one case per seed and solver).
set -uo pipefail
SOAK="$IMPULSE2D_WS/devel/lib/impulse2d/impulse2d_core_soak"
SEED="${CORE_SOAK_SEED:-1}"
LOG="$STAGE_RESULTS/core_soak.log"
if [ -n "${CORE_SOAK_SECONDS:-}" ]; then
  bound=(--seconds "$CORE_SOAK_SECONDS")
  limit=$((CORE_SOAK_SECONDS + 600))
else
  bound=(--runs "${CORE_SOAK_RUNS:-50}")
  limit=900
fi
echo "core soak: seeds from $SEED, ${bound[*]}, every solver" >&2
timeout "$limit" "$SOAK" --seed "$SEED" "${bound[@]}" --solver all \
  --junit "$STAGE_RESULTS/core_soak.xml" >"$LOG" 2>"$STAGE_RESULTS/core_soak.err"
status=$?
tail -n 1 "$LOG" >&2
if [ "$status" -ne 0 ]; then
  echo "core soak FAILED (exit $status):" >&2
  grep -v "0 violations" "$LOG" | tail -n 5 >&2
  tail -n 40 "$STAGE_RESULTS/core_soak.err" >&2
fi
exit "$status"
