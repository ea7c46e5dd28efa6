// Spring evaluations per second (springs plus anchors, per trial step) of the batched sweep
// kernel and of the plain step(), on the paper-plane scene (SPEC 5: 3745 springs + 1296
// anchors = 5041 per trial step). Trials are kept running (no restore, no divergence) so
// every lane is busy: m = 0.001, kappa = 0.001, gamma = 0.01 * lower bound (not restored
// within 1000 steps).
#include <benchmark/benchmark.h>

#include <time.h>

#include <atomic>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "core/io/scene_file.hpp"
#include "core/sweep/kernel.hpp"
#include "dampbound/physics/bounds.hpp"
#include "dampbound/physics/step.hpp"
#include "dampbound/run/scene.hpp"

namespace {

using namespace dampbound;

const SceneSpec& paper_plane() {
  static const SceneSpec s =
      load_scene(std::string(DAMPBOUND_SOURCE_DIR) + "/scenes/paper-plane.toml");
  return s;
}

TrialParams busy_trial(int k) {
  TrialParams t;
  t.m = 0.001 + 1e-6 * k;
  t.kappa = 0.001;
  t.gamma = 0.01 * lower_bound(t.m, t.kappa);
  return t;
}

/// Kernels for `threads` threads (built once, outside the timing).
std::vector<std::unique_ptr<BatchKernel>> make_kernels(int threads, DampingPolicy policy,
                                                       const StopRules& rules) {
  std::vector<std::unique_ptr<BatchKernel>> kernels;
  for (int t = 0; t < threads; ++t)
    kernels.push_back(std::make_unique<BatchKernel>(paper_plane(), policy, rules));
  return kernels;
}

/// Times the kernels side by side, kernel t taking its trials from source_for(t), and reports
/// spring evaluations and trial-steps per second.
template <typename SourceFor>
void time_kernels(benchmark::State& state,
                  const std::vector<std::unique_ptr<BatchKernel>>& kernels,
                  const SourceFor& source_for) {
  std::uint64_t lane_steps_total = 0;
  std::atomic<std::int64_t> cpu_ns{0};  // CPU time of the kernel threads: robust on a busy machine
  for (auto _ : state) {
    std::atomic<std::uint64_t> lane_steps{0};
    std::vector<std::thread> pool;
    for (size_t t = 0; t < kernels.size(); ++t)
      pool.emplace_back([&, t] {
        timespec a{}, b{};
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &a);
        lane_steps += kernels[t]->run(source_for(static_cast<int>(t)),
                                      [](std::size_t, const TrialResult&) {});
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &b);
        cpu_ns += (b.tv_sec - a.tv_sec) * 1000000000LL + (b.tv_nsec - a.tv_nsec);
      });
    for (auto& th : pool) th.join();
    lane_steps_total += lane_steps.load();
  }
  const double per_step = static_cast<double>(kernels.front()->spring_evaluations_per_step());
  state.counters["spring_evals_per_s"] = benchmark::Counter(
      static_cast<double>(lane_steps_total) * per_step, benchmark::Counter::kIsRate);
  // Per thread-CPU-second: what one core does when it runs the kernel (time-sliced or not).
  state.counters["spring_evals_per_cpu_s"] = benchmark::Counter(
      static_cast<double>(lane_steps_total) * per_step / (static_cast<double>(cpu_ns.load()) * 1e-9));
  state.counters["trial_steps_per_s"] =
      benchmark::Counter(static_cast<double>(lane_steps_total), benchmark::Counter::kIsRate);
}

/// 1000 steps of kLanes busy trials per kernel, `threads` kernels side by side.
void BM_BatchedKernel(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  const auto policy = static_cast<DampingPolicy>(state.range(1));
  StopRules rules = paper_plane().rules;
  rules.max_iterations = 1000;
  const auto kernels = make_kernels(threads, policy, rules);
  time_kernels(state, kernels, [](int t) -> TrialSource {
    auto handed = std::make_shared<int>(0);
    return [t, handed](std::size_t& id, TrialParams& p) {
      if (*handed == BatchKernel::kLanes) return false;
      id = static_cast<std::size_t>(*handed);
      p = busy_trial(t * 100 + (*handed)++);
      return true;
    };
  });
}
BENCHMARK(BM_BatchedKernel)
    ->ArgNames({"threads", "policy"})
    ->Args({1, static_cast<int>(DampingPolicy::fixed)})
    ->Args({2, static_cast<int>(DampingPolicy::fixed)})
    ->Args({2, static_cast<int>(DampingPolicy::upper)})
    ->Args({1, static_cast<int>(DampingPolicy::safe)})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// Trials as `--preset paper-upper` runs them: a fixed pseudo-random sample of its grid (m and
/// kappa in 0.0001 .. 0.1 step 0.0001, factor 1 and 1.05, policy upper, 10000 iterations),
/// each until it restores, diverges or reaches the limit, lanes refilled, `threads` kernels
/// taking trials from one list. Slower per step than BM_BatchedKernel's busy trials: states
/// that decay far enough make subnormal numbers (docs/sweeps.md).
void BM_PaperUpperSample(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  StopRules rules = paper_plane().rules;
  rules.max_iterations = 10000;
  std::vector<TrialParams> trials;
  std::mt19937_64 rng(2026);
  for (int k = 0; k < 256; ++k) {
    TrialParams t;
    t.m = 0.0001 * static_cast<double>(1 + rng() % 1000);
    t.kappa = 0.0001 * static_cast<double>(1 + rng() % 1000);
    t.factor = k % 2 == 0 ? 1.0 : 1.05;
    trials.push_back(t);
  }
  const auto kernels = make_kernels(threads, DampingPolicy::upper, rules);
  std::atomic<size_t> next{0};  // one pass over the list: the benchmark runs one iteration
  time_kernels(state, kernels, [&](int) -> TrialSource {
    return [&](std::size_t& id, TrialParams& p) {
      const size_t i = next.fetch_add(1);
      if (i >= trials.size()) return false;
      id = i;
      p = trials[i];
      return true;
    };
  });
}
BENCHMARK(BM_PaperUpperSample)
    ->ArgNames({"threads"})
    ->Arg(1)
    ->Arg(2)
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

/// The plain step() of core, one trial, one thread.
void BM_PlainStep(benchmark::State& state) {
  const SceneSpec& scene = paper_plane();
  Params params = scene.params;
  const TrialParams t = busy_trial(0);
  params.m = t.m;
  params.kappa = t.kappa;
  params.gamma = t.gamma;
  const Model model = compile_model(scene.model, params);
  State s = initial_state(scene);
  StepWorkspace ws;
  long long steps = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(step(model, params, s, ws));
    ++steps;
  }
  const double per_step = model.spec().spring_count() + model.spec().anchor_count();
  state.counters["spring_evals_per_s"] =
      benchmark::Counter(static_cast<double>(steps) * per_step, benchmark::Counter::kIsRate);
  state.counters["trial_steps_per_s"] =
      benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PlainStep)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
