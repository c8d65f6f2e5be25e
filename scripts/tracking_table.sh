#!/usr/bin/env bash
# Seed 003 Tables 1 and 2 and Fig. 12 by the tracking recipe (`mimic imitate CLIP --method
# tracking`, configs/recipes/tracking.yaml, the same for every clip: no clip gets a setting of its
# own), on 2 cores: two runs at a time, one thread each, each evaluated by imitate (20 trials of
# 20 s from evenly spaced phases).
#  - <clip>: the ten clips of seed 003 Table 1 (walk run backflip cartwheel jump kick punch roll
#    spin spinkick), from RSI, the recipe's start;
#  - dog_trot: the same recipe on DeepMimic's dog (another body, seed 003 section 9);
#  - backflip_{fsi,asi5,asi10,asi20}: with backflip (RSI), Table 2 and Fig. 12 on the backflip;
#  - cartwheel_{fsi,asi10}: with cartwheel (RSI), Table 2 on the cartwheel.
# A finished run's evaluation and learning curve are kept in RESULTS (default
# docs/data/tracking_table: <name>.json and <name>.csv, its metrics.csv), which is committed, so the
# runs can be made over several sessions and machines: a run whose evaluation is there is not
# trained again, one with a checkpoint in the out dir is resumed (to this call's budget).
# Then, of the runs whose results are there: <results>/table.md (mimic table, with seed 003's
# normalised return added), <results>/{backflip,cartwheel}_init.md and the learning curves
# <figures>/{tracking_skills,backflip_init,cartwheel_init}_reward.png.
# Usage: scripts/tracking_table.sh [samples per run (default 5000000)] [out dir (default runs/tracking_table)] [NAME...]
# (NAMEs: only those runs, in the script's order). REPORT_ONLY=1 only writes the tables and figures;
# FIGURES=dir (default: RESULTS) takes the figures; MIMIC_DATA names the shared data (default ../shared/data).
set -euo pipefail
cd "$(dirname "$0")/.."
samples=${1:-5000000}
out=${2:-runs/tracking_table}
shift $(($# < 2 ? $# : 2))
asked=("$@")
mimic=${MIMIC:-build/src/mimic}
data=${MIMIC_DATA:-../shared/data}
motions=$data/deepmimic/motions
results=${RESULTS:-docs/data/tracking_table}
figures=${FIGURES:-$results}
[[ $samples =~ ^[1-9][0-9]*$ ]] || { echo "tracking_table.sh: samples per run must be a positive number, not '$samples'" >&2; exit 2; }
[ -x "$mimic" ] || { echo "tracking_table.sh: build mimic first (cmake --preset default && cmake --build --preset default)" >&2; exit 1; }
export OPENBLAS_CORETYPE=${OPENBLAS_CORETYPE:-Haswell}
mkdir -p "$out" "$results" "$figures"
clips=(walk run backflip cartwheel jump kick punch roll spin spinkick)
# Seed 003 Table 1's normalised return of each clip.
declare -A paper=([walk]=0.932 [run]=0.878 [backflip]=0.741 [cartwheel]=0.824 [jump]=0.653 [kick]=0.761 [punch]=0.831
                  [roll]=0.603 [spin]=0.779 [spinkick]=0.747)

# name -> its clip, and the one recipe value it changes (Table 2's starts) or its character.
declare -A clip_of=() set_of=() character_of=()
names=()
for c in "${clips[@]}"; do names+=("$c"); clip_of[$c]=$motions/humanoid3d_$c.txt; done
names+=(dog_trot)
clip_of[dog_trot]=$motions/dog3d_trot.txt
character_of[dog_trot]=$data/deepmimic/characters/dog3d.txt
# start NAME CLIP SETTING: a Table 2 run, CLIP from another start distribution.
start() { names+=("$1"); clip_of[$1]=$motions/humanoid3d_$2.txt; set_of[$1]=$3; }
asi() { echo "init={kind: adaptive, components: $1, episodes: 500}"; }
for c in backflip cartwheel; do start "${c}_fsi" "$c" "env.init=fixed"; done
for k in 5 10 20; do start "backflip_asi$k" backflip "$(asi "$k")"; done
start cartwheel_asi10 cartwheel "$(asi 10)"
for n in "${asked[@]}"; do
  [[ -n ${clip_of[$n]:-} ]] || { echo "tracking_table.sh: no run '$n' (known: ${names[*]})" >&2; exit 2; }
done

kept() { [[ -f $results/$1.json ]]; }

# init_report CLIP: the start-distribution comparison on CLIP (RSI: the table's run of it).
init_report() {
  local clip=$1 runs=() labels=() n
  for n in "${clip}_fsi" "$clip" "${clip}_asi5" "${clip}_asi10" "${clip}_asi20"; do
    kept "$n" || continue
    runs+=("$results/$n")
    case $n in
      *_fsi) labels+=(FSI) ;;
      *_asi*) labels+=("ASI k = ${n##*_asi}") ;;
      *) labels+=(RSI) ;;
    esac
  done
  ((${#runs[@]} > 1)) || return 0
  "$mimic" table "${runs[@]/%/.json}" --names "${labels[@]}" -o "$results/${clip}_init.md"
  "$mimic" plot "${runs[@]/%/.csv}" --names "${labels[@]}" --y reward --smooth 10 \
    --title "$clip, start distributions: reward per step (max 1)" -o "$figures/${clip}_init_reward.png"
}

# The tables and learning curves of the runs whose results are kept.
report() {
  local rows=() n
  for n in "${clips[@]}" dog_trot; do kept "$n" && rows+=("$n"); done
  if ((${#rows[@]} == 0)); then
    echo "tracking_table.sh: no run is finished yet (nothing in $results)" >&2
    return
  fi
  local runs=("${rows[@]/#/$results/}")
  # mimic table's rows, with seed 003's figure as a last column.
  "$mimic" table "${runs[@]/%/.json}" --names "${rows[@]}" -o "$results/table.md.tmp" >/dev/null
  awk -F' [|] ' -v list="$(for n in "${rows[@]}"; do echo -n "$n=${paper[$n]:-—} "; done)" '
    BEGIN { n = split(list, kv, " "); for (i = 1; i <= n; i++) { split(kv[i], p, "="); fig[p[1]] = p[2] } }
    NR == 1 { print $0 " seed 003 |"; next }
    NR == 2 { print $0 "---|"; next }
    { name = substr($1, 3); print $0 " " fig[name] " |" }' "$results/table.md.tmp" > "$results/table.md"
  rm "$results/table.md.tmp"
  cat "$results/table.md"
  "$mimic" plot "${runs[@]/%/.csv}" --names "${rows[@]}" --y reward --smooth 10 \
    --title "Tracking skills by the recipe: reward per step (max 1)" -o "$figures/tracking_skills_reward.png"
  init_report backflip
  init_report cartwheel
}
if [[ ${REPORT_ONLY:-0} == 1 ]]; then
  report
  exit
fi

# train NAME: one run by the recipe and its evaluation, logged to <out>/NAME.log; its evaluation and
# learning curve then kept in RESULTS.
train() {
  local name=$1 run=$out/$1 cmd
  if kept "$name"; then
    echo "$name: evaluated already, not trained again"
    return
  fi
  local common=(-o "$run" --samples "$samples" --threads 1 --trials 20 --video-seconds 0)
  if [[ -f $run/checkpoint.pt ]]; then
    cmd=(imitate --resume "${common[@]}")
  else
    rm -rf "${run:?}"
    cmd=(imitate "${clip_of[$name]}" --method tracking "${common[@]}")
    [[ -n ${set_of[$name]:-} ]] && cmd+=(--set "${set_of[$name]}")
    [[ -n ${character_of[$name]:-} ]] && cmd+=(--character "${character_of[$name]}")
  fi
  echo "$name: mimic ${cmd[*]}"
  if "$mimic" "${cmd[@]}" >"$out/$name.log" 2>&1; then
    cp "$run/eval.json" "$results/$name.json.tmp" && cp "$run/metrics.csv" "$results/$name.csv" &&
      mv "$results/$name.json.tmp" "$results/$name.json"
    echo "$name: done"
  else
    echo "$name failed: see $out/$name.log" >&2
  fi
}

# At most two runs at once (one per core).
slot() {
  while (($(jobs -rp | wc -l) >= 2)); do wait -n || true; done
}

for name in "${names[@]}"; do
  ((${#asked[@]} == 0)) || [[ " ${asked[*]} " == *" $name "* ]] || continue
  slot
  train "$name" &
done
wait
report
echo "done: $results"
