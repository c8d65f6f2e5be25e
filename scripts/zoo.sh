#!/usr/bin/env bash
# The model zoo: every shipped skill made by its one command (models/README.md lists them), in
# runs/zoo/<name>. A run that is not there is started, one that was stopped is resumed, and a
# finished run's model (self-contained: clips, demonstrations, character), eval.json, report.md,
# curves.png and video.mp4 are copied into models/<name>/.
#
#   scripts/zoo.sh                       every skill, in order (days on 2 cores: a humanoid skill is 5-9 h)
#   scripts/zoo.sh humanoid_walk         one (or several, made in the zoo's order)
#   scripts/zoo.sh -j 2 [NAME...]        two skills at a time, one thread each, each writing its
#                                        output to runs/zoo/<name>.log (on 2 cores, more samples an
#                                        hour than one skill on both: the two get-ups made 2 x 845
#                                        samples/s so, one of them 1,520 alone at two threads)
#   scripts/zoo.sh --list                the commands, without running them
#
# The run, the punch and the walk from standing start from the zoo's walk (`--from`), so they wait
# for it (or use runs/zoo/humanoid_walk/model where the walk is not asked for). The walk from
# standing is the walk fine-tuned to set off from where a get-up ends (the get-up clips' last
# 0.3 s as start clips): the walk a recovery hands the character back to (docs/interactive.md).
# The CMU walk is another performer's (subject 131's stylised walk, retargeted by its built-in
# map): a clip the recipe was not tuned on, whose error is set beside the DeepMimic walk's.
# Ctrl-C saves the running runs; the same command goes on from them. Started in the background
# (nohup scripts/zoo.sh ... &), where Ctrl-C's signal is ignored, `kill -TERM` its pid does the
# same, one skill at a time or several. MIMIC names another mimic binary (default build/src/mimic,
# built first).
set -euo pipefail
cd "$(dirname "$0")/.."
data=${MIMIC_DATA:-../shared/data}
motions=$data/deepmimic/motions
mimic=${MIMIC:-build/src/mimic}

# name -> the arguments of its one command (after `mimic`); -o runs/zoo/<name> is added.
declare -A command=(
  [humanoid_walk]="imitate $motions/humanoid3d_walk.txt"
  [humanoid_walk_tracking]="imitate $motions/humanoid3d_walk.txt --method tracking --samples 5000000"
  [humanoid_run]="imitate $motions/humanoid3d_run.txt --from runs/zoo/humanoid_walk/model"
  [humanoid_kick]="imitate $motions/humanoid3d_kick.txt"
  [humanoid_punch]="imitate $motions/humanoid3d_punch.txt --from runs/zoo/humanoid_walk/model"
  [humanoid_walk_from_standing]="imitate $motions/humanoid3d_walk.txt --from runs/zoo/humanoid_walk/model --samples 1500000 --start-clips $motions/humanoid3d_getup_facedown.txt@-0.3 $motions/humanoid3d_getup_faceup.txt@-0.3"
  [humanoid_cmu_walk]="imitate $data/cmu-bvh/131_01.bvh"
  [humanoid_getup_facedown]="imitate $motions/humanoid3d_getup_facedown.txt"
  [humanoid_getup_faceup]="imitate $motions/humanoid3d_getup_faceup.txt"
  [humanoid_jumping_jack]="imitate runs/zoo/jumping_jack.mclip"
  [dog_trot]="imitate $motions/dog3d_trot.txt --character $data/deepmimic/characters/dog3d.txt --method tracking"
  [walker_ppo]="train configs/walker_ppo.yaml"
)
order=(humanoid_walk humanoid_run humanoid_kick humanoid_punch humanoid_walk_from_standing humanoid_cmu_walk
       humanoid_getup_facedown humanoid_getup_faceup humanoid_jumping_jack humanoid_walk_tracking dog_trot walker_ppo)
# name -> the zoo skill whose model it starts from.
declare -A needs=([humanoid_run]=humanoid_walk [humanoid_punch]=humanoid_walk [humanoid_walk_from_standing]=humanoid_walk)

jobs=1
asked=()
while [[ $# -gt 0 ]]; do
  case $1 in
    --list)
      for name in "${order[@]}"; do echo "mimic ${command[$name]} -o runs/zoo/$name"; done
      exit 0
      ;;
    -j)
      [[ ${2:-} =~ ^[1-9][0-9]*$ ]] || { echo "zoo.sh: -j takes a number of skills at a time (1 or more)" >&2; exit 2; }
      jobs=$2
      shift 2
      ;;
    -*) echo "zoo.sh: unknown option '$1' (--list, -j N)" >&2; exit 2 ;;
    *)
      [[ -n ${command[$1]:-} ]] || { echo "zoo.sh: no skill '$1' (known: ${order[*]})" >&2; exit 2; }
      asked+=("$1")
      shift
      ;;
  esac
