#!/usr/bin/env bash
# Tracking on another body (seed 003's heavier, otherwise proportioned Atlas; docs/results/tracking.md):
# DeepMimic's humanoid with longer thighs, shins and trunk, shorter upper arms and twice the mass
# (`mimic character scale`), its walk put on it (`mimic motion retarget`, the same-names map with
# the ankles placed by inverse kinematics), tracked by the tracking recipe with nothing changed
# (`mimic imitate --method tracking --character`), evaluated (20 trials of 20 s) and filmed with
# the clip as a ghost.
#
#   scripts/heavy_body.sh [SAMPLES]    default 5·10^6 (the ten-clip table's budget); a run already there is resumed
#
# Outputs in runs/heavy_body: heavy3d.txt and heavy3d_ctrl.txt, walk.mclip, retarget.log, run/ (the
# model, eval.json, report.md, video.mp4). The run's evaluation and learning curve are kept in
# RESULTS (default docs/data/heavy_body: walk.json, walk.csv, retarget.log). About 1 h at one
# thread for 5·10^6 samples.
set -euo pipefail
cd "$(dirname "$0")/.."
samples=${1:-5000000}
data=${MIMIC_DATA:-../shared/data}
mimic=${MIMIC:-build/src/mimic}
out=runs/heavy_body
results=${RESULTS:-docs/data/heavy_body}
[ -x "$mimic" ] || { echo "heavy_body.sh: build mimic first (cmake --preset default && cmake --build --preset default)" >&2; exit 1; }
[ -d "$data/deepmimic" ] || { echo "heavy_body.sh: the shared data is not at $data (set MIMIC_DATA)" >&2; exit 1; }
export OPENBLAS_CORETYPE=${OPENBLAS_CORETYPE:-Haswell}
mkdir -p "$out" "$results"
common=(-o "$out/run" --samples "$samples" --threads 1 --trials 20 --video-seconds 10)
if [ ! -f "$out/run/checkpoint.pt" ]; then
  "$mimic" character scale "$data/deepmimic/characters/humanoid3d.txt" -o "$out/heavy3d.txt" \
    --length hip=1.15 --length knee=1.1 --length chest=1.1 --length shoulder=0.95 --mass 2
  "$mimic" motion retarget "$data/deepmimic/motions/humanoid3d_walk.txt" --map data/retarget/humanoid3d_to_scaled.yaml \
    --target "$out/heavy3d.txt" -o "$out/walk.mclip" | tee "$out/retarget.log"
  rm -rf "$out/run"
  "$mimic" imitate "$out/walk.mclip" --character "$out/heavy3d.txt" --method tracking "${common[@]}"
else
  "$mimic" imitate --resume "${common[@]}"
fi
cp "$out/run/metrics.csv" "$results/walk.csv"
cp "$out/retarget.log" "$results/retarget.log"
cp "$out/run/eval.json" "$results/walk.json.tmp" && mv "$results/walk.json.tmp" "$results/walk.json"
echo "wrote $out/run (report.md, video.mp4) and $results"
