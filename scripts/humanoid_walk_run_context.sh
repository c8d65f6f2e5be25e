#!/usr/bin/env bash
# One ICCGAN policy, two gaits (seed 000's behaviour context over DeepMimic's walk and run,
# configs/humanoid_walk_run_context_iccgan.yaml): train, then measure each context against its
# clip and the other's (`mimic eval --context`), the switches between them (`--switch 0,1`) and
# the discriminator's reward for each clip under each context (`mimic score`); film a switch.
# Usage: scripts/humanoid_walk_run_context.sh [OUT_DIR]   (default runs/walk_run_context)
#   INIT      a run or model without a context to start from (default models/humanoid_walk_iccgan,
#             the 2·10⁷-sample walk; its inputs are widened by the one-hot); `none`: from scratch
#   LOG_STD   `learnt` (default: the source's noise, then PPO's) or a fixed log σ (e.g. −1.66)
#   STARTS    `any` (default: the config's, episodes start from either clip) or `by_context` (each
#             episode starts from its context's clip: env.context.starts)
#   PER_CONTEXT  1: one discriminator per context (rewards.0.per_context), each from the source's
#             discriminator; default 0: one discriminator with the one-hot among its inputs
#   DISCRIMINATORS  with PER_CONTEXT=1: each context's discriminator from its own run or model on
#             that behaviour alone, the walk's then the run's (mimic train --init-discriminators-from;
#             e.g. "models/humanoid_walk_iccgan models/humanoid_run_iccgan_from_walk", with INIT a
#             distilled student such as models/humanoid_walk_run_distilled)
#   MISMATCHED   other contexts' clip samples per policy sample that the discriminator learns to
#             call fake (rewards.0.mismatched; default 0: none)
#   TEACHERS  instead of training: `mimic distill` from these runs or models, the walk's then the
#             run's (e.g. "models/humanoid_walk_iccgan models/humanoid_run_iccgan_from_walk"), with
#             ROUNDS rounds (default 100) of 16 episodes; LOG_STD then sets the student's noise
#   ITERATIONS (default: the config's 5,000 of 4,096 samples), THREADS (default 1), TRIALS (20)
# Resumable: a run with a checkpoint is resumed (stop it with Ctrl-C at any time); evaluations are
# redone on each call, since the run may have moved on. Needs ../shared/data.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-runs/walk_run_context}
init=${INIT:-models/humanoid_walk_iccgan}
log_std=${LOG_STD:-learnt}
starts=${STARTS:-any}
per_context=${PER_CONTEXT:-0}
mismatched=${MISMATCHED:-0}
threads=${THREADS:-1}
trials=${TRIALS:-20}
mimic=${MIMIC:-build/src/mimic}
config=configs/humanoid_walk_run_context_iccgan.yaml
motions=../shared/data/deepmimic/motions
[ -d "$motions" ] || { echo "needs $motions (../shared/data beside the repository)" >&2; exit 1; }
mkdir -p "$out" runs
# The config reads one demonstrations file per context from runs/.
for clip in walk run; do
  demos=runs/humanoid_${clip}_links_demos.csv
  [ -f "$demos" ] || "$mimic" record-clip configs/humanoid_walk_iccgan_links.yaml --clip "$motions/humanoid3d_$clip.txt" --passes 8 -o "$demos"
done
run="$out/run"
iterations=()
[ -n "${ITERATIONS:-}" ] && iterations=(--iterations "$ITERATIONS")
if [ -n "${TEACHERS:-}" ]; then
  teachers=()
  for t in $TEACHERS; do teachers+=(--teacher "$t"); done
  args=(-o "$run" "${teachers[@]}" --rounds "${ROUNDS:-100}" --threads "$threads")
  if [ -f "$run/checkpoint.pt" ]; then
    args+=(--resume)
  else
    args+=("$config")
    [ "$log_std" != learnt ] && args+=(--set policy.learn_std=false --set "policy.log_std=$log_std")
  fi
  "$mimic" distill "${args[@]}" >> "$out/train.log" 2>&1
elif [ -f "$run/checkpoint.pt" ]; then
  "$mimic" train --resume -o "$run" --threads "$threads" "${iterations[@]}" >> "$out/train.log" 2>&1
else
  args=("$config" -o "$run" --threads "$threads" "${iterations[@]}")
  [ "$init" != none ] && args+=(--init-from "$init")
  [ "$log_std" != learnt ] && args+=(--set policy.learn_std=false --set "policy.log_std=$log_std")
  [ "$starts" != any ] && args+=(--set "env.context.starts=$starts")
  [ "$per_context" = 1 ] && args+=(--set rewards.0.per_context=true)
  [ "$mismatched" != 0 ] && args+=(--set "rewards.0.mismatched=$mismatched")
  if [ -n "${DISCRIMINATORS:-}" ]; then
    [ "$per_context" = 1 ] || { echo "DISCRIMINATORS needs PER_CONTEXT=1" >&2; exit 1; }
    args+=(--init-discriminators-from $DISCRIMINATORS)
  fi
  "$mimic" train "${args[@]}" > "$out/train.log" 2>&1
fi
# Each clip under each context: a policy that heeds its context does worse under the other one.
for context in 0 1; do
  for clip in walk run; do
    "$mimic" eval "$run" --clip "$motions/humanoid3d_$clip.txt" --context $context --episodes 10 --trials "$trials" --json "$out/${clip}_context$context.json"
  done
done
"$mimic" eval "$run" --episodes 1 --trials "$trials" --switch 0,1 --json "$out/switch.json"
"$mimic" render "$run" -o "$out/switch.mp4" --contexts 0,1 --context-seconds 5
# The discriminator's reward for each clip under each context: whether it tells them apart
# (a distilled student has none).
if [ -z "${TEACHERS:-}" ]; then
  for clip in walk run; do
    "$mimic" score "$run" --demos "runs/humanoid_${clip}_links_demos.csv" --json "$out/score_$clip.json"
  done
fi
python3 - "$out" <<'PY'
import csv, json, sys
out = sys.argv[1]
import os
log = f"{out}/run/metrics.csv" if os.path.exists(f"{out}/run/metrics.csv") else f"{out}/run/distill.csv"
m = list(csv.DictReader(open(log)))[-1]
print(f"{float(m['samples']) / 1e6:.2f} M samples in this run, {float(m['wall_s']):.0f} s")
print("| context held | against | imitation error | down | progress |")
print("| --- | --- | --- | --- | --- |")
for context, behaviour in enumerate(("walk", "run")):
    for name, speed in (("walk", 0.98), ("run", 3.56)):
        i = json.load(open(f"{out}/{name}_context{context}.json"))["imitation"]
        progress = "—" if i.get("progress") is None else f"{i['progress']:.2f}"
        print(f"| {context} ({behaviour}) | {name} clip, {speed} m/s | {i['error_mean']:.3f} ± {i['error_std']:.3f} m | "
              f"{i['down']} of {i['trials']} | {progress} |")
print("| switch | fell before / after | speed before → after (m/s) |")
print("| --- | --- | --- |")
def speed(mean, sd):  # null: every trial had fallen by then
    return "—" if mean is None else f"{mean:.2f} ± {sd:.2f}"
for s in json.load(open(f"{out}/switch.json"))["switches"]:
    print(f"| {s['from']} → {s['to']} | {s['fell_before']} / {s['fell_after']} | "
          f"{speed(s['speed_before_mean'], s['speed_before_std'])} → {speed(s['speed_after_mean'], s['speed_after_std'])} |")
PY
