#!/usr/bin/env bash
# libFuzzer harnesses (test/fuzz/fuzz_*.cpp, cmake/fuzz.cmake): builds them in a core-only clang
# build with ASan + UBSan, then runs each for FUZZ_SECONDS (default 20) from its seed corpus
# (test/fuzz/corpus/<name without fuzz_>/) with leak detection on. Any crash, leak, sanitizer
# report, timeout or broken property fails the harness; the input that did it is kept in
# $STAGE_RESULTS and printed in base64. Writes one JUnit test case per harness.
# Bound: build ~3 min on 2 cores, then FUZZ_SECONDS per harness and core (70 s for 3 harnesses
# on 2 cores).
set -uo pipefail
REPO="${REPO:-$(cd "$(dirname "$0")/../.." && pwd)}"
STAGE_RESULTS="${STAGE_RESULTS:-$(mktemp -d)}"
BUILD="${IMPULSE2D_WS:-/tmp}/build_fuzz"
SECONDS_EACH="${FUZZ_SECONDS:-20}"
mkdir -p "$STAGE_RESULTS"
XML="$STAGE_RESULTS/fuzz.xml"

write_xml() {  # write_xml NAME:STATUS... (STATUS ok or the log file of a failure)
  local cases=() failures=0
  for entry in "$@"; do
    local name="${entry%%:*}" status="${entry#*:}"
    if [ "$status" = ok ]; then
      cases+=("  <testcase classname=\"fuzz\" name=\"$name\"/>")
    else
      failures=$((failures + 1))
      cases+=("  <testcase classname=\"fuzz\" name=\"$name\"><failure message=\"see log\"><![CDATA[$(tail -n 40 "$status" | sed 's/]]>/]] >/g')]]></failure></testcase>")
    fi
  done
  {
    echo "<?xml version=\"1.0\" encoding=\"UTF-8\"?>"
    echo "<testsuite name=\"fuzz\" tests=\"$#\" failures=\"$failures\">"
    printf '%s\n' "${cases[@]}"
    echo "</testsuite>"
  } >"$XML"
  [ "$failures" -eq 0 ]
}

if ! { CC=clang CXX=clang++ cmake -S "$REPO" -B "$BUILD" -DIMPULSE2D_CORE_ONLY=ON -DIMPULSE2D_FUZZ=ON \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo >"$STAGE_RESULTS/build.log" 2>&1 &&
  cmake --build "$BUILD" -j"$(nproc)" --target fuzzers >>"$STAGE_RESULTS/build.log" 2>&1; }; then
  tail -n 40 "$STAGE_RESULTS/build.log" >&2
  write_xml "build:$STAGE_RESULTS/build.log"
  exit 1
fi

# One harness per core at a time: the stage takes about ceil(harnesses / cores) * FUZZ_SECONDS.
run_harness() {  # run_harness PATH: runs it, leaves its exit code in $STAGE_RESULTS/NAME.rc
  local harness="$1" name seeds work log
  name="$(basename "$harness")"
  seeds="$REPO/test/fuzz/corpus/${name#fuzz_}"
  [ -d "$seeds" ] || seeds="$REPO/test/fuzz/corpus/$name"
  work="$(mktemp -d)"  # new inputs go here, never into the repository's seed corpus
  log="$STAGE_RESULTS/$name.log"
  local dirs=("$work")
  [ -d "$seeds" ] && dirs+=("$seeds")
  # -timeout: one input taking 10 s is a hang; -rss_limit_mb: growth without bound is a failure.
  ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=0 UBSAN_OPTIONS=print_stacktrace=1 \
    "$harness" -max_total_time="$SECONDS_EACH" -max_len=8192 -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$STAGE_RESULTS/$name-" "${dirs[@]}" >"$log" 2>&1
  echo $? >"$STAGE_RESULTS/$name.rc"
  rm -rf "$work"
}

harnesses=()
for harness in "$BUILD"/fuzz_*; do
  [ -x "$harness" ] && harnesses+=("$harness")
done
running=0
for harness in "${harnesses[@]}"; do
  run_harness "$harness" &
  running=$((running + 1))
  if [ "$running" -ge "$(nproc)" ]; then
    wait -n
    running=$((running - 1))
  fi
done
wait

results=()
for harness in "${harnesses[@]}"; do
  name="$(basename "$harness")"
  log="$STAGE_RESULTS/$name.log"
  rc="$(cat "$STAGE_RESULTS/$name.rc" 2>/dev/null || echo 1)"
  if [ "$rc" -eq 0 ]; then
    echo "fuzz: $name ok ($(grep -o 'Done [0-9]* runs' "$log" | head -n 1))" >&2
    results+=("$name:ok")
  else
    echo "fuzz: $name FAILED (exit $rc); log $log" >&2
    tail -n 30 "$log" >&2
    results+=("$name:$log")
  fi
done
[ ${#results[@]} -gt 0 ] || { echo "fuzz: no harness was built" >&2; exit 1; }
write_xml "${results[@]}"
