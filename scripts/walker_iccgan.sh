#!/usr/bin/env bash
# Reduced-budget stand-in for seed 004 section 6.7's ablation, on the planar walker (see
# configs/walker_iccgan.yaml): 1 / 8 / 32 / 64 discriminator heads, with and without the gradient
# penalty, 512,000 samples each (125 iterations). Each policy is evaluated over 20 episodes with
# its mean action; the table is normalised by the PPO expert's return measured the same way.
# Usage: scripts/walker_iccgan.sh [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-runs/walker_iccgan}
mimic=${MIMIC:-build/src/mimic}
iterations=125
mkdir -p "$out"
names=()
for gp in 10 0; do
  for heads in 1 8 32 64; do
    name="heads${heads}_gp${gp}"
    names+=("$name")
    if [ -f "$out/$name/checkpoint.pt" ]; then
      grep -q "^$iterations," "$out/$name/metrics.csv" || "$mimic" train --resume -o "$out/$name" --iterations $iterations >> "$out/$name.log" 2>&1
    else
      "$mimic" train configs/walker_iccgan.yaml -o "$out/$name" --iterations $iterations \
        --set rewards.0.heads=$heads --set rewards.0.gradient_penalty=$gp > "$out/$name.log" 2>&1
    fi
    "$mimic" eval "$out/$name" --episodes 20 --json "$out/$name.json"
  done
done
"$mimic" eval models/walker_ppo --episodes 20 --json "$out/expert.json"
"$mimic" plot "$out/heads1_gp10" "$out/heads8_gp10" "$out/heads32_gp10" "$out/heads64_gp10" "$out/heads32_gp0" --smooth 10 \
  --names "1 head" "8 heads" "32 heads" "64 heads" "32 heads, no penalty" \
  --title "Walker, discriminator ensemble ablation: task return (unseen by the imitation)" -o "$out/walker_iccgan_return.svg"
python3 - "$out" <<'PY'
import csv, json, sys
out = sys.argv[1]
expert = json.load(open(f"{out}/expert.json"))["return_mean"]
rows = ["| heads | with gradient penalty (lambda 10) | without |", "|---|---|---|"]
for heads in (1, 8, 32, 64):
    cells = []
    for gp in (10, 0):
        name = f"heads{heads}_gp{gp}"
        r = json.load(open(f"{out}/{name}.json"))
        m = list(csv.DictReader(open(f"{out}/{name}/metrics.csv")))[-1]
        cells.append(f"{r['return_mean'] / expert:.2f} ({r['return_mean']:.0f} ± {r['return_std']:.0f}; {float(m['wall_s']):.0f} s)")
    rows.append(f"| {heads} | " + " | ".join(cells) + " |")
table = "\n".join(rows) + f"\n\nExpert (models/walker_ppo, mean actions, 20 episodes): {expert:.0f}.\n"
open(f"{out}/table.md", "w").write(table)
print(table)
PY
