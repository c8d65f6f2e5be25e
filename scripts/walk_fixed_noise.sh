#!/usr/bin/env bash
# Why is the ICCGAN walk at 2·10⁷ samples less robust to cubes than at 7.96 M (docs/results/tracking.md)?
# Candidate: PPO shrank its learnt action noise (log σ about −1.66 at 7.96 M, −2.63 at 2·10⁷, from
# the entropy column), so late training met only small deviations from the clip. Test: train the
# 2·10⁷-sample walk on with the noise held at the 7.96 M level (`mimic train --init-from`, fixed σ),
# then measure imitation and robustness as scripts/walk_robustness.sh does.
# Usage: scripts/walk_fixed_noise.sh [SOURCE_RUN] [OUT_DIR]   (defaults: the walk's run directory,
# runs/walk_fixed_noise). ITERATIONS (default 750: 3.07 M samples, the run in docs/results/tracking.md), LOG_STD (default −1.66;
# `learnt` leaves the noise to PPO as in the source run: the control with the same samples),
# THREADS (default 1), TRIALS (default 100) robustness trials a mass at 5, 10 and 20 kg.
# Resumable: a run with a checkpoint is resumed, an evaluation whose JSON exists is kept. The source
# needs its full checkpoint (the run's, with the discriminator's replay; an exported model also works).
set -euo pipefail
cd "$(dirname "$0")/.."
source_run=${1:-runs/humanoid_walk_iccgan_cpu_feet_vel}
out=${2:-runs/walk_fixed_noise}
iterations=${ITERATIONS:-750}
log_std=${LOG_STD:--1.66}
threads=${THREADS:-1}
trials=${TRIALS:-100}
mimic=${MIMIC:-build/src/mimic}
clip=../shared/data/deepmimic/motions/humanoid3d_walk.txt
[ -f "$clip" ] || { echo "needs $clip (../shared/data beside the repository)" >&2; exit 1; }
[ -f "$source_run/checkpoint.pt" ] || { echo "needs $source_run/checkpoint.pt (the walk's run, see models/humanoid_walk_iccgan/README.md)" >&2; exit 1; }
run="$out/run"
mkdir -p "$out"
if [ -f "$run/checkpoint.pt" ]; then
  "$mimic" train --resume -o "$run" --iterations "$iterations" --threads "$threads"
else
  noise=(--set policy.learn_std=false --set "policy.log_std=$log_std")
  [ "$log_std" = learnt ] && noise=()
  "$mimic" train "$source_run/config.yaml" -o "$run" --init-from "$source_run" --iterations "$iterations" --threads "$threads" \
    "${noise[@]}"
fi
[ -f "$out/eval.json" ] || "$mimic" eval "$run" --clip "$clip" --episodes 10 --trials 20 --json "$out/eval.json"
[ -f "$out/robustness.json" ] || "$mimic" eval "$run" --clip "$clip" --episodes 1 --trials 1 --robustness 5,10,20 \
  --robustness-trials "$trials" --json "$out/robustness.json"
python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
e = json.load(open(f"{out}/eval.json"))["imitation"]
r = json.load(open(f"{out}/robustness.json"))["robustness"]
print(f"imitation error {e['error_mean']:.3f} ± {e['error_std']:.3f} m, progress {e['progress']:.2f}, down {e['down']} of {e['trials']}")
print("| policy | " + " | ".join(f"{x['mass']:g} kg" for x in r) + " |")
print("| --- |" + " --- |" * len(r))
print(f"| {out} | " + " | ".join(f"{x['frames_mean']:.1f} ± {x['frames_std'] / x['trials'] ** 0.5:.1f}" for x in r) + " |")
PY
