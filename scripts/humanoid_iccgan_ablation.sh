#!/usr/bin/env bash
# Seed 004 §6.7's ablation on the humanoid walk at a reduced budget: 1 / 8 / 32 / 64 discriminator
# heads, with and without the gradient penalty, configs/humanoid_walk_iccgan_cpu.yaml otherwise.
# ITERATIONS (default 750: 3.07 M samples, where the full config begins to walk) each, then
# `mimic eval` against the walk clip. Resumes what a previous call left (Ctrl-C and call again).
# Writes OUT_DIR/table.md (imitation error and progress per cell) and a learning-curve plot.
# Usage: scripts/humanoid_iccgan_ablation.sh [OUT_DIR]
# THREADS (default 2) sets collect.threads. About 30 min a cell on two cores; needs ../shared/data.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-runs/humanoid_iccgan_ablation}
mimic=${MIMIC:-build/src/mimic}
iterations=${ITERATIONS:-750}
threads=${THREADS:-2}
walk=../shared/data/deepmimic/motions/humanoid3d_walk.txt
[ -f "$walk" ] || { echo "needs $walk (../shared/data beside the repository)" >&2; exit 1; }
demos=runs/humanoid_walk_links_demos.csv
mkdir -p "$out" runs
[ -f "$demos" ] || "$mimic" record-clip configs/humanoid_walk_iccgan_links.yaml --clip "$walk" --passes 8 -o "$demos"
for gp in 10 0; do
  for heads in 1 8 32 64; do
    run="$out/heads${heads}_gp${gp}"
    if [ -f "$run/checkpoint.pt" ]; then
      grep -q "^$iterations," "$run/metrics.csv" || "$mimic" train --resume -o "$run" --threads "$threads" >> "$run.log" 2>&1
    else
      "$mimic" train configs/humanoid_walk_iccgan_cpu.yaml -o "$run" --iterations "$iterations" --threads "$threads" \
        --set rewards.0.heads=$heads --set rewards.0.gradient_penalty=$gp > "$run.log" 2>&1
    fi
    "$mimic" eval "$run" --clip "$walk" --episodes 10 --trials 20 --json "$run.json"
  done
done
"$mimic" plot "$out/heads1_gp10" "$out/heads8_gp10" "$out/heads32_gp10" "$out/heads64_gp10" "$out/heads32_gp0" --smooth 10 \
  --y episode_length --names "1 head" "8 heads" "32 heads" "64 heads" "32 heads, no penalty" \
  --title "Humanoid walk, discriminator ensemble ablation: episode length" -o "$out/ablation_episode_length.png"
python3 - "$out" <<'PY'
import csv, json, sys
out = sys.argv[1]
rows = ["| heads | with gradient penalty (λ 10) | without |", "| --- | --- | --- |"]
for heads in (1, 8, 32, 64):
    cells = []
    for gp in (10, 0):
        name = f"heads{heads}_gp{gp}"
        i = json.load(open(f"{out}/{name}.json"))["imitation"]
        m = list(csv.DictReader(open(f"{out}/{name}/metrics.csv")))[-1]
        progress = f"{i['progress']:.2f}" if i.get("progress") is not None else "—"
        cells.append(f"{i['error_mean']:.3f} ± {i['error_std']:.3f} m, progress {progress}, down {i['down']} "
                     f"({float(m['samples']) / 1e6:.2f} M samples, {float(m['wall_s']):.0f} s)")
    rows.append(f"| {heads} | " + " | ".join(cells) + " |")
table = "\n".join(rows) + "\n"
open(f"{out}/table.md", "w").write(table)
print(table)
PY
