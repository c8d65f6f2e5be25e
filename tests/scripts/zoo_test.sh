#!/usr/bin/env bash
# scripts/zoo.sh's scheduling, with a stand-in for mimic (fake_mimic.pl): the order, the skills that
# start from the walk waiting for it, at most -j skills at a time at one thread each, a failure
# skipping what starts from it, Ctrl-C (or a TERM, one skill at a time) saving every running skill,
# and the bad arguments refused.
# Usage: zoo_test.sh SOURCE_DIR WORK_DIR
set -euo pipefail
src=$1
work=$2
fake=$src/tests/scripts/fake_mimic.pl
rm -rf "$work"
mkdir -p "$work/scripts"
cp "$src/scripts/zoo.sh" "$work/scripts/"
cd "$work"
export MIMIC=$fake MIMIC_DATA=/data FAKE_LOG=$work/calls FAKE_SECONDS=0.5
fail() { echo "zoo_test: $*" >&2; echo "--- calls:" >&2; cat "$work/calls" >&2 || true; exit 1; }
# When NAME's EVENT (start, done, failed, stopped) happened: its line in the calls, which are in order.
at() { awk -v e="$2" -v o="runs/zoo/$1" '$1 == e && $2 == o {print NR; exit}' calls; }
before() { [[ -n $1 && -n $2 && $1 -lt $2 ]]; }

# 1. Everything, three at a time; the dog's run fails. (Runs of 1.5 s, so that three overlap on a
# busy machine.)
if FAKE_SECONDS=1.5 FAKE_FAIL=dog3d scripts/zoo.sh -j 3 >out 2>&1; then fail "a failed skill did not fail the zoo"; fi
grep -q "dog_trot failed (exit 4): see runs/zoo/dog_trot.log" out || fail "no failure line: $(cat out)"
for name in humanoid_walk humanoid_run humanoid_kick humanoid_punch humanoid_walk_from_standing humanoid_cmu_walk humanoid_getup_facedown \
            humanoid_getup_faceup humanoid_jumping_jack humanoid_walk_tracking walker_ppo; do
  [[ -f models/$name/networks.mimic ]] || fail "models/$name was not made"
done
[[ ! -e models/dog_trot ]] || fail "the failed dog's model was copied"
for name in humanoid_run humanoid_punch humanoid_walk_from_standing; do
  before "$(at humanoid_walk "done")" "$(at $name start)" || fail "$name started before the walk it starts from was done"
done
# Never more than three at a time; each at one thread.
awk '$2 ~ /^runs\/zoo\/[a-z_]+$/ && $3 != "demo" && $3 != "export" {n += ($1 == "start") - ($1 != "start"); if (n > most) most = n}
     END {exit !(most == 3)}' calls || fail "not three skills at a time at most and at least"
grep -q "imitate /data/deepmimic/motions/humanoid3d_kick.txt -o runs/zoo/humanoid_kick --threads 1" calls || fail "the kick not at one thread"
grep -q "train configs/walker_ppo.yaml -o runs/zoo/walker_ppo --threads 1" calls || fail "the walker not at one thread"
grep -q "imitate /data/deepmimic/motions/humanoid3d_walk.txt --method tracking --samples 5000000 -o runs/zoo/humanoid_walk_tracking --threads 1" calls ||
  fail "the tracked walk not by the tracking recipe"
grep -q "imitate /data/cmu-bvh/131_01.bvh -o runs/zoo/humanoid_cmu_walk --threads 1" calls || fail "the CMU walk not from its BVH"
grep -q "start-clips /data/deepmimic/motions/humanoid3d_getup_facedown.txt@-0.3 /data/deepmimic/motions/humanoid3d_getup_faceup.txt@-0.3" calls ||
  fail "the walk from standing not started from the get-ups' ends"

# 2. Made runs are resumed, not started again; one at a time needs no thread count.
rm -f calls
scripts/zoo.sh humanoid_kick >out 2>&1 || fail "one skill: $(cat out)"
grep -q "^start runs/zoo/humanoid_kick imitate --resume -o runs/zoo/humanoid_kick$" calls || fail "the kick's run was not resumed"

