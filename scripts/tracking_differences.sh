#!/usr/bin/env bash
# What each of the five likely differences from DeepMimic's implementation does to tracking the
# walk (docs/results/tracking.md, "How mimic's tracking differs"): configs/humanoid_walk_tracking.yaml
# as it is, and with one difference changed to DeepMimic's way at a time, at the same budget;
# `mimic eval` of each (20 trials of 20 s from evenly spaced phases: normalised return, progress,
# imitation error, falls) into <results>/<name>.json, then <results>/table.md and the failure-rate curves
# <figures>/tracking_differences_falls.png.
#   baseline         the config as it is
#   deepmimic_reward 0.5 pose, 0.05 velocity, 0.15 end effector, 0.2 root, 0.1 centre-of-mass
#                    velocity (scale 1), the reference re-synced to the character every cycle (1)
#   small_steps      2 policy epochs at a policy rate of 2·10^-5 instead of 5 at 10^-4 (2)
#   short_episodes   2 s episodes (evaluated on 20 s), any contact but the feet's a fall (3)
#   annealed_noise   action noise σ from 0.2 down to 0.07 over the run (4)
#   lag_observed     the reference's root in the observation (`reference_root`) (5)
#   combined         the three that helped alone, together: short_episodes, annealed_noise and
#                    lag_observed (the tracking recipe's settings)
# Two runs at a time, one thread each. A finished run's evaluation and learning curve are kept in
# RESULTS (default docs/data/tracking_differences: <name>.json and <name>.csv, its metrics.csv),
# which is committed, so that the runs can be made over several sessions and machines: a run
# whose evaluation is there is not trained again; one with a checkpoint in the out dir is resumed.
# The table and the figure cover the runs whose results are there.
# Usage: scripts/tracking_differences.sh [samples per run (default 5000000)] [out dir (default runs/tracking_differences)]
# REPORT_ONLY=1 only writes the table and the figure; FIGURES=dir (default: RESULTS) takes the figure.
set -euo pipefail
cd "$(dirname "$0")/.."
samples=${1:-5000000}
out=${2:-runs/tracking_differences}
mimic=${MIMIC:-build/src/mimic}
config=configs/humanoid_walk_tracking.yaml
results=${RESULTS:-docs/data/tracking_differences}
figures=${FIGURES:-$results}
iterations=$(((samples + 4095) / 4096))
[ -x "$mimic" ] || { echo "tracking_differences.sh: build mimic first (cmake --preset default && cmake --build --preset default)" >&2; exit 1; }
export OPENBLAS_CORETYPE=${OPENBLAS_CORETYPE:-Haswell}
mkdir -p "$out" "$results" "$figures"
names=(baseline deepmimic_reward small_steps short_episodes annealed_noise lag_observed combined)
declare -A changes=(
  [baseline]=""
  [deepmimic_reward]="env.weights={pose: 0.5, velocity: 0.05, end_effector: 0.15, com: 0.1, root: 0.2};env.com_term=velocity;env.scales={com: 1};env.resync_root=true"
  [small_steps]="ppo.epochs=2;optimizer.policy_lr=2.0e-5"
  [short_episodes]="env.max_seconds=2;env.fall_links=[root, chest, neck, right_hip, right_knee, right_shoulder, right_elbow, right_wrist, left_hip, left_knee, left_shoulder, left_elbow, left_wrist]"
  [annealed_noise]="policy.log_std_final=-2.66"
  [lag_observed]="env.observations=[full_state, phase, reference_root]"
)
changes[combined]="${changes[short_episodes]};${changes[annealed_noise]};${changes[lag_observed]}"

report() {
  local finished=() name
  for name in "${names[@]}"; do [[ -f $results/$name.json ]] && finished+=("$name"); done
  if ((${#finished[@]} == 0)); then
    echo "tracking_differences.sh: no run is finished yet (nothing in $results)" >&2
    return
  fi
  local runs=("${finished[@]/#/$results/}")
  "$mimic" table "${runs[@]/%/.json}" --names "${finished[@]}" -o "$results/table.md"
  "$mimic" plot "${runs[@]/%/.csv}" --names "${finished[@]}" --y failure_rate --smooth 20 \
    --title "The walk tracked, one difference changed at a time: falls per episode" -o "$figures/tracking_differences_falls.png"
}
if [[ ${REPORT_ONLY:-0} == 1 ]]; then
  report
  exit
fi

# train NAME: one run and its evaluation (on 20 s episodes whatever it trained on), logged to <out>/NAME.log.
train() {
  local name=$1 sets=() change
  if [[ -f $results/$name.json ]]; then
    echo "$name: evaluated already, not trained again"
    return
  fi
  IFS=';' read -r -a list <<<"${changes[$name]}"
  for change in "${list[@]}"; do sets+=(--set "$change"); done
  local start=("$config" --iterations "$iterations" --threads 1 "${sets[@]}")
  if [[ -f $out/$name/checkpoint.pt ]]; then
    start=(--resume --iterations "$iterations")
  else
    rm -rf "${out:?}/$name"
  fi
  local eval_sets=()
  [[ $name == short_episodes || $name == combined ]] && eval_sets=(--set env.max_seconds=20)
  {
    "$mimic" train "${start[@]}" -o "$out/$name" &&
      "$mimic" eval "$out/$name" --trials 20 "${eval_sets[@]}" --json "$out/$name.json" &&
      cp "$out/$name/metrics.csv" "$results/$name.csv" && mv "$out/$name.json" "$results/$name.json"
  } > "$out/$name.log" 2>&1 || echo "$name failed: see $out/$name.log" >&2
}

# At most two runs at once (one per core).
slot() {
  while (($(jobs -rp | wc -l) >= 2)); do wait -n || true; done
}
for name in "${names[@]}"; do
  slot
  train "$name" &
done
wait
report
echo "done: $results"
