#!/usr/bin/env bash
# Skills trained to take over (docs/interactive.md): the shipped walk fine-tuned with a share of
# its episodes started from the other shipped skills' clips (`mimic imitate --start-clips`: the
# run, the kick and the punch; `env.start_clip_share`), into runs/switch_walk_shareNN (a run
# already there is resumed), then the transition test of the four skills with it in the shipped
# walk's place, into docs/data/transitions_switch_walk_shareNN.json (the shipped four's is
# docs/data/transitions.json), and its imitation of the walk into switch_walk_style_shareNN.json.
#
#   scripts/switching.sh [SHARE]           train (or resume) and measure; SHARE 0.75 (the
#                                          default, as mimic imitate's: 1.5·10^6 samples) or 0.25 (2·10^6)
#   scripts/switching.sh measure [SHARE]   measure what the run holds now (its model, or the
#                                          run's last checkpoint where it was stopped before the end)
#
# The training takes 30-40 min at one thread; the measurement about 10 min.
set -euo pipefail
cd "$(dirname "$0")/.."
data=${MIMIC_DATA:-../shared/data}
mimic=${MIMIC:-build/src/mimic}
motions=$data/deepmimic/motions
measure=false
[ "${1:-}" = measure ] && { measure=true; shift; }
share=${1:-0.75}
case $share in
  0.25) samples=2000000 ;;
  0.75) samples=1500000 ;;
  *) echo "switching.sh: SHARE is 0.25 or 0.75" >&2; exit 1 ;;
esac
name=switch_walk_share${share#0.}
run=runs/$name
export OPENBLAS_CORETYPE=${OPENBLAS_CORETYPE:-Haswell}
[ -x "$mimic" ] || { echo "switching.sh: build mimic first (cmake --preset default && cmake --build --preset default)" >&2; exit 1; }
[ -f "$motions/humanoid3d_walk.txt" ] || { echo "switching.sh: the shared data is not at $data (set MIMIC_DATA)" >&2; exit 1; }

if ! $measure; then
  if [ ! -f "$run/config.yaml" ]; then
    "$mimic" imitate "$motions/humanoid3d_walk.txt" --from models/humanoid_walk_iccgan -o "$run" --samples $samples --threads 1 \
      --set env.start_clip_share=$share --start-clips "$motions/humanoid3d_run.txt" "$motions/humanoid3d_kick.txt" "$motions/humanoid3d_punch.txt"
  elif [ ! -f "$run/model/networks.mimic" ]; then
    "$mimic" imitate --resume -o "$run"
  fi
fi
skill=$run/model
[ -f "$skill/networks.mimic" ] || skill=$run
mkdir -p docs/data
"$mimic" eval "$skill" --episodes 1 --trials 1 \
  --transitions models/humanoid_run_iccgan_straight_loop,models/humanoid_kick_iccgan_total,models/humanoid_punch_iccgan_annealed \
  --transition-trials 10 --transition-taus=-0.6,-0.4,-0.2,0,0.2,0.4,0.6,0.8,1 --json docs/data/transitions_$name.json
"$mimic" eval "$skill" --episodes 1 --trials 20 --clip "$motions/humanoid3d_walk.txt" --json docs/data/${name/switch_walk/switch_walk_style}.json
echo "wrote docs/data/transitions_$name.json and ${name/switch_walk/switch_walk_style}.json (measured: $skill)"
