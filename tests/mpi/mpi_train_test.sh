#!/usr/bin/env bash
# One training run over two ranks, as a cluster user starts it: `mpirun -np 2 mimic train
# configs/walker_ci.yaml`. It must learn as the one-process test does (TrainerLearning.WalkerLearnsToMoveForward:
# the first iteration's return under 20, the last three's mean over 100 and over five times the
# first); a seed must give the same numbers twice; and a run killed (SIGKILL, mpirun and its ranks)
# after a checkpoint must resume over two ranks and finish with the numbers of the run never killed;
# and a run saved by two ranks goes on in one process.
# Usage: mpi_train_test.sh MIMIC SOURCE_DIR OUT_DIR [MPIRUN]
set -euo pipefail
mimic=$1 src=$2 out=$3 mpirun=${4:-mpirun}
rm -rf "$out" && mkdir -p "$out"
# Containers run tests as root; the shared-memory transport's kernel copy is often not allowed there.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none OMPI_MCA_rmaps_base_oversubscribe=1
config=$src/configs/walker_ci.yaml
train() { "$mpirun" -np 2 --bind-to none "$mimic" train "$config" --threads 1 --set checkpoint_every=4 "$@"; }
fail() { echo "FAIL: $*" >&2; exit 1; }

# The column named $2 of metrics.csv $1, one value per iteration.
column() { awk -F, -v name="$2" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == name) c = i; next } { print $c }' "$1"; }

train -o "$out/whole" > "$out/whole.log" 2>&1 || { cat "$out/whole.log"; fail "mpirun -np 2 mimic train"; }
grep -q "2 ranks (mpirun)" "$out/whole.log" || fail "the run did not say it ran over 2 ranks"
returns=($(column "$out/whole/metrics.csv" return))
samples=($(column "$out/whole/metrics.csv" samples))
[ ${#returns[@]} -eq 16 ] || fail "16 iterations expected, metrics.csv has ${#returns[@]}"
[ "${samples[15]}" = 65536 ] || fail "2 ranks x 2048 samples x 16 iterations is 65536 samples, metrics.csv says ${samples[15]}"
echo "returns over 2 ranks: ${returns[*]}"
awk -v first="${returns[0]}" -v a="${returns[13]}" -v b="${returns[14]}" -v c="${returns[15]}" 'BEGIN {
  late = (a + b + c) / 3
  if (!(first < 20)) { print "FAIL: first return " first " (one process: under 20)"; exit 1 }
  if (!(late > 100 && late > 5 * first)) { print "FAIL: last three returns average " late " (one process: over 100 and 5x the first)"; exit 1 }
}' || exit 1

# The same seed again, killed after its checkpoint of iteration 8, then resumed: its first eight
# iterations (the same seed, the same numbers) and the eight after the resume are the whole run's.
setsid "$mpirun" -np 2 --bind-to none "$mimic" train "$config" --threads 1 --set checkpoint_every=4 -o "$out/killed" > "$out/killed.log" 2>&1 &
launcher=$!
for _ in $(seq 1200); do
  rows=$( [ -f "$out/killed/metrics.csv" ] && column "$out/killed/metrics.csv" return | wc -l || echo 0)
  [ "$rows" -ge 9 ] && break
  kill -0 $launcher 2>/dev/null || { cat "$out/killed.log"; fail "the run to kill ended early"; }
  sleep 0.1
done
kill -KILL -- -$launcher 2>/dev/null || true
wait $launcher 2>/dev/null || true
[ -f "$out/killed/checkpoint.pt" ] || fail "no checkpoint before the kill"
"$mpirun" -np 2 --bind-to none "$mimic" train --resume -o "$out/killed" --threads 1 > "$out/resumed.log" 2>&1 || { cat "$out/resumed.log"; fail "resume over 2 ranks"; }
grep -q "resuming at iteration 8" "$out/resumed.log" || { cat "$out/resumed.log"; fail "the resume did not start at iteration 8"; }
[ "$(column "$out/killed/metrics.csv" return)" = "$(column "$out/whole/metrics.csv" return)" ] ||
  fail "the killed and resumed run's returns differ from the whole run's: $(column "$out/killed/metrics.csv" return | tr '\n' ' ')"
[ "$(column "$out/killed/metrics.csv" kl)" = "$(column "$out/whole/metrics.csv" kl)" ] || fail "the killed and resumed run's KLs differ from the whole run's"
# Another number of ranks goes on too, and says so: the 2-rank run resumed in one process.
"$mimic" train --resume -o "$out/whole" --iterations 18 --threads 1 > "$out/one.log" 2>&1 || { cat "$out/one.log"; fail "resume in one process"; }
grep -q "was saved by 2 rank(s) and goes on over 1" "$out/one.log" || { cat "$out/one.log"; fail "no word that the number of ranks changed"; }
[ "$(column "$out/whole/metrics.csv" samples | tail -1)" = 69632 ] || fail "65536 + 2 x 2048 samples expected after two iterations in one process"

# mimic imitate over two ranks: rank 0 writes the run and, after training, the model, its
# evaluation and report; one iteration of 256 samples on each rank (this tests the pipeline).
walk=${MIMIC_DATA:-$src/../shared/data}/deepmimic/motions/humanoid3d_walk.txt
if [ -f "$walk" ]; then
  "$mpirun" -np 2 --bind-to none "$mimic" imitate "$walk" -o "$out/imitate" --samples 1 --trials 1 --video-seconds 0 --threads 1 \
    --set collect.samples=256 --set collect.envs=2 --set env.max_seconds=2 > "$out/imitate.log" 2>&1 || { cat "$out/imitate.log"; fail "mpirun -np 2 mimic imitate"; }
  for f in model/networks.mimic eval.json report.md; do [ -f "$out/imitate/$f" ] || fail "mpirun -np 2 mimic imitate wrote no $f"; done
  grep -q "| samples | 512 (1 iteration of 256 on each of 2 ranks) |" "$out/imitate/report.md" || { cat "$out/imitate/report.md"; fail "the report's samples"; }
else
  echo "skipped mimic imitate over two ranks: $walk not found (the shared data)"
fi

echo "PASS: 2 ranks learn (return ${returns[0]} -> ${returns[15]}), repeat, and resume after a kill"
