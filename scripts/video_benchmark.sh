#!/usr/bin/env bash
# The reconstruction's two benchmarks with a known answer (docs/video.md), on DeepMimic's humanoid
# clips, each reconstructed on DeepMimic's humanoid (`mimic reconstruct`, its defaults) and
# measured against the clip:
#  1. keypoints: the clip seen through a known camera with a pose estimator's errors
#     (`mimic video synth`, its documented levels) -> docs/results/video_benchmark.md;
#  2. video: the clip rendered (`mimic render`) and put through the pose model
#     (`mimic video keypoints`) -> docs/results/video_benchmark_rendered.md, and a still of the
#     first clip's video beside its reconstruction -> docs/figures/video_reconstruction.png.
# Intermediate files in runs/video_benchmark/.
#
#   scripts/video_benchmark.sh                 the clips below
#   scripts/video_benchmark.sh walk run        some of them
#
# Minutes on 2 cores (the pose model: about 40 ms a frame). Extra options for both steps: SYNTH_ARGS="--pixel-noise 6" RECONSTRUCT_ARGS="...".
set -euo pipefail
cd "$(dirname "$0")/.."
data=${MIMIC_DATA:-../shared/data}
mimic=${MIMIC:-build/src/mimic}
out=runs/video_benchmark
clips=("$@")
[ ${#clips[@]} -eq 0 ] && clips=(walk run jump kick punch dance_a cartwheel backflip spinkick roll)
[ -x "$mimic" ] || { echo "video_benchmark.sh: build mimic first (cmake --preset default && cmake --build --preset default)" >&2; exit 1; }
[ -d "$data/deepmimic" ] || { echo "video_benchmark.sh: the shared data is not at $data (set MIMIC_DATA)" >&2; exit 1; }
mkdir -p "$out"
character=$data/deepmimic/characters/humanoid3d.txt
reports=() rendered=()
for c in "${clips[@]}"; do
  clip=$data/deepmimic/motions/humanoid3d_$c.txt
  [ -f "$clip" ] || { echo "video_benchmark.sh: no clip $clip" >&2; exit 1; }
  # shellcheck disable=SC2086
  "$mimic" video synth "$clip" -o "$out/$c.keypoints.json" ${SYNTH_ARGS:-}
  # shellcheck disable=SC2086
  "$mimic" reconstruct "$out/$c.keypoints.json" --character "$character" -o "$out/$c.mclip" \
    --raw "$out/$c.raw.mclip" --truth "$clip" --json "$out/$c.json" ${RECONSTRUCT_ARGS:-}
  reports+=("$out/$c.json")
  "$mimic" render "$clip" -o "$out/$c.mp4"
  "$mimic" video keypoints "$out/$c.mp4" -o "$out/$c.video.json"
  # shellcheck disable=SC2086
  "$mimic" reconstruct "$out/$c.video.json" --character "$character" -o "$out/$c.video.mclip" \
    --raw "$out/$c.video.raw.mclip" --truth "$clip" --json "$out/$c.video.report.json" ${RECONSTRUCT_ARGS:-}
  rendered+=("$out/$c.video.report.json")
done
# A still of the first clip's video beside its reconstruction (docs/figures/video_reconstruction.png).
first=${clips[0]}
"$mimic" render "$out/$first.video.mclip" --character "$character" -o "$out/$first.video.reconstructed.mp4"
ffmpeg -v error -y -i "$out/$first.mp4" -i "$out/$first.video.reconstructed.mp4" \
  -filter_complex "[0:v][1:v]hstack=inputs=2,select=eq(n\\,20)" -frames:v 1 docs/figures/video_reconstruction.png
mkdir -p docs/results
"$mimic" table "${reports[@]}" --names "${clips[@]}" -o docs/results/video_benchmark.md
"$mimic" table "${rendered[@]}" --names "${clips[@]}" -o docs/results/video_benchmark_rendered.md
