#!/usr/bin/env bash
# Builds mimic and runs the whole test suite twice: the release build, then the ASan+UBSan build
# (set MIMIC_SKIP_SANITIZE=1 to skip the second). The sanitizer pass leaves out the long learning
# checks (CTest label `learning`: policies trained until they do a task, the same code the short
# tests run under the sanitizers); MIMIC_SANITIZE_LEARNING=1 runs them there too.
# Run scripts/setup.sh first on a new machine.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)

echo "== release build (build/)"
cmake --preset default >/dev/null
cmake --build --preset default -j "$jobs"
ctest --preset default -j "$jobs"

if [ "${MIMIC_SKIP_SANITIZE:-0}" != "1" ]; then
  echo "== ASan + UBSan build (build-asan/)"
  cmake --preset asan >/dev/null
  cmake --build --preset asan -j "$jobs"
  skip_learning=(-LE learning)
  [ "${MIMIC_SANITIZE_LEARNING:-0}" = "1" ] && skip_learning=()
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --preset asan -j "$jobs" "${skip_learning[@]}"
fi
