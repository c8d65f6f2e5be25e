#!/usr/bin/env bash
# scripts/recovery.sh walk, with a stand-in for mimic (fake_mimic.pl): 40 sessions recorded, the
# 0.3 s that end 0.1 s before each hand-back of their events given as start clips beside the
# get-up clips' ends, the fine-tune copied into models/; missing get-ups and unknown parts refused.
# Usage: recovery_test.sh SOURCE_DIR WORK_DIR
set -euo pipefail
src=$1
work=$2
rm -rf "$work"
mkdir -p "$work/scripts" "$work/models/humanoid_getup_facedown" "$work/models/humanoid_getup_faceup"
cp "$src/scripts/recovery.sh" "$work/scripts/"
cd "$work"
export MIMIC=$src/tests/scripts/fake_mimic.pl MIMIC_DATA=/data FAKE_LOG=$work/calls FAKE_SECONDS=0
fail() { echo "recovery_test: $*" >&2; echo "--- calls:" >&2; cat "$work/calls" >&2 || true; exit 1; }

# No get-ups: a named error, nothing run.
scripts/recovery.sh walk >out 2>&1 && fail "ran without get-ups"
grep -q "no get-up model in models/humanoid_getup_facedown" out || fail "no error naming the missing get-up: $(cat out)"
[[ ! -e calls ]] || fail "something ran without get-ups"
touch models/humanoid_getup_facedown/networks.mimic models/humanoid_getup_faceup/networks.mimic
scripts/recovery.sh landing >out 2>&1 && fail "an unknown part ran"
grep -q "unknown part 'landing'" out || fail "no error naming the unknown part: $(cat out)"

# Two hand-backs a session, at 9.5 s and 14.25 s.
FAKE_RECOVERED="9.5 14.25" scripts/recovery.sh walk >out 2>&1 || fail "walk: $(cat out)"
[[ $(grep -c "^start - play models/humanoid_walk_iccgan --recover models/humanoid_getup_facedown models/humanoid_getup_faceup" calls) == 40 ]] ||
  fail "not 40 sessions of the shipped walk with both get-ups"
grep -q -- "--seed 40 --motion runs/getup_ends/session_40.mclip --json runs/getup_ends/session_40.json" calls || fail "session 40 not recorded"
grep -q "80 hand-backs in 40 sessions" out || fail "no count of the hand-backs: $(cat out)"
imitate=$(grep "^start runs/humanoid_walk_iccgan_after_getups imitate" calls) || fail "no fine-tune"
for want in "--from models/humanoid_walk_iccgan --samples 1500000" \
            "--start-clips /data/deepmimic/motions/humanoid3d_getup_faceup.txt@-0.3 /data/deepmimic/motions/humanoid3d_getup_facedown.txt@-0.3 " \
            "runs/getup_ends/session_1.mclip@9.1000:9.4000 runs/getup_ends/session_1.mclip@13.8500:14.1500 runs/getup_ends/session_2.mclip@9.1000:9.4000" \
            "runs/getup_ends/session_40.mclip@13.8500:14.1500 -o runs/humanoid_walk_iccgan_after_getups"; do
  [[ $imitate == *"$want"* ]] || fail "the fine-tune's command lacks '$want': $imitate"
done
for f in networks.mimic eval.json report.md curves.png video.mp4; do
  [[ -f models/humanoid_walk_iccgan_after_getups/$f ]] || fail "models/humanoid_walk_iccgan_after_getups/$f not copied"
done
echo "recovery_test: the walk's fine-tune as expected"
