#!/usr/bin/env bash
# Seed 003 Table 2 at a reduced budget: the walk tracked from fixed (FSI), reference (RSI) and
# adaptive (ASI, k = 10) initial states, same config and seed otherwise; then `mimic eval` of each.
# Usage: scripts/tracking_init.sh [iterations (default 250: 1.02 M samples)] [out dir (runs/tracking_init)]
set -euo pipefail
iterations=${1:-250}
out=${2:-runs/tracking_init}
mimic=${MIMIC:-build/src/mimic}
config=configs/humanoid_walk_tracking.yaml
mkdir -p "$out"
common=(--set iterations="$iterations" --set collect.threads=1)
"$mimic" train "$config" -o "$out/fsi" "${common[@]}" --set env.init=fixed > "$out/fsi.log" 2>&1 &
"$mimic" train "$config" -o "$out/rsi" "${common[@]}" > "$out/rsi.log" 2>&1 &
"$mimic" train "$config" -o "$out/asi" "${common[@]}" --set "init={kind: adaptive, components: 10, episodes: 500}" > "$out/asi.log" 2>&1 &
wait
for run in fsi rsi asi; do
  "$mimic" eval "$out/$run" --episodes 10 --trials 20 --json "$out/$run.json"
done
