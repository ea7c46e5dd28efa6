// The bound that IEEE division and square root set on the batched sweep kernel's AVX2 copy:
// throughput of vsqrtpd and vdivpd on 256-bit registers (4 doubles), alone and interleaved,
// measured with 12 independent dependency chains (more than latency / throughput, so the
// divider, not a chain, is the limit). The kernel cannot do fewer of either and stay
// bit-identical to step(): per trial step it takes one square root and one division per spring
// (length, force scale) and, per free node, two square roots (|v|, |v m/dt + F|) and four
// divisions (gamma_hi, a = .../m for x, y, z). For the paper-plane scene (3745 springs, 1296
// free nodes, 5041 spring evaluations per trial step) the bound is printed as
// spring_evals_per_s, to compare with sweep_bench's BM_BatchedKernel (policy fixed).
#include <benchmark/benchmark.h>

#if defined(__x86_64__)
#include <immintrin.h>

#include <time.h>

#include <cstdint>

namespace {

constexpr double kSprings = 3745, kFreeNodes = 1296, kEvalsPerStep = 5041;
constexpr double kSqrtPerStep = kSprings + 2 * kFreeNodes;
constexpr double kDivPerStep = kSprings + 4 * kFreeNodes;
constexpr int kChains = 12;
constexpr int kLanes = 4;  // doubles per ymm register

/// Read once per call, so the compiler cannot treat the chains as a pure function of `reps`.
volatile double seed = 1.5;

bool have_avx2() { return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("avx"); }

/// `reps` rounds of kChains dependent chains: sqrt only (Sqrt), division only (Div), or one
/// of each per chain and round (both). Returns a value that depends on every result.
template <bool Sqrt, bool Div>
__attribute__((target("avx2,avx"), noinline)) double chains(std::int64_t reps) {
  __m256d x[kChains], y[kChains];
  for (int k = 0; k < kChains; ++k) {
    x[k] = _mm256_set1_pd(seed + k);
    y[k] = _mm256_set1_pd(seed + 1 + k);
  }
  // Operands with full mantissas, as the kernel's are: x -> 1.7 sqrt(x) settles near 2.89,
  // y -> 1.3700001 y / 1.37 grows slowly; neither becomes 1, 0, a subnormal or inf.
  const __m256d c = _mm256_set1_pd(1.7), d = _mm256_set1_pd(1.37), e = _mm256_set1_pd(1.3700001);
  for (std::int64_t r = 0; r < reps; ++r)
    for (int k = 0; k < kChains; ++k) {
      if constexpr (Sqrt) x[k] = _mm256_mul_pd(_mm256_sqrt_pd(x[k]), c);
      if constexpr (Div) y[k] = _mm256_mul_pd(_mm256_div_pd(y[k], d), e);
    }
  __m256d s = _mm256_setzero_pd();
  for (int k = 0; k < kChains; ++k) s = _mm256_add_pd(s, _mm256_add_pd(x[k], y[k]));
  double out[4];
  _mm256_storeu_pd(out, s);
  return out[0] + out[1] + out[2] + out[3];
}

template <bool Sqrt, bool Div>
void BM_Ymm(benchmark::State& state) {
  if (!have_avx2()) {
    state.SkipWithError("this CPU has no avx2");
    return;
  }
  constexpr std::int64_t kReps = 1 << 16;
  for (auto _ : state) benchmark::DoNotOptimize(chains<Sqrt, Div>(kReps));
  const double instructions =
      static_cast<double>(state.iterations()) * kReps * kChains * ((Sqrt ? 1 : 0) + (Div ? 1 : 0));
  // Per CPU second of the benchmark's thread (Google Benchmark's rates use CPU time here).
  state.counters["instr_per_s"] = benchmark::Counter(instructions, benchmark::Counter::kIsRate);
  state.counters["ns_per_instr"] = benchmark::Counter(
      instructions * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK_TEMPLATE(BM_Ymm, true, false)->Name("BM_VsqrtpdYmm");
BENCHMARK_TEMPLATE(BM_Ymm, false, true)->Name("BM_VdivpdYmm");
BENCHMARK_TEMPLATE(BM_Ymm, true, true)->Name("BM_VsqrtpdVdivpdInterleaved");

/// The kernel's bound: the time of its square roots and divisions per 4 trial steps, each at
/// the throughput measured alone and summed (on Zen 4 one unit does both: the interleaved
/// benchmark shows no overlap), as spring evaluations per second.
void BM_KernelBoundAVX2(benchmark::State& state) {
  if (!have_avx2()) {
    state.SkipWithError("this CPU has no avx2");
    return;
  }
  constexpr std::int64_t kReps = 1 << 14;
  double sqrt_s = 0, div_s = 0;
  for (auto _ : state) {
    // Thread CPU time, as the other benchmarks report (robust on a busy machine).
    auto time = [](auto f) {
      timespec a{}, b{};
      clock_gettime(CLOCK_THREAD_CPUTIME_ID, &a);
      benchmark::DoNotOptimize(f(kReps));
      clock_gettime(CLOCK_THREAD_CPUTIME_ID, &b);
      return static_cast<double>(b.tv_sec - a.tv_sec) + 1e-9 * static_cast<double>(b.tv_nsec - a.tv_nsec);
    };
    sqrt_s += time(chains<true, false>);
    div_s += time(chains<false, true>);
  }
  const double n = static_cast<double>(state.iterations()) * kReps * kChains;
  const double step_s = (kSqrtPerStep * sqrt_s / n + kDivPerStep * div_s / n) / kLanes;
  state.counters["spring_evals_per_s"] = kEvalsPerStep / step_s;
  state.counters["trial_steps_per_s"] = 1.0 / step_s;
}
BENCHMARK(BM_KernelBoundAVX2);

}  // namespace
#endif  // __x86_64__

BENCHMARK_MAIN();