# 3. The walk fails: what starts from it is not made, the rest is.
rm -rf runs/zoo/humanoid_walk runs/zoo/humanoid_run runs/zoo/humanoid_getup_faceup models
rm -f calls
if FAKE_FAIL=humanoid3d_walk.txt scripts/zoo.sh -j 2 humanoid_run humanoid_walk humanoid_getup_faceup >out 2>&1; then fail "the walk failed and the zoo did not"; fi
grep -q "humanoid_run not made: humanoid_walk, which it starts from, did not finish" out || fail "no skip line: $(cat out)"
! grep -q "runs/zoo/humanoid_run" calls || fail "the run was started without its walk"
[[ -f models/humanoid_getup_faceup/networks.mimic ]] || fail "the get-up, which needs no walk, was not made"

# 4. Ctrl-C (SIGINT to the scheduler's process group, as a terminal sends it) stops each running
# skill once, saved. (Job control gives the scheduler a group of its own and leaves its SIGINT
# alone: a background command of a script without it starts with SIGINT ignored.)
rm -rf runs/zoo/humanoid_kick runs/zoo/humanoid_getup_facedown
rm -f calls
set -m
FAKE_SECONDS=30 scripts/zoo.sh -j 2 humanoid_kick humanoid_getup_facedown >out 2>&1 &
scheduler=$!
set +m
for _ in $(seq 100); do [[ $(grep -c "^start runs/zoo/humanoid_" calls 2>/dev/null) == 2 ]] && break; sleep 0.1; done
kill -INT -- "-$scheduler"
status=0
wait "$scheduler" || status=$?
[[ $status == 130 ]] || fail "stopped, the zoo exited $status, not 130: $(cat out)"
[[ $(grep -c "^stopped runs/zoo/humanoid_" calls) == 2 ]] || fail "not both skills stopped once"
grep -q "humanoid_kick stopped and saved; the same command goes on from it" out || fail "no stop line: $(cat out)"

# 5. One at a time, started in the background: a TERM to the zoo (as `kill` sends it) stops the
# running skill once, saved, and starts nothing after it; the zoo exits 143.
rm -rf runs/zoo/humanoid_kick runs/zoo/humanoid_getup_facedown
rm -f calls
FAKE_SECONDS=30 scripts/zoo.sh humanoid_kick humanoid_getup_facedown >out 2>&1 &
scheduler=$!
for _ in $(seq 100); do grep -q "^start runs/zoo/humanoid_kick" calls 2>/dev/null && break; sleep 0.1; done
kill -TERM "$scheduler"
status=0
wait "$scheduler" || status=$?
[[ $status == 143 ]] || fail "stopped by TERM, the zoo exited $status, not 143: $(cat out)"
[[ $(grep -c "^stopped runs/zoo/humanoid_kick" calls) == 1 ]] || fail "the kick was not stopped once"
! grep -q "runs/zoo/humanoid_getup_facedown" calls || fail "the next skill was started after the stop"
grep -q "humanoid_kick stopped and saved; the same command goes on from it" out || fail "no stop line: $(cat out)"
! pgrep -f "fake_mimic.pl imitate.*runs/zoo/humanoid_kick" >/dev/null || fail "the kick's run goes on after the zoo stopped"

# 6. Bad arguments, refused before anything runs.
rm -rf runs/zoo/humanoid_walk
rm -f calls
expect_refused() {
  local expected=$1
  shift
  if scripts/zoo.sh "$@" >out 2>&1; then fail "zoo.sh $* ran"; fi
  grep -qF -- "$expected" out || fail "zoo.sh $*: expected '$expected' in: $(cat out)"
}
expect_refused "-j takes a number of skills at a time" -j 0
expect_refused "no skill 'humanoid_fly'" humanoid_fly
expect_refused "humanoid_punch starts from humanoid_walk's model, which is not made yet: scripts/zoo.sh humanoid_walk humanoid_punch" humanoid_punch
[[ ! -e calls ]] || fail "a refused zoo called mimic"
echo "zoo_test: passed"
