#!/usr/bin/env bash
# The walker imitation comparison of docs/results/walker.md (seed 002 section 3.2.1, seed 000 Fig. 3
# left): GAIL with (s, a), GAIL with states only, and behavioural cloning, from 5, 10, 25 and 50
# expert trajectories (models/walker_ppo/expert_50.csv, sub-sampled every 20 steps). Each run is
# evaluated over 20 episodes with the policy's mean action; scores are normalised by the expert's
# return measured the same way. Usage: scripts/walker_gail.sh [OUT_DIR] [PARALLEL_RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-runs/walker_gail}
parallel=${2:-1}
mimic=${MIMIC:-build/src/mimic}
mkdir -p "$out"

runs=()
for n in 5 10 25 50; do
  for t in s sa; do runs+=("gail_${t}_$n"); done
done
train() {  # name
  local name=$1 t n
  t=$(echo "$name" | cut -d_ -f2); n=$(echo "$name" | cut -d_ -f3)
  [ -f "$out/$name/checkpoint.pt" ] && grep -q "^250," "$out/$name/metrics.csv" 2>/dev/null && return 0
  local resume=()
  [ -f "$out/$name/checkpoint.pt" ] && resume=(--resume)
  if [ ${#resume[@]} -eq 0 ]; then
    "$mimic" train configs/walker_gail.yaml -o "$out/$name" --set rewards.0.transition=$t --set rewards.0.episodes=$n > "$out/$name.log" 2>&1
  else
    "$mimic" train --resume -o "$out/$name" >> "$out/$name.log" 2>&1
  fi
}
export -f train; export out mimic
printf '%s\n' "${runs[@]}" | xargs -P "$parallel" -I{} bash -c 'train {}'

for n in 5 10 25 50; do
  [ -f "$out/bc_$n/checkpoint.pt" ] || "$mimic" clone configs/walker_gail.yaml --expert models/walker_ppo/expert_50.csv --episodes $n -o "$out/bc_$n"
done

"$mimic" eval models/walker_ppo --episodes 20 --json "$out/expert.json"
for name in "${runs[@]}" bc_5 bc_10 bc_25 bc_50; do
  "$mimic" eval "$out/$name" --episodes 20 --json "$out/$name.json"
done
python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
expert = json.load(open(f"{out}/expert.json"))["return_mean"]
rows = ["| expert trajectories | GAIL (s, a) | GAIL (s) | BC |", "|---|---|---|---|"]
for n in (5, 10, 25, 50):
    cells = []
    for name in (f"gail_sa_{n}", f"gail_s_{n}", f"bc_{n}"):
        r = json.load(open(f"{out}/{name}.json"))
        cells.append(f"{r['return_mean'] / expert:.2f} ({r['return_mean']:.0f} ± {r['return_std']:.0f})")
    rows.append(f"| {n} | " + " | ".join(cells) + " |")
table = "\n".join(rows) + f"\n\nExpert (models/walker_ppo, mean actions, 20 episodes): {expert:.0f}.\n"
open(f"{out}/table.md", "w").write(table)
print(table)
PY
