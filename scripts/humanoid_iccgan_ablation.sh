#!/usr/bin/env bash
# Seed 004 §6.7's ablation on the humanoid walk at a reduced budget: 1 / 8 / 32 / 64 discriminator
# heads, with and without the gradient penalty, configs/humanoid_walk_iccgan_cpu.yaml otherwise.
# ITERATIONS (default 750: 3.07 M samples, where the full config begins to walk) each, then
# `mimic eval` against the walk clip. Resumes what a previous call left (Ctrl-C and call again).
# Writes OUT_DIR/table.md (imitation error and progress per cell; cells not yet run are "—") and
# learning-curve plots of the cells that exist.
# Usage: scripts/humanoid_iccgan_ablation.sh [OUT_DIR]
# THREADS (default 2) sets collect.threads. GPS (default "10 0") and HEADS (default "1 8 32 64")
# pick the cells, so two calls on disjoint cells can share a machine, one core each:
#   THREADS=1 GPS=10 scripts/humanoid_iccgan_ablation.sh & THREADS=1 GPS=0 scripts/humanoid_iccgan_ablation.sh
# SEEDS (default 1) trains each cell once per seed; seed 1's run is heads<H>_gp<G>, another seed's
# heads<H>_gp<G>_seed<S>. The table lists every seed of a cell that exists.
# With ITERATIONS=500, 22–28 min a cell on one core, two such calls side by side (docs/results/humanoid_iccgan.md
# has that run's table); needs ../shared/data.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-runs/humanoid_iccgan_ablation}
mimic=${MIMIC:-build/src/mimic}
iterations=${ITERATIONS:-750}
threads=${THREADS:-2}
gps=${GPS:-10 0}
heads_list=${HEADS:-1 8 32 64}
seeds=${SEEDS:-1}
walk=../shared/data/deepmimic/motions/humanoid3d_walk.txt
[ -f "$walk" ] || { echo "needs $walk (../shared/data beside the repository)" >&2; exit 1; }
demos=runs/humanoid_walk_links_demos.csv
mkdir -p "$out" runs
[ -f "$demos" ] || "$mimic" record-clip configs/humanoid_walk_iccgan_links.yaml --clip "$walk" --passes 8 -o "$demos"
for gp in $gps; do
  for heads in $heads_list; do
    for seed in $seeds; do
      run="$out/heads${heads}_gp${gp}$([ "$seed" = 1 ] || echo "_seed$seed")"
      echo "cell: $heads heads, penalty $gp, seed $seed -> $run"
      if [ -f "$run/checkpoint.pt" ]; then
        # --iterations again: cells started before config.yaml recorded it would go on to 5,000.
        grep -q "^$iterations," "$run/metrics.csv" ||
          "$mimic" train --resume -o "$run" --iterations "$iterations" --threads "$threads" >> "$run.log" 2>&1
      else
        "$mimic" train configs/humanoid_walk_iccgan_cpu.yaml -o "$run" --iterations "$iterations" --threads "$threads" \
          --set rewards.0.heads=$heads --set rewards.0.gradient_penalty=$gp --set seed=$seed > "$run.log" 2>&1
      fi
      # Evaluated again when the cell trained on since (a larger ITERATIONS).
      [ "$run.json" -nt "$run/checkpoint.pt" ] || "$mimic" eval "$run" --clip "$walk" --episodes 10 --trials 20 --json "$run.json"
    done
  done
done
# Curves and table of whatever cells exist, so each partial call leaves a readable summary.
for gp in 10 0; do
  runs=() names=()
  for heads in 1 8 32 64; do
    [ -f "$out/heads${heads}_gp${gp}/metrics.csv" ] && { runs+=("$out/heads${heads}_gp${gp}"); names+=("$heads head$([ "$heads" = 1 ] || echo s)"); }
  done
  [ ${#runs[@]} -gt 0 ] || continue
  label=$([ "$gp" = 0 ] && echo "no gradient penalty" || echo "gradient penalty $gp")
  for y in episode_length iccgan_policy_accuracy; do
    "$mimic" plot "${runs[@]}" --smooth 10 --y "$y" --names "${names[@]}" \
      --title "Humanoid walk, ensemble ablation ($label): $y" -o "$out/ablation_gp${gp}_$y.png"
  done
done
python3 - "$out" <<'PY'
import csv, json, os, re, sys
out = sys.argv[1]
rows = ["| heads | with gradient penalty (λ 10) | without |", "| --- | --- | --- |"]
def seed_of(name):
    m = re.search(r"_seed(\d+)$", name)
    return int(m.group(1)) if m else 1

for heads in (1, 8, 32, 64):
    cells = []
    for gp in (10, 0):
        base = f"heads{heads}_gp{gp}"
        names = sorted((f[:-5] for f in os.listdir(out) if re.fullmatch(base + r"(_seed\d+)?\.json", f)), key=seed_of)
        entries = []
        for name in names:
            i = json.load(open(f"{out}/{name}.json"))["imitation"]
            m = list(csv.DictReader(open(f"{out}/{name}/metrics.csv")))[-1]
            progress = f"{i['progress']:.2f}" if i.get("progress") is not None else "—"
            entries.append(f"seed {seed_of(name)}: {i['error_mean']:.3f} ± {i['error_std']:.3f} m, progress {progress}, "
                           f"down {i['down']} ({float(m['samples']) / 1e6:.2f} M samples, {float(m['wall_s']):.0f} s)")
        cells.append("<br>".join(entries) if entries else "—")
    rows.append(f"| {heads} | " + " | ".join(cells) + " |")
table = "\n".join(rows) + "\n"
open(f"{out}/table.md", "w").write(table)
print(table)
PY
