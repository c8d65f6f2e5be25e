#!/usr/bin/env bash
# Skills trained to take over (docs/interactive.md): a shipped skill fine-tuned with a share of its
# episodes started from the other shipped skills' clips (`mimic imitate --start-clips`;
# `env.start_clip_share`), into runs/switch_SKILL_shareNN (a run already there is resumed), then
# the transition test of the four skills with it in the shipped one's place, into
# docs/data/transitions_switch_SKILL_shareNN.json (the shipped four's is docs/data/transitions.json),
# and its imitation of its own clip into switch_SKILL_style_shareNN.json.
#
#   scripts/switching.sh [SKILL] [SHARE] [held]    train (or resume) and measure; SKILL walk (the
#                                                  default), run, kick or punch; SHARE 0.75 (the
#                                                  default, as mimic imitate's: 1.5·10^6 samples)
#                                                  or 0.25 (2·10^6); held: the exploration noise
#                                                  held at sigma = e^-1.66 (as --task heading's
#                                                  fine-tunes), not the skill's own, into
#                                                  runs/switch_SKILL_shareNN_held
#   scripts/switching.sh measure [SKILL] [SHARE] [held]  measure what the run holds now (its model,
#                                                  or the run's last checkpoint where it was stopped
#                                                  before the end)
#
# The training takes 30-40 min at one thread; the measurement about 10 min.
set -euo pipefail
cd "$(dirname "$0")/.."
data=${MIMIC_DATA:-../shared/data}
mimic=${MIMIC:-build/src/mimic}
motions=$data/deepmimic/motions
measure=false
[ "${1:-}" = measure ] && { measure=true; shift; }
skill_name=walk
case ${1:-} in walk|run|kick|punch) skill_name=$1; shift ;; esac
share=${1:-0.75}
[ $# -gt 0 ] && shift
held=false
case ${1:-} in held) held=true ;; '') ;; *) echo "switching.sh: the last argument is held or nothing" >&2; exit 1 ;; esac
case $share in
  0.25) samples=2000000 ;;
  0.75) samples=1500000 ;;
  *) echo "switching.sh: SKILL is walk, run, kick or punch; SHARE is 0.25 or 0.75" >&2; exit 1 ;;
esac
# The shipped skills, and the clips they imitate.
declare -A shipped=([walk]=models/humanoid_walk_iccgan [run]=models/humanoid_run_iccgan_straight_loop
                    [kick]=models/humanoid_kick_iccgan_total [punch]=models/humanoid_punch_iccgan_annealed)
others=() starts=()
for k in walk run kick punch; do
  [ "$k" = "$skill_name" ] && continue
  others+=("${shipped[$k]}")
  starts+=("$motions/humanoid3d_$k.txt")
done
name=switch_${skill_name}_share${share#0.}
# Held: the noise as --task heading's fine-tunes hold it (the share of 0.75 left to mimic imitate's default).
if $held; then
  name=${name}_held
  settings=(--set policy.log_std=-1.66 --set policy.learn_std=false)
  [ "$share" = 0.75 ] || settings+=(--set "env.start_clip_share=$share")
else
  settings=(--set "env.start_clip_share=$share")
fi
run=runs/$name
export OPENBLAS_CORETYPE=${OPENBLAS_CORETYPE:-Haswell}
[ -x "$mimic" ] || { echo "switching.sh: build mimic first (cmake --preset default && cmake --build --preset default)" >&2; exit 1; }
[ -f "$motions/humanoid3d_walk.txt" ] || { echo "switching.sh: the shared data is not at $data (set MIMIC_DATA)" >&2; exit 1; }

if ! $measure; then
  if [ ! -f "$run/config.yaml" ]; then
    "$mimic" imitate "$motions/humanoid3d_$skill_name.txt" --from "${shipped[$skill_name]}" -o "$run" --samples $samples --threads 1 \
      "${settings[@]}" --start-clips "${starts[@]}"
  elif [ ! -f "$run/model/networks.mimic" ]; then
    "$mimic" imitate --resume -o "$run"
  fi
fi
skill=$run/model
[ -f "$skill/networks.mimic" ] || skill=$run
mkdir -p docs/data
style=switch_${skill_name}_style_share${share#0.}
$held && style=${style}_held
"$mimic" eval "$skill" --episodes 1 --trials 1 --transitions "$(IFS=,; echo "${others[*]}")" \
  --transition-trials 10 --transition-taus=-0.6,-0.4,-0.2,0,0.2,0.4,0.6,0.8,1 --json "docs/data/transitions_$name.json"
"$mimic" eval "$skill" --episodes 1 --trials 20 --clip "$motions/humanoid3d_$skill_name.txt" --json "docs/data/$style.json"
echo "wrote docs/data/transitions_$name.json and $style.json (measured: $skill)"
