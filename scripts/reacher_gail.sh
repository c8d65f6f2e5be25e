#!/usr/bin/env bash
# The arms comparison of docs/results/arms.md (seed 000 Fig. 3 right): GAIL from the 2-link expert
# (models/reacher_ppo) by a 2-link arm seeing the expert's whole observation, a 2-link arm whose
# discriminator sees only the fingertip-to-target vector, and a 3-link arm with that vector only.
# Plots the task's reach term (minus the fingertip-target distance per step), which no GAIL run
# optimises, beside the PPO expert's own learning curve. Usage: scripts/reacher_gail.sh [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-runs/reacher_gail}
mimic=${MIMIC:-build/src/mimic}
mkdir -p "$out"
run() {  # name, --set arguments...
  local name=$1; shift
  [ -f "$out/$name/checkpoint.pt" ] && grep -q "^250," "$out/$name/metrics.csv" && return 0
  if [ -f "$out/$name/checkpoint.pt" ]; then
    "$mimic" train --resume -o "$out/$name" > "$out/$name.log" 2>&1
  else
    "$mimic" train configs/reacher_gail.yaml -o "$out/$name" "$@" > "$out/$name.log" 2>&1
  fi
}
run two_link_full
run two_link_vector --set "rewards.0.features=[ee_to_target]"
run three_link_vector --set "rewards.0.features=[ee_to_target]" --set env.links=3
"$mimic" plot models/reacher_ppo "$out/two_link_full" "$out/two_link_vector" "$out/three_link_vector" --y term_reach --smooth 5 \
  --names "PPO expert (task reward)" "GAIL 2-link, full features" "GAIL 2-link, vector only" "GAIL 3-link, vector only" \
  --title "Arms imitating a 2-link expert: reach term per step (task reward unseen by GAIL)" -o "$out/reacher_gail_reach.svg"
for name in two_link_full two_link_vector three_link_vector; do
  "$mimic" eval "$out/$name" --episodes 50 --json "$out/$name.json"
done
"$mimic" eval models/reacher_ppo --episodes 50 --json "$out/expert.json"
