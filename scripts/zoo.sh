#!/usr/bin/env bash
# The model zoo: every shipped skill made by its one command (models/README.md lists them), in
# runs/zoo/<name>. A run that is not there is started, one that was stopped is resumed, and a
# finished run's model (self-contained: clips, demonstrations, character), eval.json, report.md,
# curves.png and video.mp4 are copied into models/<name>/.
#
#   scripts/zoo.sh                 every skill, in order (days on 2 cores: a humanoid skill is 5-9 h)
#   scripts/zoo.sh humanoid_walk   one
#   scripts/zoo.sh --list          the commands, without running them
#
# The run, the punch and the walk from standing start from the zoo's walk (`--from`), so the walk
# comes first. The walk from standing is the walk fine-tuned to set off from where a get-up ends
# (the get-up clips' last 0.3 s as start clips): the walk a recovery hands the character back to
# (docs/interactive.md). Ctrl-C saves the run; the same command goes on from it.
set -euo pipefail
cd "$(dirname "$0")/.."
data=${MIMIC_DATA:-../shared/data}
motions=$data/deepmimic/motions
mimic=build/src/mimic

# name -> the arguments of its one command (after `mimic`); -o runs/zoo/<name> is added.
declare -A command=(
  [humanoid_walk]="imitate $motions/humanoid3d_walk.txt"
  [humanoid_run]="imitate $motions/humanoid3d_run.txt --from runs/zoo/humanoid_walk/model"
  [humanoid_kick]="imitate $motions/humanoid3d_kick.txt"
  [humanoid_punch]="imitate $motions/humanoid3d_punch.txt --from runs/zoo/humanoid_walk/model"
  [humanoid_walk_from_standing]="imitate $motions/humanoid3d_walk.txt --from runs/zoo/humanoid_walk/model --samples 1500000 --start-clips $motions/humanoid3d_getup_facedown.txt $motions/humanoid3d_getup_faceup.txt --start-clips-last 0.3"
  [humanoid_getup_facedown]="imitate $motions/humanoid3d_getup_facedown.txt"
  [humanoid_getup_faceup]="imitate $motions/humanoid3d_getup_faceup.txt"
  [humanoid_jumping_jack]="imitate runs/zoo/jumping_jack.mclip"
  [dog_trot]="imitate $motions/dog3d_trot.txt --character $data/deepmimic/characters/dog3d.txt --method tracking"
  [walker_ppo]="train configs/walker_ppo.yaml"
)
order=(humanoid_walk humanoid_run humanoid_kick humanoid_punch humanoid_walk_from_standing humanoid_getup_facedown
       humanoid_getup_faceup humanoid_jumping_jack dog_trot walker_ppo)

if [[ ${1:-} == --list ]]; then
  for name in "${order[@]}"; do echo "mimic ${command[$name]} -o runs/zoo/$name"; done
  exit 0
fi
names=("$@")
[[ ${#names[@]} -gt 0 ]] || names=("${order[@]}")
for name in "${names[@]}"; do
  [[ -n ${command[$name]:-} ]] || { echo "zoo.sh: no skill '$name' (known: ${order[*]})" >&2; exit 2; }
done

cmake --preset default >/dev/null
cmake --build --preset default -j "$(nproc)" --target mimic
export OPENBLAS_CORETYPE=Haswell
mkdir -p runs/zoo
# The built-in jumping jack as a file (`mimic demo` writes it).
[[ -f runs/zoo/jumping_jack.mclip ]] ||
  { $mimic demo --no-video --train-iterations 0 -o runs/zoo/builtin >/dev/null && cp runs/zoo/builtin/jumping_jack.mclip runs/zoo/; }

for name in "${names[@]}"; do
  run=runs/zoo/$name
  read -r -a args <<<"${command[$name]}"
  if [[ ${args[0]} == train ]]; then
    if [[ -f $run/checkpoint.pt ]]; then $mimic train --resume -o "$run"; else $mimic train "${args[@]:1}" -o "$run"; fi
    $mimic export "$run" -o "$run/model"
  elif [[ -d $run ]]; then
    $mimic imitate --resume -o "$run"
  else
    $mimic "${args[@]}" -o "$run"
  fi
  mkdir -p "models/$name"
  cp -r "$run/model/." "models/$name/"
  for f in eval.json report.md curves.png video.mp4; do [[ -f $run/$f ]] && cp "$run/$f" "models/$name/"; done
  echo "zoo.sh: models/$name from: mimic ${command[$name]} -o $run"
done
