#!/usr/bin/env bash
# Seed 004 §6's recovery with the get-ups (docs/interactive.md), from the built mimic (build/):
#
#   scripts/recovery.sh curve     the walk under seed 004's cubes, the fraction of the time
#                                 performing without and with the get-ups:
#                                 docs/data/recovery_WALK.json and docs/figures/recovery_WALK.png
#                                 (about 15 min on one core)
#   scripts/recovery.sh session   the scripted session: the walk pushed down, got up by a get-up,
#                                 walking on (docs/videos/recovery_session.mp4 and its events)
#   scripts/recovery.sh standing  the walk started where a recovery hands it back, the get-up
#                                 clips' last 0.3 s: the shipped walk and the walk fine-tuned with
#                                 them as start clips (`--start-clips CLIP@-0.3`), 20 episodes from
#                                 each: docs/data/standing_*.json. The fine-tune is
#                                 models/humanoid_walk_iccgan_from_standing, made by its one command
#                                 into runs/ where it is not there (1.5·10^6 samples, about 45 min
#                                 at one thread; a run already there is resumed)
#   scripts/recovery.sh walk      models/humanoid_walk_iccgan_after_getups, the walk a recovery hands
#                                 the character back to: the shipped walk fine-tuned (1.5·10^6
#                                 samples, about 20 min at two threads) to set off from where the
#                                 get-ups actually leave a character, the 0.3 s before each hand-back
#                                 of 40 recorded sessions (the shipped walk pushed down, got up;
#                                 seeds 1-40: runs/getup_ends/, `mimic play --motion`), and from
#                                 where the get-up clips end (their last 0.3 s); trained into
#                                 runs/humanoid_walk_iccgan_after_getups (resumed where stopped)
#   scripts/recovery.sh handbacks where the get-ups hand a character back in 30 sessions not trained
#                                 on (seeds 101-130, recorded as the walk part records its own):
#                                 the shipped walk, the walk from standing and WALK started there,
#                                 as many episodes of 10 s as there are hand-backs, each from a
#                                 random one (docs/data/handbacks_WALK.json: the failure rate)
#   scripts/recovery.sh           curve and session
#
# The get-ups are GETUPS (default: models/humanoid_getup_facedown and models/humanoid_getup_faceup,
# the zoo's: scripts/zoo.sh makes them); the walk is WALK (default
# models/humanoid_walk_iccgan_after_getups, the walk that sets off from where they leave it). A
# skill is named by its directory (a run's RUN/model by its run), so theirs must differ. MIMIC names
# another mimic binary (default build/src/mimic).
set -euo pipefail
cd "$(dirname "$0")/.."
export OPENBLAS_CORETYPE=${OPENBLAS_CORETYPE:-Haswell}
mimic=${MIMIC:-build/src/mimic}
walk=${WALK:-models/humanoid_walk_iccgan_after_getups}
motions=${MIMIC_DATA:-../shared/data}/deepmimic/motions
read -r -a getups <<<"${GETUPS:-models/humanoid_getup_facedown models/humanoid_getup_faceup}"
parts=("$@")
[[ ${#parts[@]} -gt 0 ]] || parts=(curve session)
if [[ " ${parts[*]} " =~ \ (curve|session|walk|handbacks)\  ]]; then
  for g in "${getups[@]}"; do
    [[ -f $g/networks.mimic ]] || { echo "recovery.sh: no get-up model in $g (scripts/zoo.sh makes them)" >&2; exit 2; }
  done
fi
if [[ " ${parts[*]} " =~ \ (curve|session|handbacks)\  && ! -f $walk/networks.mimic ]]; then
  echo "recovery.sh: no walk model in $walk (scripts/recovery.sh walk makes the default one)" >&2
  exit 2
fi
# A skill's name: its directory's, a run's RUN/model its run's (as mimic names skills).
skill_name() {
  local name
  name=$(basename "$1")
  [[ $name == model ]] && name=$(basename "$(dirname "$1")")
  echo "$name"
}
# Sessions of the shipped walk pushed down and got up, seeds FIRST to LAST, recorded into DIR where
# not there (their motion and events: session_SEED.mclip and .json); prints each hand-back as
# "DIR/session_SEED.mclip TIME" (the seconds of its "recovered" event).
record_handbacks() {
  local dir=$1 seed t
  mkdir -p "$dir"
  printf '%s\n' "# the walk pushed down" "2.0 p" "2.2 p" "2.4 p" "2.6 p" >"$dir/pushes.txt"
  for seed in $(seq "$2" "$3"); do
    [[ -f $dir/session_$seed.json ]] ||
      "$mimic" play models/humanoid_walk_iccgan --recover "${getups[@]}" --headless --script "$dir/pushes.txt" --seconds 20 \
        --push-force 900 --seed "$seed" --motion "$dir/session_$seed.mclip" --json "$dir/session_$seed.json" >/dev/null
    sed -n 's/.*"t": \([0-9.]*\), "event": "recovered".*/\1/p' "$dir/session_$seed.json" |
      while read -r t; do echo "$dir/session_$seed.mclip $t"; done
  done
}
mkdir -p docs/data docs/figures docs/videos
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for part in "${parts[@]}"; do
  case $part in
    curve)
      name=$(skill_name "$walk")
      "$mimic" eval "$walk" --episodes 1 --trials 1 --robustness 0,10,20,30,40 \
        --recover "$(IFS=,; echo "${getups[*]}")" --robustness-trials 10 --robustness-seconds 20 --json "docs/data/recovery_$name.json"
      "$mimic" plot "docs/data/recovery_$name.json" --y performing -o "docs/figures/recovery_$name.png"
      ;;
    session)
      script=$tmp/$part.txt
      # Walk; three hard pushes put it down; the get-up takes over; the walk takes it back.
      printf '%s\n' "# walk, pushed down, gets up, walks on" "2.0 p" "2.2 p" "2.4 p" "2.6 p" >"$script"
      "$mimic" play "$walk" --recover "${getups[@]}" --headless --script "$script" --seconds 20 \
        --push-force 900 -o docs/videos/recovery_session.mp4 --json docs/data/recovery_session.json
      ;;
    standing)
      # The walk from standing where it is not in models/ yet: its one command (models/README.md).
      fine=models/humanoid_walk_iccgan_from_standing
      if [[ ! -f $fine/networks.mimic ]]; then
        run=runs/humanoid_walk_iccgan_from_standing
        if [[ ! -f $run/config.yaml ]]; then
          "$mimic" imitate "$motions/humanoid3d_walk.txt" --from models/humanoid_walk_iccgan --samples 1500000 \
            --start-clips "$motions/humanoid3d_getup_faceup.txt@-0.3" "$motions/humanoid3d_getup_facedown.txt@-0.3" -o "$run" --threads 1
        elif [[ ! -f $run/model/networks.mimic ]]; then
          "$mimic" imitate --resume -o "$run"
        fi
        fine=$run/model
      fi
      # Both walks started from the get-up ends the fine-tune trained with (its start_clips/).
      for who in shipped fine_tuned; do
        model=models/humanoid_walk_iccgan
        [[ $who == fine_tuned ]] && model=$fine
        for side in faceup facedown; do
          "$mimic" eval "$model" --episodes 20 --trials 1 --set "env.start_clips=[$fine/start_clips/humanoid3d_getup_$side.mclip]" \
            --set env.start_clip_share=1 --json "docs/data/standing_${who}_from_${side}.json"
        done
      done
      # The fine-tune's own walk, by the imitation protocol.
      "$mimic" eval "$fine" --episodes 1 --trials 20 --clip "$motions/humanoid3d_walk.txt" --json docs/data/standing_fine_tuned_style.json
      ;;
    walk)
      ends=runs/getup_ends
      run=runs/humanoid_walk_iccgan_after_getups
      if [[ ! -f $run/config.yaml ]]; then
        starts=("$motions/humanoid3d_getup_faceup.txt@-0.3" "$motions/humanoid3d_getup_facedown.txt@-0.3")
        # The 0.3 s that end 0.1 s before each hand-back (the get-up's, before the walk acts).
        while read -r clip t; do
          starts+=("$clip@$(awk -v t="$t" 'BEGIN {printf "%.4f:%.4f", t - 0.4, t - 0.1}')")
        done < <(record_handbacks "$ends" 1 40)
        echo "recovery.sh: $((${#starts[@]} - 2)) hand-backs in 40 sessions, and the get-up clips' ends"
        "$mimic" imitate "$motions/humanoid3d_walk.txt" --from models/humanoid_walk_iccgan --samples 1500000 \
          --start-clips "${starts[@]}" -o "$run"
      elif [[ ! -f $run/model/networks.mimic ]]; then
        "$mimic" imitate --resume -o "$run"
      fi
      model=models/humanoid_walk_iccgan_after_getups
      mkdir -p "$model"
      cp -r "$run/model/." "$model/"
      for f in eval.json report.md curves.png video.mp4; do cp "$run/$f" "$model/"; done
      echo "recovery.sh: $model made"
      ;;
    handbacks)
      held=runs/getup_ends_held_out
      starts=()
      while read -r clip t; do
        cut=$held/handback_$((${#starts[@]} + 1)).mclip
        "$mimic" motion convert "$clip" --start "$(awk -v t="$t" 'BEGIN {print t - 0.4}')" \
          --end "$(awk -v t="$t" 'BEGIN {print t - 0.1}')" -o "$cut" >/dev/null
        starts+=("$cut")
      done < <(record_handbacks "$held" 101 130)
      echo "recovery.sh: ${#starts[@]} hand-backs in 30 sessions"
      for w in models/humanoid_walk_iccgan models/humanoid_walk_iccgan_from_standing "$walk"; do
        "$mimic" eval "$w" --episodes "${#starts[@]}" --trials 1 --set "env.start_clips=[$(IFS=,; echo "${starts[*]}")]" \
          --set env.start_clip_share=1 --json "docs/data/handbacks_$(skill_name "$w").json"
      done
      ;;
    *) echo "recovery.sh: unknown part '$part' (curve, session, standing, walk, handbacks)" >&2; exit 2 ;;
  esac
done
