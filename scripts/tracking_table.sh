#!/usr/bin/env bash
# Seed 003 Tables 1 and 2 and Fig. 12 at a reduced budget, on 2 cores: two runs at a time, one
# thread each, all from configs/humanoid_walk_tracking.yaml with only the clip (and what a clip
# needs) changed; `mimic eval` of each into <out>/<name>.json.
#  - table/<clip>: the ten clips of seed 003 Table 1 with RSI (roll without early termination:
#    its torso touches the ground by design);
#  - dog_trot: the same objective on DeepMimic's dog (another body, seed 003 section 9);
#  - backflip_{fsi,asi5,asi10,asi20}: with table/backflip (RSI), Table 2 and Fig. 12 on the backflip;
#  - walk_{fsi,asi10}: with table/walk (RSI), Table 2 on the walk.
# Then the tables (mimic table) and learning curves (mimic plot) docs/results/tracking.md shows:
# <out>/{table,backflip_init,walk_init}.md and <figures>/{tracking_skills,backflip_init,walk_init}_reward.png.
# A run whose evaluation is already there is not trained again and one with a checkpoint is
# resumed (to this call's iterations), so a stopped script picks up where it was.
# Usage: scripts/tracking_table.sh [iterations per run (default 250: 1.02 M samples)] [out dir]
# EVAL_ONLY=1 evaluates the runs already there again (after a change to mimic eval) instead;
# REPORT_ONLY=1 only writes the tables and figures; FIGURES=dir (default: out dir) takes the figures.
set -euo pipefail
iterations=${1:-250}
out=${2:-runs/tracking_table}
mimic=${MIMIC:-build/src/mimic}
config=configs/humanoid_walk_tracking.yaml
motions=deepmimic/motions
figures=${FIGURES:-$out}
mkdir -p "$out/table" "$figures"
clips=(walk run backflip cartwheel jump kick punch roll spin spinkick)

# init_report CLIP RUN...: the start-distribution comparison on CLIP, RSI being table/CLIP.
init_report() {
  local clip=$1 names=() runs=() run
  shift
  for run in "$@"; do
    case $run in
      table/*) names+=(RSI) ;;
      *_fsi) names+=(FSI) ;;
      *) names+=("ASI k = ${run##*_asi}") ;;
    esac
    runs+=("$out/$run")
  done
  "$mimic" table "${runs[@]/%/.json}" --names "${names[@]}" -o "$out/${clip}_init.md"
  "$mimic" plot "${runs[@]}" --names "${names[@]}" --y reward --smooth 10 \
    --title "$clip, start distributions: reward per step (max 1)" -o "$figures/${clip}_init_reward.png"
}

# The tables and learning curves of the runs in <out>.
report() {
  local runs=("${clips[@]/#/$out/table/}")
  "$mimic" table "${runs[@]/%/.json}" "$out/dog_trot.json" --names "${clips[@]}" dog_trot -o "$out/table.md"
  "$mimic" plot "${runs[@]}" --names "${clips[@]}" --y reward --smooth 10 \
    --title "Tracking skills, $iterations iterations each: reward per step (max 1)" -o "$figures/tracking_skills_reward.png"
  init_report backflip backflip_fsi table/backflip backflip_asi5 backflip_asi10 backflip_asi20
  init_report walk walk_fsi table/walk walk_asi10
}
if [[ ${REPORT_ONLY:-0} == 1 ]]; then
  report
  exit
fi

# train NAME [--set ...]: one run and its evaluation, logged to <out>/NAME.log.
train() {
  local name=$1
  shift
  if [[ ${EVAL_ONLY:-0} == 1 ]]; then
    "$mimic" eval "$out/$name" --episodes 10 --trials 20 --json "$out/$name.json" > "$out/$name.eval.log" 2>&1 ||
      echo "$name: evaluation failed: see $out/$name.eval.log" >&2
    return
  fi
  if [[ -f $out/$name.json ]]; then
    echo "$name: evaluated already, not trained again"
    return
  fi
  local start=("$config" --set iterations="$iterations" --set collect.threads=1 --set checkpoint_every=10 "$@")
  if [[ -f $out/$name/checkpoint.pt ]]; then
    start=(--resume --iterations "$iterations")  # to this call's count, not the one it was started with
  else
    rm -rf "${out:?}/$name"
  fi
  {
    "$mimic" train "${start[@]}" -o "$out/$name" &&
      "$mimic" eval "$out/$name" --episodes 10 --trials 20 --json "$out/$name.json"
  } > "$out/$name.log" 2>&1 || echo "$name failed: see $out/$name.log" >&2
}

# At most two runs at once (one per core).
slot() {
  while (($(jobs -rp | wc -l) >= 2)); do wait -n || true; done
}

clip() { echo "env.clip=$motions/humanoid3d_$1.txt"; }
asi() { echo "init={kind: adaptive, components: $1, episodes: 500}"; }
for c in "${clips[@]}"; do
  slot
  if [[ $c == roll ]]; then
    train "table/$c" --set "$(clip "$c")" --set env.early_termination=false &
  else
    train "table/$c" --set "$(clip "$c")" &
  fi
done
slot
train dog_trot --set "env.character=deepmimic/characters/dog3d.txt" --set "env.clip=$motions/dog3d_trot.txt" &
slot
train backflip_fsi --set "$(clip backflip)" --set env.init=fixed &
for k in 5 10 20; do
  slot
  train "backflip_asi$k" --set "$(clip backflip)" --set "$(asi "$k")" &
done
slot
train walk_fsi --set env.init=fixed &
slot
train walk_asi10 --set "$(asi 10)" &
wait
report
echo "done: $out"
