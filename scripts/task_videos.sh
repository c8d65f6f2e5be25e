#!/usr/bin/env bash
# The videos of docs/tasks.md, each a headless `mimic play` session filmed into docs/videos/:
#   steer_walk.mp4   the steered walk (runs/steer_walk/model, scripts/steering.sh) commanded by the
#                    arrow keys: 90 degrees left, then right twice, then left again
#   navigation.mp4   the high-level controller (runs/navigation_walls, scripts/navigation.sh)
#                    driving the steered walk on four walls courses (a reset, r, every 10 s)
#   stairs_0.02.mp4, stairs_0.10.mp4
#                    the stairs fine-tune (runs/stairs_walk, scripts/stairs.sh) walking along a
#                    staircase of 0.02 m steps and of 0.10 m ones (seed 000's)
# A run stopped before its end is filmed from its last checkpoint (its networks exported first).
#
#   scripts/task_videos.sh [steer_walk|navigation|stairs]...   (default: all three)
set -euo pipefail
cd "$(dirname "$0")/.."
mimic=${MIMIC:-build/src/mimic}
export OPENBLAS_CORETYPE=${OPENBLAS_CORETYPE:-Haswell}
[ -x "$mimic" ] || { echo "task_videos.sh: build mimic first (cmake --preset default && cmake --build --preset default)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p docs/videos

# The model of a run: its exported one, or the run itself with its last checkpoint's networks
# written beside its config (mimic export --networks-only).
model_of() {
  if [ -f "$1/model/networks.mimic" ]; then echo "$1/model"; return; fi
  [ -f "$1/checkpoint.pt" ] || { echo "task_videos.sh: $1 has no checkpoint: train it first" >&2; exit 1; }
  "$mimic" export "$1" -o "$1" --networks-only >&2
  echo "$1"
}

steer_walk() {
  printf '%s\n' "# 90 degrees left, 180 right, 90 left (30 degrees a press)" \
    "2.0 left" "2.2 left" "2.4 left" "6.0 right" "6.2 right" "6.4 right" "6.6 right" "6.8 right" "7.0 right" \
    "11.0 left" "11.2 left" "11.4 left" > "$tmp/steer.script"
  "$mimic" play "$(model_of runs/steer_walk)" --headless --script "$tmp/steer.script" --seconds 15 \
    -o docs/videos/steer_walk.mp4 --json "$tmp/steer.json"
}

navigation() {  # a new course every 10 s (r), whether or not the walk is down by then
  printf '%s\n' "10.0 r" "20.0 r" "30.0 r" > "$tmp/navigation.script"
  "$mimic" play "$(model_of runs/navigation_walls)" --headless --script "$tmp/navigation.script" --seconds 40 \
    -o docs/videos/navigation.mp4 --json "$tmp/navigation.json"
}

stairs() {  # mimic render films a run (its last checkpoint) or a model
  for h in 0.02 0.10; do
    "$mimic" render runs/stairs_walk --set "env.terrain={kind: stairs, step_height: $h}" --seconds 12 -o "docs/videos/stairs_$h.mp4"
  done
}

for what in "${@:-steer_walk navigation stairs}"; do
  for w in $what; do "$w"; done
done
