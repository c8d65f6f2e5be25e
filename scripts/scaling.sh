#!/usr/bin/env bash
# The figures of docs/scaling.md, from the built mimic (build/), into runs/scaling/:
#
#   scripts/scaling.sh bench    throughput: one process at 1 and 2 threads, each with and without
#                               collect.overlap; two MPI ranks of one thread; the MPI parallel
#                               efficiency; where a simulation step's time goes (minutes)
#   scripts/scaling.sh curves   learning with and without collect.overlap at equal samples, two seeds
#                               each: the walker (walker_ppo, 500 iterations of 2,048 samples) and the
#                               humanoid walk (ICCGAN, 150 iterations of 4,096 samples); about 90 min
#                               on 2 cores
#   scripts/scaling.sh          both
#
# Run on a machine with nothing else running: the figures are rates.
set -euo pipefail
cd "$(dirname "$0")/.."
out=runs/scaling
mimic=build/src/mimic
mkdir -p "$out"
export OPENBLAS_CORETYPE=${OPENBLAS_CORETYPE:-Haswell}
# mpirun as root (containers) and without the shared-memory transport's kernel copy, which
# containers often forbid.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
parts=("$@")
[[ ${#parts[@]} -gt 0 ]] || parts=(bench curves)

bench() {
  echo "== throughput (mimic bench train): $out/bench.md"
  "$mimic" bench train --threads 1,2 --overlap --iterations 4 --rounds 3 | tee "$out/bench.md"
  mpirun -np 2 --bind-to none "$mimic" bench train --threads 1 --iterations 4 --rounds 3 | tee "$out/bench_mpi.md"
  # Parallel efficiency: two ranks' samples/s over twice one process's at one thread (no overlap).
  one=$(awk -F'|' '$2+0 == 1 && $3+0 == 1 && $4 ~ /no/ { print $6 + 0 }' "$out/bench.md")
  two=$(awk -F'|' '$2+0 == 2 && $3+0 == 1 { print $6 + 0 }' "$out/bench_mpi.md")
  awk -v one="$one" -v two="$two" 'BEGIN { printf "MPI parallel efficiency at 2 ranks: %.0f / (2 x %.0f) = %.2f\n", two, one, two / (2 * one) }' |
    tee "$out/efficiency.txt"
  echo "== the simulation's step: $out/sim_profile.md"
  build/bench/mimic_sim_profile 3000 | tee "$out/sim_profile.md"
}

# Two seeds of a config, with and without collect.overlap, then their curves against samples.
pairs() {
  local name=$1 config=$2 iterations=$3 threads=$4
  local runs=() names=()
  for seed in 1 2; do
    for overlap in false true; do
      local run=$out/${name}_seed${seed}_overlap_$overlap
      if [[ ! -f $run/checkpoint.pt ]]; then
        echo "== $run"
        "$mimic" train "$config" --iterations "$iterations" --threads "$threads" --set seed=$seed --set collect.overlap=$overlap -o "$run"
      fi
      runs+=("$run")
      names+=("seed $seed$([[ $overlap == true ]] && echo ', overlapped' || echo '')")
    done
  done
  # The return, and the reward per step the learner optimises (the discriminators' for ICCGAN).
  for y in return reward; do
    "$mimic" plot "${runs[@]}" --names "${names[@]}" --y $y --smooth 10 --title "$name: $y against samples" -o "$out/${name}_$y.png"
  done
  for run in "${runs[@]}"; do
    # Means over iterations: the first and second half of the run, and the last 10.
    awk -F, -v run="$run" 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
      { r[NR - 1] = $c["return"]; w[NR - 1] = $c["reward"]; samples = $c["samples"]; wall = $c["wall_s"] }
      END { n = NR - 1; h = int(n / 2)
            for (i = 1; i <= n; ++i) { if (i <= h) { r1 += r[i]; w1 += w[i] } else { r2 += r[i]; w2 += w[i] } }
            for (i = n - 9; i <= n; ++i) { rl += r[i]; wl += w[i] }
            printf "%s: return %.1f / %.1f / %.1f, reward %.3f / %.3f / %.3f (first half / second half / last 10 iterations), %d samples, %.0f s\n",
                   run, r1 / h, r2 / (n - h), rl / 10, w1 / h, w2 / (n - h), wl / 10, samples, wall }' "$run/metrics.csv"
  done | tee "$out/${name}_summary.txt"
}

curves() {
  pairs walker configs/walker_ppo.yaml 500 1
  [[ -f runs/humanoid_walk_links_demos.csv ]] ||
    "$mimic" record-clip configs/humanoid_walk_iccgan_links.yaml --clip "${MIMIC_DATA:-../shared/data}/deepmimic/motions/humanoid3d_walk.txt" \
      --passes 8 -o runs/humanoid_walk_links_demos.csv
  pairs humanoid_walk configs/humanoid_walk_iccgan_cpu.yaml 150 1
}

for part in "${parts[@]}"; do
  case $part in
    bench) bench ;;
    curves) curves ;;
    *) echo "scripts/scaling.sh: unknown part '$part' (bench, curves)" >&2; exit 2 ;;
  esac
done
