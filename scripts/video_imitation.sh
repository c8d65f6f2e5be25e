#!/usr/bin/env bash
# A skill learnt from a video (docs/video.md): 4 s of DeepMimic's walk rendered on its humanoid
# by a camera that stays put (`mimic render --fixed-camera`: a following camera would hide the
# walk's travel from the pose model), put through the pose model (`mimic video keypoints`),
# reconstructed (`mimic reconstruct`, its defaults), imitated (`mimic imitate`, the ICCGAN recipe,
# 10^7 samples), evaluated against the reconstructed clip (the run's eval.json) and against the
# capture the video was rendered from (eval_truth.json), and filmed beside the source video
# (side_by_side.mp4; a still of it in docs/figures/video_imitation.png). The three reports go into
# docs/data/video_imitation/.
#
#   scripts/video_imitation.sh        the whole of it; a run already in runs/video_walk is resumed
#
# The imitation takes about 3-4 h on 2 cores (beside nothing else); the rest a few minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
data=${MIMIC_DATA:-../shared/data}
mimic=${MIMIC:-build/src/mimic}
src=runs/video_walk_source
run=runs/video_walk
[ -x "$mimic" ] || { echo "video_imitation.sh: build mimic first (cmake --preset default && cmake --build --preset default)" >&2; exit 1; }
[ -d "$data/deepmimic" ] || { echo "video_imitation.sh: the shared data is not at $data (set MIMIC_DATA)" >&2; exit 1; }
walk=$data/deepmimic/motions/humanoid3d_walk.txt
character=$data/deepmimic/characters/humanoid3d.txt
mkdir -p "$src"
if [ ! -f "$run/config.yaml" ]; then
  "$mimic" render "$walk" --seconds 4 --fixed-camera -o "$src/walk.mp4"
  "$mimic" video keypoints "$src/walk.mp4" -o "$src/walk.keypoints.json"
  "$mimic" reconstruct "$src/walk.keypoints.json" --character "$character" -o "$src/walk.video.mclip" --truth "$walk" --json "$src/reconstruction.json"
  "$mimic" imitate "$src/walk.video.mclip" -o "$run" --samples 10000000 --threads 1
else
  [ -f "$src/walk.mp4" ] || "$mimic" render "$walk" --seconds 4 --fixed-camera -o "$src/walk.mp4"
  "$mimic" imitate --resume -o "$run"
fi
# Against the capture itself: how near the skill learnt from the video comes to the true motion.
"$mimic" eval "$run" --clip "$walk" --json "$run/eval_truth.json"
# The source video (left) and the skill (right), 10 s of each side by side (the video loops).
"$mimic" render "$run" -o "$src/skill.mp4" --seconds 10
ffmpeg -v error -y -stream_loop -1 -i "$src/walk.mp4" -i "$src/skill.mp4" -filter_complex "[0:v][1:v]hstack=inputs=2" -t 10 "$run/side_by_side.mp4"
ffmpeg -v error -y -i "$run/side_by_side.mp4" -vf "select=eq(n\\,45)" -frames:v 1 docs/figures/video_imitation.png
# The figures of docs/video.md: the reconstruction's report and the skill's two evaluations.
mkdir -p docs/data/video_imitation
cp "$src/reconstruction.json" "$run/eval.json" "$run/eval_truth.json" docs/data/video_imitation/
echo "wrote $run/side_by_side.mp4, docs/figures/video_imitation.png and docs/data/video_imitation/"
