#!/usr/bin/env bash
# Tracking on another body (seed 003's heavier, otherwise proportioned Atlas; docs/tracking.md):
# DeepMimic's humanoid with longer thighs, shins and trunk, shorter upper arms and twice the mass
# (`mimic character scale`), its walk put on it (`mimic motion retarget`, the same-names map with
# the ankles placed by inverse kinematics), tracked with the walk's tracking config and nothing
# else changed, evaluated (20 trials of 20 s) and filmed with the clip as a ghost.
#
#   scripts/heavy_body.sh [SAMPLES]    default 2·10^7 (the walk's budget); a run already there is resumed
#
# Outputs in runs/heavy_body: heavy3d.txt and heavy3d_ctrl.txt, walk.mclip, retarget.log, run/,
# eval.json, walk.mp4. TRACKING_CONFIG=FILE tracks with another config (default
# configs/humanoid_walk_tracking.yaml). About 6 h at one thread for 2·10^7 samples.
set -euo pipefail
cd "$(dirname "$0")/.."
samples=${1:-20000000}
data=${MIMIC_DATA:-../shared/data}
mimic=${MIMIC:-build/src/mimic}
config=${TRACKING_CONFIG:-configs/humanoid_walk_tracking.yaml}
out=runs/heavy_body
[ -x "$mimic" ] || { echo "heavy_body.sh: build mimic first (cmake --preset default && cmake --build --preset default)" >&2; exit 1; }
[ -d "$data/deepmimic" ] || { echo "heavy_body.sh: the shared data is not at $data (set MIMIC_DATA)" >&2; exit 1; }
export OPENBLAS_CORETYPE=${OPENBLAS_CORETYPE:-Haswell}
mkdir -p "$out"
if [ ! -f "$out/run/checkpoint.pt" ]; then
  "$mimic" character scale "$data/deepmimic/characters/humanoid3d.txt" -o "$out/heavy3d.txt" \
    --length hip=1.15 --length knee=1.1 --length chest=1.1 --length shoulder=0.95 --mass 2
  "$mimic" motion retarget "$data/deepmimic/motions/humanoid3d_walk.txt" --map data/retarget/humanoid3d_to_scaled.yaml \
    --target "$out/heavy3d.txt" -o "$out/walk.mclip" | tee "$out/retarget.log"
  rm -rf "$out/run"
  "$mimic" train "$config" -o "$out/run" --iterations $(((samples + 4095) / 4096)) --threads 1 \
    --set "env.character=$out/heavy3d.txt" --set "env.clip=$out/walk.mclip"
else
  "$mimic" train --resume -o "$out/run" --iterations $(((samples + 4095) / 4096))
fi
"$mimic" eval "$out/run" --trials 20 --json "$out/eval.json"
"$mimic" render "$out/run" -o "$out/walk.mp4" --seconds 10 --ghost
echo "wrote $out/eval.json and $out/walk.mp4"
