#!/usr/bin/env bash
# Seed 000's stairs: the shipped walk fine-tuned by RL on a staircase (8 steps up, a landing, 7
# down), rewarded for walking along the course (the heading goal held on +x) and for the clip's
# style (its discriminator), with a height map 2 m square ahead of the feet in its input. The
# staircase is a curriculum (seed 002 section 3.1.2): 20 levels of 1 cm to 20 cm steps, each of
# the 16 environments going a level up after crossing and down after falling before the course's
# middle (on the landing), and the policy reads the height map through seed 002's perceptual
# encoder (30-40-100 tanh).
# Trained into runs/stairs_walk (a run already there is resumed), then measured into
# docs/data/stairs.json: the share of 20 trials that get over the staircase at each step height,
# for the fine-tuned walk and for the shipped walk on the same courses.
#
#   scripts/stairs.sh               train (or resume) and measure
#   scripts/stairs.sh fixed         the same fine-tune on 0.10 m steps throughout, no curriculum
#                                   and no encoder, into runs/stairs_walk_fixed (then measured into
#                                   docs/data/stairs_fixed.json)
#   scripts/stairs.sh measure [RUN] measure what RUN (runs/stairs_walk) holds now: its model, or
#                                   the run's last checkpoint where it was stopped before the end
#
# The training takes about 3 h on 2 cores beside nothing else; the measurements about 15 min.
set -euo pipefail
cd "$(dirname "$0")/.."
data=${MIMIC_DATA:-../shared/data}
mimic=${MIMIC:-build/src/mimic}
mode=${1:-train}
run=runs/stairs_walk
terrain="{kind: stairs, step_height: 0.2, levels: 20}"
encoder=("--set" "policy.encoder={input: height_map}")
out=docs/data/stairs.json
if [ "$mode" = fixed ]; then
  run=runs/stairs_walk_fixed terrain="{kind: stairs, step_height: 0.1}" out=docs/data/stairs_fixed.json encoder=()
elif [ "$mode" = measure ] && [ -n "${2:-}" ]; then
  run=${2%/}
  [ "$run" = runs/stairs_walk_fixed ] && out=docs/data/stairs_fixed.json
fi
walk=$data/deepmimic/motions/humanoid3d_walk.txt
heights="0.02 0.05 0.10 0.15 0.20"
export OPENBLAS_CORETYPE=${OPENBLAS_CORETYPE:-Haswell}
[ -x "$mimic" ] || { echo "stairs.sh: build mimic first (cmake --preset default && cmake --build --preset default)" >&2; exit 1; }
[ -f "$walk" ] || { echo "stairs.sh: the shared data is not at $data (set MIMIC_DATA)" >&2; exit 1; }

if [ "$mode" != measure ]; then
  if [ ! -f "$run/config.yaml" ]; then
    "$mimic" imitate "$walk" --task heading --from models/humanoid_walk_iccgan -o "$run" --samples 5000000 \
      --set env.goal_turn=0 --set env.goal_period=1000000 --set env.max_seconds=15 \
      --set "env.terrain=$terrain" --set "env.observations=[links, link_velocities, height_map]" "${encoder[@]}"
  elif [ ! -f "$run/model/networks.mimic" ]; then
    "$mimic" imitate --resume -o "$run"
  fi
fi
skill=$run/model
[ -f "$skill/networks.mimic" ] || skill=$run
mkdir -p docs/data
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for who in fine_tuned shipped; do
  model=$skill
  [ $who = shipped ] && model=models/humanoid_walk_iccgan
  for h in $heights; do
    "$mimic" eval "$model" --episodes 1 --trials 1 --crossing --crossing-trials 20 \
      --set "env.terrain={kind: stairs, step_height: $h}" --json "$tmp/${who}_$h.json"
  done
done
# One file: {"fine_tuned": [crossing at each height], "shipped": [...]}.
python3 - "$tmp" "$heights" > "$out" <<'PY'
import json, sys
tmp, heights = sys.argv[1], sys.argv[2].split()
out = {who: [json.load(open(f"{tmp}/{who}_{h}.json"))["crossing"] for h in heights] for who in ("fine_tuned", "shipped")}
print(json.dumps(out, indent=1))
PY
echo "wrote $out (measured: $skill and models/humanoid_walk_iccgan)"
