// What a step() on the paper's plane spends on the spring pass: the internal forces alone
// (SPEC 1), SPEC 9's row sums alone, both in one pass (what step() runs every step), and the
// whole step, in ms per call on 1 thread, with each copy of the spring batch this CPU runs
// (include/dampbound/physics/step_isa.hpp: generic, avx2). The plane's free nodes are moved by a small
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
#include "core/physics/detail/spring_pass.hpp"
#include "dampbound/physics/step.hpp"
#include "dampbound/physics/step_isa.hpp"

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
  std::printf("plane %dx%d (%zu nodes, %zu springs), 1 thread, ms per call:\n", n, n, s.x.size(),
              model.spec().springs.size());
  // Each copy of the spring batch the CPU runs (include/dampbound/physics/step_isa.hpp), measured in turn.
  double first_step = 0;
  for (StepIsa isa : {StepIsa::generic, StepIsa::avx2}) {
    if (!step_isa_supported(isa)) {
      std::printf("  %-8s not run: this CPU lacks it\n", to_string(isa));
      continue;
    }
    StepWorkspace ws;
    ws.pass.isa = isa;
    std::vector<Vec3> force;
    std::vector<double> rows;
    const double both =
        fastest_ms([&] { detail::spring_pass(model, s.x, &force, &rows, &ws.pass); });
    const double forces =
        fastest_ms([&] { detail::spring_pass(model, s.x, &force, nullptr, &ws.pass); });
    const double sums =
        fastest_ms([&] { detail::spring_pass(model, s.x, nullptr, &rows, &ws.pass); });
    State moving = s;
    const double whole = fastest_ms([&] { step(model, p, moving, ws); });
    std::printf("  %-8s forces only %.3g  row sums only %.3g  both in one pass %.3g  "
                "whole step() %.3g",
                to_string(isa), forces, sums, both, whole);
    if (first_step > 0)
      std::printf("  (step %.2fx the generic copy's)", first_step / whole);
    else
      first_step = whole;
    std::printf("\n");
  }
  return 0;
}
