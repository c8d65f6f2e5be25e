#!/usr/bin/env bash
# Seed 003 Tables 1 and 2 and Fig. 12 at a reduced budget, on 2 cores: two runs at a time, one
# thread each, all from configs/humanoid_walk_tracking.yaml with only the clip (and what a clip
# needs) changed; `mimic eval` of each into <out>/<name>.json.
#  - table/<clip>: the ten clips of seed 003 Table 1 with RSI (roll without early termination:
#    its torso touches the ground by design);
#  - dog_trot: the same objective on DeepMimic's dog (another body, seed 003 section 9);
#  - backflip_{fsi,asi5,asi10,asi20}: with table/backflip (RSI), Table 2 and Fig. 12 on the backflip.
# Usage: scripts/tracking_table.sh [iterations per run (default 250: 1.02 M samples)] [out dir]
# EVAL_ONLY=1 evaluates the runs already there again (after a change to mimic eval) instead.
set -euo pipefail
iterations=${1:-250}
out=${2:-runs/tracking_table}
mimic=${MIMIC:-build/src/mimic}
config=configs/humanoid_walk_tracking.yaml
motions=deepmimic/motions
mkdir -p "$out/table"

# train NAME [--set ...]: one run and its evaluation, logged to <out>/NAME.log.
train() {
  local name=$1
  shift
  if [[ ${EVAL_ONLY:-0} == 1 ]]; then
    "$mimic" eval "$out/$name" --episodes 10 --trials 20 --json "$out/$name.json" > "$out/$name.eval.log" 2>&1 ||
      echo "$name: evaluation failed: see $out/$name.eval.log" >&2
    return
  fi
  {
    "$mimic" train "$config" -o "$out/$name" --set iterations="$iterations" --set collect.threads=1 --set checkpoint_every=10 "$@" &&
      "$mimic" eval "$out/$name" --episodes 10 --trials 20 --json "$out/$name.json"
  } > "$out/$name.log" 2>&1 || echo "$name failed: see $out/$name.log" >&2
}

# At most two runs at once (one per core).
slot() {
  while (($(jobs -rp | wc -l) >= 2)); do wait -n || true; done
}

clip() { echo "env.clip=$motions/humanoid3d_$1.txt"; }
for c in walk run backflip cartwheel jump kick punch roll spin spinkick; do
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
  train "backflip_asi$k" --set "$(clip backflip)" --set "init={kind: adaptive, components: $k, episodes: 500}" &
done
wait
echo "done: $out"
