#!/usr/bin/env bash
# Builds mimic and runs the whole test suite twice: the release build, then the ASan+UBSan build
# (set MIMIC_SKIP_SANITIZE=1 to skip the second). The sanitizer pass leaves out the long learning
# checks (CTest label `learning`: policies trained until they do a task, the same code the short
# tests run under the sanitizers); MIMIC_SANITIZE_LEARNING=1 runs them there too.
# Run scripts/setup.sh first on a new machine. Where a test fails, the failed tests are run once
# more with their output, at the end of the log (a CI log's tail then shows why, and whether the
# failure repeats); the script still fails.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)

# ctest with the given arguments; on a failure, the failed tests again with their output, then exit 1.
# The last lines say why in short (a CI log may show only its tail), with the disk's free space.
run_ctest() {
  if ! ctest "$@"; then
    echo "== the failed tests again, with their output"
    local rerun=0 log
    log=$(mktemp)
    ctest "$@" --rerun-failed --output-on-failure 2>&1 | tee "$log" || rerun=1
    echo "== why, in short (the rerun $([ "$rerun" = 0 ] && echo passed || echo failed too))"
    grep -m 2 -A 2 -E "CMake Error|Failure|ERROR: |Error:" "$log" | cut -c1-240 || true
    echo "disk: $(df -h . | tail -1)"
    exit 1
  fi
}

echo "== release build (build/)"
cmake --preset default >/dev/null
cmake --build --preset default -j "$jobs"
run_ctest --preset default -j "$jobs"

if [ "${MIMIC_SKIP_SANITIZE:-0}" != "1" ]; then
  echo "== ASan + UBSan build (build-asan/)"
  cmake --preset asan >/dev/null
  cmake --build --preset asan -j "$jobs"
  skip_learning=(-LE learning)
  [ "${MIMIC_SANITIZE_LEARNING:-0}" = "1" ] && skip_learning=()
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    run_ctest --preset asan -j "$jobs" "${skip_learning[@]}"
fi