done
[[ ${#asked[@]} -gt 0 ]] || asked=("${order[@]}")
names=()  # the asked ones, in the zoo's order
for name in "${order[@]}"; do [[ " ${asked[*]} " == *" $name "* ]] && names+=("$name"); done
for name in "${names[@]}"; do
  dep=${needs[$name]:-}
  if [[ -n $dep && " ${names[*]} " != *" $dep "* && ! -f runs/zoo/$dep/model/networks.mimic ]]; then
    echo "zoo.sh: $name starts from $dep's model, which is not made yet: scripts/zoo.sh $dep $name" >&2
    exit 2
  fi
done

if [[ -z ${ZOO_PREPARED:-} ]]; then
  if [[ -z ${MIMIC:-} ]]; then
    cmake --preset default >/dev/null
    cmake --build --preset default -j "$(nproc)" --target mimic
  fi
  export OPENBLAS_CORETYPE=Haswell
  mkdir -p runs/zoo
  # The built-in jumping jack as a file (`mimic demo` writes it).
  [[ -f runs/zoo/jumping_jack.mclip ]] ||
    { $mimic demo --no-video --train-iterations 0 -o runs/zoo/builtin >/dev/null && cp runs/zoo/builtin/jumping_jack.mclip runs/zoo/; }
fi

# One skill: its run started or resumed (with ZOO_THREADS collection threads where set), then its
# model and figures copied into models/<name>/.
make_one() {
  local name=$1 run=runs/zoo/$1 args threads=()
  [[ -n ${ZOO_THREADS:-} ]] && threads=(--threads "$ZOO_THREADS")
  read -r -a args <<<"${command[$name]}"
  if [[ ${args[0]} == train ]]; then
    if [[ -f $run/checkpoint.pt ]]; then
      $mimic train --resume -o "$run" "${threads[@]}"
    else
      $mimic train "${args[@]:1}" -o "$run" "${threads[@]}"
    fi
    $mimic export "$run" -o "$run/model"
  elif [[ -d $run ]]; then
    $mimic imitate --resume -o "$run" "${threads[@]}"
  else
    $mimic "${args[@]}" -o "$run" "${threads[@]}"
  fi
  mkdir -p "models/$name"
  cp -r "$run/model/." "models/$name/"
  for f in eval.json report.md curves.png video.mp4; do [[ -f $run/$f ]] && cp "$run/$f" "models/$name/"; done
  echo "zoo.sh: models/$name from: mimic ${command[$name]} -o $run"
}

# A skill's own process (started by the scheduler below): its run, then its model.
if [[ -n ${ZOO_SKILL:-} ]]; then
  for name in "${names[@]}"; do make_one "$name"; done
  exit 0
fi

# The scheduler, one skill at a time or -j. Each skill runs as this script for that skill alone
# (ZOO_SKILL), in a session of its own, so that Ctrl-C or a TERM reaches this scheduler only, which
# asks each running skill once to save and stop. (A run in this script's own foreground would not
# hear a TERM sent to the script, and would go on after it.) Several at a time: one thread each,
# each skill's output in runs/zoo/<name>.log; one at a time: the machine's threads, the output here.
declare -A name_of=()  # pid -> name, while it runs
declare -A result=()   # name -> exit status, once it ended
pending=("${names[@]}")
stopping=0  # 128 + the signal that stopped the zoo, once one came
failed=0
# shellcheck disable=SC2317  # (called by the traps)
stop_all() {
  stopping=$1
  local p
  for p in "${!name_of[@]}"; do kill -INT -- "-$p" 2>/dev/null || true; done
}
trap 'stop_all 130' INT
trap 'stop_all 143' TERM
while :; do
  if ((stopping == 0)); then
    waiting=()
    for name in "${pending[@]}"; do
      dep=${needs[$name]:-}
      dep_state=ready
      if [[ -n $dep && " ${names[*]} " == *" $dep "* ]]; then
        if [[ -z ${result[$dep]+x} ]]; then dep_state=waiting; elif [[ ${result[$dep]} != 0 ]]; then dep_state=failed; fi
      fi
      if [[ $dep_state == failed ]]; then
        echo "zoo.sh: $name not made: $dep, which it starts from, did not finish"
        failed=1
      elif [[ $dep_state == waiting || ${#name_of[@]} -ge $jobs ]]; then
        waiting+=("$name")
      else
        if ((jobs == 1)); then
          ZOO_PREPARED=1 ZOO_SKILL=1 setsid "$0" "$name" </dev/null &
          where=""
        else
          ZOO_PREPARED=1 ZOO_SKILL=1 ZOO_THREADS=1 setsid "$0" "$name" >>"runs/zoo/$name.log" 2>&1 </dev/null &
          where="; its output: runs/zoo/$name.log"
        fi
        name_of[$!]=$name
        echo "zoo.sh: $name started (pid $!$where)"
      fi
    done
    pending=("${waiting[@]}")
  fi
  ((${#name_of[@]} > 0)) || break
  pid=
  if wait -n -p pid; then status=0; else status=$?; fi
  [[ -n ${pid:-} && -n ${name_of[$pid]:-} ]] || continue  # a signal, not an end
  name=${name_of[$pid]}
  unset "name_of[$pid]"
  result[$name]=$status
  if ((status == 0)); then
    echo "zoo.sh: $name made: models/$name"
  elif ((stopping)); then
    echo "zoo.sh: $name stopped and saved; the same command goes on from it"
  else
    where="runs/zoo/$name.log"
    ((jobs > 1)) || where="its output above"
    echo "zoo.sh: $name failed (exit $status): see $where"
    failed=1
  fi
done
((stopping == 0)) || exit "$stopping"
exit "$failed"
