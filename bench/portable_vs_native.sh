#!/usr/bin/env bash
# The batched sweep kernel's speed, portable build against native build, side by side in one
# run: BM_BatchedKernel (paper plane, 1 thread, policy fixed, 8 busy trials x 1000 steps)
# from each build's sweep_bench, alternated ROUNDS times so that a busy machine slows both
# alike; the portable build also runs each of its variants (DAMPBOUND_KERNEL_ISA).
# Usage: bench/portable_vs_native.sh PORTABLE_BUILD NATIVE_BUILD [ROUNDS]
#   (NATIVE_BUILD configured with -DDAMPBOUND_NATIVE=ON; only its sweep_bench is needed)
set -euo pipefail
portable=$1/bench/sweep_bench native=$2/bench/sweep_bench rounds=${3:-3}
filter='BM_BatchedKernel/threads:1/policy:0'
rate() {  # spring evaluations per thread-CPU second (time-slicing on a busy machine does not
          # count), the median of 3 repetitions
  env "${@:2}" "$1" --benchmark_filter="$filter" --benchmark_repetitions=3 \
    --benchmark_report_aggregates_only=true --benchmark_format=csv 2>/dev/null |
    awk -F, '/_median"?,/ { for (i = 1; i <= NF; ++i) if (h[i] == "spring_evals_per_cpu_s") print $i }
             /^name,/ { for (i = 1; i <= NF; ++i) { h[i] = $i; gsub(/"/, "", h[i]) } }'
}
echo "cores: $(nproc), load: $(cut -d' ' -f1-3 /proc/loadavg), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
declare -A sum
for r in $(seq "$rounds"); do
  for v in native portable-best portable-avx512 portable-avx2 portable-generic; do
    case $v in
      native) x=$(rate "$native" DAMPBOUND_KERNEL_ISA=best) ;;
      portable-best) x=$(rate "$portable" DAMPBOUND_KERNEL_ISA=best) ;;
      portable-*) x=$(rate "$portable" DAMPBOUND_KERNEL_ISA="${v#portable-}") ;;
    esac
    printf 'round %d  %-17s %.3e spring evals/CPU-s\n' "$r" "$v" "$x"
    sum[$v]=$(awk -v a="${sum[$v]:-0}" -v b="$x" 'BEGIN { print a + b }')
  done
done
n=${sum[native]}
for v in native portable-best portable-avx512 portable-avx2 portable-generic; do
  awk -v v="$v" -v s="${sum[$v]}" -v n="$n" -v r="$rounds" \
    'BEGIN { printf "mean %-17s %.3e spring evals/CPU-s  %5.1f%% of native\n", v, s / r, 100 * s / n }'
done
