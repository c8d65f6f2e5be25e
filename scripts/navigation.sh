#!/usr/bin/env bash
# Seed 000's high-level controller over the steered walk (docs/tasks.md): trained on walls courses
# redrawn every episode, with its height map (configs/navigation_walls.yaml) and without
# (configs/navigation_walls_blind.yaml), each into runs/ (a run already there is resumed), then
# measured on the same 20 courses (eval --paired: episode k is the same start and walls for each)
# into docs/data/:
#   navigation.json           the HLC with its view of the course
#   navigation_blind.json     the HLC without it
#   navigation_straight.json  a fixed "straight on" command (--fixed-action 0) in its place
#
#   scripts/navigation.sh           train (or resume) both and measure
#   scripts/navigation.sh measure   measure what the runs hold now (a stopped run: its checkpoint)
#
# Needs the steered walk at runs/steer_walk/model (scripts/steering.sh). Each controller takes
# about an hour at one thread; the two run side by side.
set -euo pipefail
cd "$(dirname "$0")/.."
mimic=${MIMIC:-build/src/mimic}
export OPENBLAS_CORETYPE=${OPENBLAS_CORETYPE:-Haswell}
[ -x "$mimic" ] || { echo "navigation.sh: build mimic first (cmake --preset default && cmake --build --preset default)" >&2; exit 1; }
[ -f runs/steer_walk/model/networks.mimic ] || { echo "navigation.sh: the steered walk is not trained yet: run scripts/steering.sh" >&2; exit 1; }

train() {  # config, run (a finished run resumed trains nothing more)
  if [ ! -f "$2/checkpoint.pt" ]; then "$mimic" train "$1" -o "$2"; else "$mimic" train --resume -o "$2"; fi
}
if [ "${1:-}" != measure ]; then
  train configs/navigation_walls.yaml runs/navigation_walls > runs/navigation_walls.log 2>&1 &
  seeing=$!
  train configs/navigation_walls_blind.yaml runs/navigation_walls_blind > runs/navigation_walls_blind.log 2>&1 &
  blind=$!
  wait $seeing || { echo "navigation.sh: training failed; see runs/navigation_walls.log" >&2; exit 1; }
  wait $blind || { echo "navigation.sh: training failed; see runs/navigation_walls_blind.log" >&2; exit 1; }
fi
mkdir -p docs/data
# --paired: episode k is the same course for all three, so they compare course by course.
"$mimic" eval runs/navigation_walls --episodes 20 --paired --json docs/data/navigation.json
"$mimic" eval runs/navigation_walls_blind --episodes 20 --paired --json docs/data/navigation_blind.json
"$mimic" eval runs/navigation_walls --episodes 20 --paired --fixed-action 0 --json docs/data/navigation_straight.json
python3 - <<'PY'
import json
r = {k: json.load(open(f"docs/data/{k}.json"))["returns"] for k in ("navigation", "navigation_blind", "navigation_straight")}
for k in ("navigation", "navigation_blind"):
    wins = sum(a > b for a, b in zip(r[k], r["navigation_straight"]))
    print(f"{k}: further than straight on in {wins} of {len(r[k])} courses")
PY
echo "wrote docs/data/navigation.json, navigation_blind.json and navigation_straight.json"
