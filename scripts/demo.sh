#!/usr/bin/env bash
# Builds mimic (release) and runs its showcase: `mimic demo -o out/demo`. Extra arguments go to
# `mimic demo`. Run scripts/setup.sh first on a new machine.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset default >/dev/null
cmake --build --preset default -j "$(nproc)" --target mimic
./build/src/mimic demo "$@"
