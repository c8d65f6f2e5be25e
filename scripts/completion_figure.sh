#!/usr/bin/env bash
# docs/figures/motion_completion.png (docs/video.md): one frame of DeepMimic's run rendered on its
# humanoid, put to `mimic complete` with the four shipped humanoid skills, and the still beside the
# completion 0.5, 1.5 and 2.5 s later. Intermediate files in runs/completion/. About a minute.
set -euo pipefail
cd "$(dirname "$0")/.."
data=${MIMIC_DATA:-../shared/data}
mimic=${MIMIC:-build/src/mimic}
out=runs/completion
[ -x "$mimic" ] || { echo "completion_figure.sh: build mimic first (cmake --preset default && cmake --build --preset default)" >&2; exit 1; }
[ -d "$data/deepmimic" ] || { echo "completion_figure.sh: the shared data is not at $data (set MIMIC_DATA)" >&2; exit 1; }
mkdir -p "$out"
"$mimic" render "$data/deepmimic/motions/humanoid3d_run.txt" -o "$out/run.mp4"
ffmpeg -v error -y -i "$out/run.mp4" -vf "select=eq(n\\,10)" -frames:v 1 "$out/still.png"
"$mimic" complete "$out/still.png" --skills models/humanoid_walk_iccgan models/humanoid_run_iccgan_straight_loop \
  models/humanoid_kick_iccgan_total models/humanoid_punch_iccgan_annealed --seconds 3 -o "$out/completion.mp4" --json "$out/completion.json"
# The still, then the completion at 0.5, 1.5 and 2.5 s (frames 15, 45, 75 at 30 Hz), each 320 wide.
ffmpeg -v error -y -i "$out/still.png" -i "$out/completion.mp4" -filter_complex \
  "[0:v]scale=320:-2[s];[1:v]select=eq(n\\,15)+eq(n\\,45)+eq(n\\,75),scale=320:-2,tile=3x1[c];[s][c]hstack=inputs=2" \
  -frames:v 1 docs/figures/motion_completion.png
echo "wrote docs/figures/motion_completion.png"
