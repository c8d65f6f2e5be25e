#!/usr/bin/env bash
# Seed 004 Fig. 7 on the walk with more trials than the models' own eval.json (20 a mass, ±7–16
# frames of standard error): the tracking model, the ICCGAN model, and the ICCGAN model as it was at
# 7.96 M samples (read out of git: commit 5900f38 replaced it). Resumable: an evaluation whose JSON
# exists is kept. Usage: scripts/walk_robustness.sh [OUT_DIR] [FIGURE.png]  (figure: OUT_DIR/walk_robustness.png)
# TRIALS (default 100) trials per mass; MASSES (default 5,10,20: the masses where the models
# differ; no cubes and 1 kg are in the models' eval.json). About 4 min a model at 100 trials on one
# core. Needs ../shared/data.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-runs/walk_robustness}
figure=${2:-$out/walk_robustness.png}
trials=${TRIALS:-100}
masses=${MASSES:-5,10,20}
mimic=${MIMIC:-build/src/mimic}
clip=../shared/data/deepmimic/motions/humanoid3d_walk.txt
[ -f "$clip" ] || { echo "needs $clip (../shared/data beside the repository)" >&2; exit 1; }
mkdir -p "$out/iccgan_7.96M"
if [ ! -f "$out/iccgan_7.96M/checkpoint.pt" ]; then
  for f in checkpoint.pt config.yaml; do git show "5900f38^:models/humanoid_walk_iccgan/$f" > "$out/iccgan_7.96M/$f"; done
fi
declare -A models=([tracking]=models/humanoid_walk_tracking [iccgan]=models/humanoid_walk_iccgan [iccgan_7.96M]="$out/iccgan_7.96M")
for name in tracking iccgan iccgan_7.96M; do
  json="$out/$name.json"
  [ -f "$json" ] && continue
  # mimic eval writes its JSON atomically at the end: a killed evaluation leaves none to skip.
  "$mimic" eval "${models[$name]}" --clip "$clip" --episodes 1 --trials 1 --robustness "$masses" \
    --robustness-trials "$trials" --json "$json" > "$out/$name.log" 2>&1
done
"$mimic" plot "$out/tracking.json" "$out/iccgan.json" "$out/iccgan_7.96M.json" \
  --names "tracking, 19.5 M samples" "ICCGAN, 20.0 M samples" "ICCGAN, 7.96 M samples" \
  --title "walk: frames survived against cubes, $trials trials a mass" -o "$figure"
python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
masses = [r["mass"] for r in json.load(open(f"{out}/tracking.json"))["robustness"]]
print("frames survived, mean ± standard error of the mean")
print("| policy | " + " | ".join(f"{m:g} kg" for m in masses) + " |")
print("| --- |" + " --- |" * len(masses))
for name in ("tracking", "iccgan", "iccgan_7.96M"):
    r = json.load(open(f"{out}/{name}.json"))["robustness"]
    print(f"| {name} | " + " | ".join(f"{x['frames_mean']:.1f} ± {x['frames_std'] / x['trials'] ** 0.5:.1f}" for x in r) + " |")
PY
