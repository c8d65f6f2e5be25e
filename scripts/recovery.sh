#!/usr/bin/env bash
# Seed 004 §6's recovery with the get-ups (docs/interactive.md), from the built mimic (build/):
#
#   scripts/recovery.sh curve     the shipped walk under seed 004's cubes, the fraction of the time
#                                 performing without and with the get-ups: docs/data/recovery.json
#                                 and docs/figures/recovery.png (about 15 min on one core)
#   scripts/recovery.sh session   the scripted session: the walk pushed down, got up by a get-up,
#                                 walking on (docs/videos/recovery_session.mp4 and its events)
#   scripts/recovery.sh           both
#
# The get-ups are GETUPS (default: models/humanoid_getup_facedown and models/humanoid_getup_faceup,
# the zoo's: scripts/zoo.sh makes them). A skill is named by its directory, so theirs must differ
# (two runs' `model` directories collide: link them under other names).
set -euo pipefail
cd "$(dirname "$0")/.."
export OPENBLAS_CORETYPE=${OPENBLAS_CORETYPE:-Haswell}
mimic=build/src/mimic
read -r -a getups <<<"${GETUPS:-models/humanoid_getup_facedown models/humanoid_getup_faceup}"
for g in "${getups[@]}"; do
  [[ -f $g/networks.mimic ]] || { echo "recovery.sh: no get-up model in $g (scripts/zoo.sh makes them)" >&2; exit 2; }
done
parts=("$@")
[[ ${#parts[@]} -gt 0 ]] || parts=(curve session)
mkdir -p docs/data docs/figures docs/videos
for part in "${parts[@]}"; do
  case $part in
    curve)
      "$mimic" eval models/humanoid_walk_iccgan --episodes 1 --trials 1 --robustness 0,10,20,30,40 \
        --recover "$(IFS=,; echo "${getups[*]}")" --robustness-trials 10 --robustness-seconds 20 --json docs/data/recovery.json
      "$mimic" plot docs/data/recovery.json --y performing -o docs/figures/recovery.png
      ;;
    session)
      script=$(mktemp)
      trap 'rm -f "$script"' EXIT
      # Walk; three hard pushes put it down; the get-up takes over; the walk takes it back.
      printf '%s\n' "# walk, pushed down, gets up, walks on" "2.0 p" "2.2 p" "2.4 p" "2.6 p" >"$script"
      "$mimic" play models/humanoid_walk_iccgan --recover "${getups[@]}" --headless --script "$script" --seconds 20 \
        --push-force 900 -o docs/videos/recovery_session.mp4 --json docs/data/recovery_session.json
      ;;
    *) echo "recovery.sh: unknown part '$part' (curve, session)" >&2; exit 2 ;;
  esac
done
