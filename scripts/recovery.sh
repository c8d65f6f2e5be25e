#!/usr/bin/env bash
# Seed 004 §6's recovery with the get-ups (docs/interactive.md), from the built mimic (build/):
#
#   scripts/recovery.sh curve     the walk under seed 004's cubes, the fraction of the time
#                                 performing without and with the get-ups: docs/data/recovery.json
#                                 and docs/figures/recovery.png (about 15 min on one core)
#   scripts/recovery.sh session   the scripted session: the walk pushed down, got up by a get-up,
#                                 walking on (docs/videos/recovery_session.mp4 and its events)
#   scripts/recovery.sh standing  the walk started where a recovery hands it back: the get-up
#                                 clips' last 0.3 s (runs/standing/), the shipped walk and the walk
#                                 fine-tuned with them as start clips (`--start-clips CLIP@-0.3`;
#                                 the zoo's humanoid_walk_from_standing; runs/walk_from_getup_ends,
#                                 1.5·10^6 samples, about 45 min at one thread; a run already there
#                                 is resumed), 20 episodes from each: docs/data/standing_*.json
#   scripts/recovery.sh           curve and session
#
# The get-ups are GETUPS (default: models/humanoid_getup_facedown and models/humanoid_getup_faceup,
# the zoo's: scripts/zoo.sh makes them); the walk is WALK (default models/humanoid_walk_iccgan). A
# skill is named by its directory (a run's RUN/model by its run), so theirs must differ.
set -euo pipefail
cd "$(dirname "$0")/.."
export OPENBLAS_CORETYPE=${OPENBLAS_CORETYPE:-Haswell}
mimic=build/src/mimic
walk=${WALK:-models/humanoid_walk_iccgan}
motions=${MIMIC_DATA:-../shared/data}/deepmimic/motions
read -r -a getups <<<"${GETUPS:-models/humanoid_getup_facedown models/humanoid_getup_faceup}"
parts=("$@")
[[ ${#parts[@]} -gt 0 ]] || parts=(curve session)
if [[ " ${parts[*]} " == *" curve "* || " ${parts[*]} " == *" session "* ]]; then
  for g in "${getups[@]}"; do
    [[ -f $g/networks.mimic ]] || { echo "recovery.sh: no get-up model in $g (scripts/zoo.sh makes them)" >&2; exit 2; }
  done
fi
mkdir -p docs/data docs/figures docs/videos
for part in "${parts[@]}"; do
  case $part in
    curve)
      "$mimic" eval "$walk" --episodes 1 --trials 1 --robustness 0,10,20,30,40 \
        --recover "$(IFS=,; echo "${getups[*]}")" --robustness-trials 10 --robustness-seconds 20 --json docs/data/recovery.json
      "$mimic" plot docs/data/recovery.json --y performing -o docs/figures/recovery.png
      ;;
    session)
      script=$(mktemp)
      trap 'rm -f "$script"' EXIT
      # Walk; three hard pushes put it down; the get-up takes over; the walk takes it back.
      printf '%s\n' "# walk, pushed down, gets up, walks on" "2.0 p" "2.2 p" "2.4 p" "2.6 p" >"$script"
      "$mimic" play "$walk" --recover "${getups[@]}" --headless --script "$script" --seconds 20 \
        --push-force 900 -o docs/videos/recovery_session.mp4 --json docs/data/recovery_session.json
      ;;
    standing)
      mkdir -p runs/standing
      ends=()
      for side in faceup facedown; do
        clip=$motions/humanoid3d_getup_$side.txt
        seconds=$("$mimic" motion info "$clip" | awk '/^frames/ {for (i = 1; i < NF; ++i) if ($(i + 1) == "s,") print $i}')
        end=runs/standing/getup_${side}_end.mclip
        "$mimic" motion convert "$clip" --start "$(awk -v s="$seconds" 'BEGIN {printf "%.3f", s - 0.3}')" -o "$end"
        ends+=("$end")
      done
      run=runs/walk_from_getup_ends
      if [[ ! -f $run/config.yaml ]]; then
        "$mimic" imitate "$motions/humanoid3d_walk.txt" --from "$walk" -o "$run" --samples 1500000 --threads 1 \
          --start-clips "$motions/humanoid3d_getup_faceup.txt@-0.3" "$motions/humanoid3d_getup_facedown.txt@-0.3"
      elif [[ ! -f $run/model/networks.mimic ]]; then
        "$mimic" imitate --resume -o "$run"
      fi
      for who in shipped fine_tuned; do
        model=$walk
        [[ $who == fine_tuned ]] && model=$run/model
        for side in faceup facedown; do
          "$mimic" eval "$model" --episodes 20 --trials 1 --set "env.start_clips=[runs/standing/getup_${side}_end.mclip]" \
            --set env.start_clip_share=1 --json "docs/data/standing_${who}_from_${side}.json"
        done
      done
      # The fine-tune's own walk, by the imitation protocol.
      "$mimic" eval "$run/model" --episodes 1 --trials 20 --clip "$motions/humanoid3d_walk.txt" --json docs/data/standing_fine_tuned_style.json
      ;;
    *) echo "recovery.sh: unknown part '$part' (curve, session, standing)" >&2; exit 2 ;;
  esac
done
