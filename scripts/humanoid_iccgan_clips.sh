#!/usr/bin/env bash
# Seed 004 Table 2 on this project's CPU set-up: ICCGAN on DeepMimic's walk, run, kick and punch
# (configs/humanoid_<clip>_iccgan_cpu.yaml), each to the config's 5,000 iterations (20.5 M
# samples), then `mimic eval` against its clip (DESIGN.md section 5) and a 6 s video. Resumes
# whatever a previous call left: stop it (Ctrl-C) at any time and call it again. Writes
# OUT_DIR/table.md with seed 004's errors beside ours.
# Usage: scripts/humanoid_iccgan_clips.sh [OUT_DIR] [CLIP...]   (clips: walk run kick punch)
# THREADS (default 2) sets collect.threads; one clip trains at a time. About 3.3 h a clip on two
# cores. Needs ../shared/data.
#   INIT     a run or model each new clip starts from (`mimic train --init-from`; default none:
#            from scratch), e.g. models/humanoid_walk_iccgan to start the run from the walk
#   LOG_STD  `learnt` (default) or a log σ to hold the action noise at (e.g. -1.66)
#   SETS     more config overrides for new runs, KEY=VALUE separated by spaces (`mimic train --set`),
#            e.g. SETS="env.max_drift=0.5"
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-runs/iccgan_clips}
shift || true
clips=("$@")
[ ${#clips[@]} -gt 0 ] || clips=(walk run kick punch)
mimic=${MIMIC:-build/src/mimic}
threads=${THREADS:-2}
init=${INIT:-none}
log_std=${LOG_STD:-learnt}
motions=../shared/data/deepmimic/motions
[ -d "$motions" ] || { echo "needs $motions (../shared/data beside the repository)" >&2; exit 1; }
mkdir -p "$out" runs
for clip in "${clips[@]}"; do
  config=configs/humanoid_${clip}_iccgan_cpu.yaml
  [ -f "$config" ] || { echo "$config: no such config (clips: walk run kick punch)" >&2; exit 1; }
  # The configs read their demonstrations from runs/humanoid_<clip>_links_demos.csv.
  demos=runs/humanoid_${clip}_links_demos.csv
  [ -f "$demos" ] || "$mimic" record-clip configs/humanoid_walk_iccgan_links.yaml --clip "$motions/humanoid3d_$clip.txt" --passes 8 -o "$demos"
  run="$out/$clip"
  if [ -f "$run/checkpoint.pt" ]; then
    # A finished clip is not resumed again (that would only rewrite its checkpoint) nor re-evaluated.
    iterations=$(awk '/^iterations:/ {print $2}' "$run/config.yaml")
    if grep -q "^$iterations," "$run/metrics.csv" 2>/dev/null; then
      [ -f "$run.json" ] && [ -f "$run.mp4" ] && continue
    else
      "$mimic" train --resume -o "$run" --threads "$threads" >> "$run.log" 2>&1
    fi
  else
    args=("$config" -o "$run" --threads "$threads")
    [ "$init" != none ] && args+=(--init-from "$init")
    [ "$log_std" != learnt ] && args+=(--set policy.learn_std=false --set "policy.log_std=$log_std")
    for set in ${SETS:-}; do args+=(--set "$set"); done
    "$mimic" train "${args[@]}" > "$run.log" 2>&1
  fi
  "$mimic" eval "$run" --clip "$motions/humanoid3d_$clip.txt" --episodes 20 --trials 20 --latency --json "$run.json"
  "$mimic" render "$run" -o "$run.mp4" --seconds 6
done
python3 - "$out" <<'PY'
import csv, json, os, sys
out = sys.argv[1]
paper = {"walk": 0.06, "run": 0.10, "kick": 0.14, "punch": 0.09}  # seed 004 Table 2, 2e7 samples
rows = ["| clip | samples | wall (s) | imitation error (m) | seed 004 | progress | down (of 20 trials) |",
        "| --- | --- | --- | --- | --- | --- | --- |"]
for clip in paper:
    if not os.path.exists(f"{out}/{clip}.json"):
        continue
    e = json.load(open(f"{out}/{clip}.json"))
    m = list(csv.DictReader(open(f"{out}/{clip}/metrics.csv")))[-1]
    i = e["imitation"]
    progress = f"{i['progress']:.2f}" if i.get("progress") is not None else "—"
    rows.append(f"| {clip} | {float(m['samples']) / 1e6:.2f} M | {float(m['wall_s']):.0f} | "
                f"{i['error_mean']:.3f} ± {i['error_std']:.3f} | {paper[clip]:.2f} | {progress} | {i['down']} |")
table = "\n".join(rows) + "\n"
open(f"{out}/table.md", "w").write(table)
print(table)
PY
