#!/usr/bin/env bash
# The steered walk of docs/tasks.md: trained from the shipped walk by `mimic imitate --task
# heading` (10^7 samples, into runs/steer_walk; a run already there is resumed), then measured
# into docs/data/:
#   steering.json        the response to commanded turns of 45 and 90 degrees, 20 trials each
#   steering_style.json  the imitation error of its walk with the targets held straight on
#   steering_plain.json  the shipped walk's by the same protocol (the style target: within 25 %)
#
#   scripts/steering.sh           train (or resume) and measure
#   scripts/steering.sh measure   measure what runs/steer_walk holds now (its model, or the run's
#                                 last checkpoint where it was stopped before the end)
#
# The training takes about 1.5 h on 2 cores beside nothing else; the measurements a few minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
data=${MIMIC_DATA:-../shared/data}
mimic=${MIMIC:-build/src/mimic}
run=runs/steer_walk
walk=$data/deepmimic/motions/humanoid3d_walk.txt
export OPENBLAS_CORETYPE=${OPENBLAS_CORETYPE:-Haswell}
[ -x "$mimic" ] || { echo "steering.sh: build mimic first (cmake --preset default && cmake --build --preset default)" >&2; exit 1; }
[ -f "$walk" ] || { echo "steering.sh: the shared data is not at $data (set MIMIC_DATA)" >&2; exit 1; }

if [ "${1:-}" != measure ]; then
  if [ ! -f "$run/config.yaml" ]; then
    "$mimic" imitate "$walk" --task heading --from models/humanoid_walk_iccgan -o "$run" --samples 10000000
  elif [ ! -f "$run/model/networks.mimic" ]; then
    "$mimic" imitate --resume -o "$run"
  fi
fi
skill=$run/model
[ -f "$skill/networks.mimic" ] || skill=$run
mkdir -p docs/data
"$mimic" eval "$skill" --episodes 1 --trials 1 --steering 45,90 --steering-trials 20 --json docs/data/steering.json
"$mimic" eval "$skill" --episodes 1 --trials 20 --clip "$walk" --set env.goal_turn=0 --json docs/data/steering_style.json
"$mimic" eval models/humanoid_walk_iccgan --episodes 1 --trials 20 --clip "$walk" --json docs/data/steering_plain.json
echo "wrote docs/data/steering.json, steering_style.json and steering_plain.json (measured: $skill)"
