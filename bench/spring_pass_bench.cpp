// What a step() on the paper's plane spends on the spring pass: the internal forces alone
// (SPEC 1), SPEC 9's row sums alone, both in one pass (what step() runs every step), and the
// whole step, in ms per call on 1 thread. The plane's free nodes are moved by a small
// pseudo-random vector first (all springs busy); the fastest of 5 windows of 20 calls is
// printed (the least disturbed on a shared machine).
//
//   spring_pass_bench [N]   (an N x N plane; default 200, the tuner's 40k-node benchmark)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>

#include "bench/bench_meshes.hpp"
#include "core/detail/spring_pass.hpp"
#include "core/step.hpp"

namespace {

using namespace dampbound;

double fastest_ms(const std::function<void()>& call) {
  double best = 1e300;
  for (int window = 0; window < 5; ++window) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < 20; ++k) call();
    const std::chrono::duration<double, std::milli> d = std::chrono::steady_clock::now() - t0;
    best = std::min(best, d.count() / 20);
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 200;
  if (n < 2 || n > 2000) {
    std::fprintf(stderr, "spring_pass_bench: N must be 2..2000, got '%s'\n", argv[1]);
    return 2;
  }
  Params p;
  p.policy = DampingPolicy::fixed;
  const Model model = compile_model(bench::plane(n), p);
  State s = rest_state(model);
  bench::shake(model, s);
  StepWorkspace ws;
  std::vector<Vec3> force;
  std::vector<double> rows;
  const double both = fastest_ms([&] { detail::spring_pass(model, s.x, &force, &rows, &ws.pass); });
  const double forces =
      fastest_ms([&] { detail::spring_pass(model, s.x, &force, nullptr, &ws.pass); });
  const double sums = fastest_ms([&] { detail::spring_pass(model, s.x, nullptr, &rows, &ws.pass); });
  State moving = s;
  const double whole = fastest_ms([&] { step(model, p, moving, ws); });
  std::printf("plane %dx%d (%zu nodes, %zu springs), 1 thread, ms per call:\n", n, n, s.x.size(),
              model.springs.size());
  std::printf("  forces only %.3g  row sums only %.3g  both in one pass %.3g  whole step() %.3g\n",
              forces, sums, both, whole);
  std::printf("  the row sums add %.3g ms to the pass (%.2gx the forces), %.0f%% of the step\n",
              both - forces, (both - forces) / forces, 100 * (both - forces) / whole);
  return 0;
}
