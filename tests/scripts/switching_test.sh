#!/usr/bin/env bash
# scripts/switching.sh, with a stand-in for mimic (fake_mimic.pl): the take-over fine-tune of a
# skill from the other three's clips (its noise held with `held`), then its measurements; a bad
# last argument refused.
# Usage: switching_test.sh SOURCE_DIR WORK_DIR
set -euo pipefail
src=$1
work=$2
rm -rf "$work"
mkdir -p "$work/scripts" "$work/data/deepmimic/motions"
cp "$src/scripts/switching.sh" "$work/scripts/"
touch "$work/data/deepmimic/motions/humanoid3d_walk.txt"
cd "$work"
motions=$work/data/deepmimic/motions
export MIMIC=$src/tests/scripts/fake_mimic.pl MIMIC_DATA=$work/data FAKE_LOG=$work/calls FAKE_SECONDS=0
fail() { echo "switching_test: $*" >&2; echo "--- calls:" >&2; cat "$work/calls" >&2 || true; exit 1; }

scripts/switching.sh kick 0.75 fast >out 2>&1 && fail "ran with a bad last argument"
grep -q "the last argument is held or nothing" out || fail "no error naming the argument: $(cat out)"
[[ ! -e calls ]] || fail "something ran with a bad argument"

# The kick, its noise held: the recipe's share (0.75) left to mimic imitate.
scripts/switching.sh kick 0.75 held >out 2>&1 || fail "kick held: $(cat out)"
imitate=$(grep "^start runs/switch_kick_share75_held imitate" calls) || fail "no fine-tune into runs/switch_kick_share75_held"
for want in "imitate $motions/humanoid3d_kick.txt --from models/humanoid_kick_iccgan_total -o runs/switch_kick_share75_held --samples 1500000 --threads 1 " \
            "--set policy.log_std=-1.66 --set policy.learn_std=false --start-clips $motions/humanoid3d_walk.txt $motions/humanoid3d_run.txt $motions/humanoid3d_punch.txt"; do
  [[ $imitate == *"$want"* ]] || fail "the fine-tune's command lacks '$want': $imitate"
done
[[ $imitate != *start_clip_share* ]] || fail "the held fine-tune sets the share: $imitate"
grep -q -- "eval runs/switch_kick_share75_held/model .*--transitions models/humanoid_walk_iccgan,models/humanoid_run_iccgan_straight_loop,models/humanoid_punch_iccgan_annealed .*--json docs/data/transitions_switch_kick_share75_held.json" calls ||
  fail "no transition test of the fine-tune"
grep -q -- "--clip $motions/humanoid3d_kick.txt --json docs/data/switch_kick_style_share75_held.json" calls || fail "no imitation of its own clip"

# The walk with its own noise and a quarter of the episodes from the others.
rm calls
scripts/switching.sh walk 0.25 >out 2>&1 || fail "walk 0.25: $(cat out)"
imitate=$(grep "^start runs/switch_walk_share25 imitate" calls) || fail "no fine-tune into runs/switch_walk_share25"
[[ $imitate == *"--samples 2000000 --threads 1 --set env.start_clip_share=0.25 --start-clips"* ]] || fail "not the quarter's command: $imitate"
[[ $imitate != *log_std* ]] || fail "the walk's own noise was not kept: $imitate"
echo "switching_test: the fine-tunes as expected"
