// The paper's step() on big meshes: nanoseconds per node-step on 1 thread and on more, and the
// memory the model, the state and the step's workspace hold per node and per spring, for
// planes (SPEC 5's geometry, anchors) and tetrahedral blocks (bench_meshes.hpp) of about 1k,
// 10k, 100k and 1M nodes.
//
//   step_scale_bench [--max-nodes N] [--threads T]     (defaults 1100000 and 2)
//
// Each mesh starts with every free node moved by a small pseudo-random vector (all springs
// busy) and runs policy clamp (bounds of eq. 5 and eq. 6 and SPEC 9's row sums every step)
// at the paper's Fig. 1 parameters. Steps repeat for at least 0.5 s of wall time per thread
// count; the speed-up is the 1-thread time over the T-thread time measured back to back. The
// trajectories are the same bits on any thread count (tests/core/step_test.cpp).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "bench/bench_meshes.hpp"
#include "core/step.hpp"

namespace {

using namespace dampbound;
using Clock = std::chrono::steady_clock;

template <class T>
size_t bytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

/// Per node: the model's per-node arrays, the state and the workspace's per-node arrays
/// (with the spring pass's 9 row-sum accumulators).
size_t node_bytes(const Model& m, const State& s, const StepWorkspace& ws) {
  return bytes(m.rest) + bytes(m.mass_scale) + bytes(m.gamma_scale) + bytes(m.anchor_scale) +
         bytes(m.external_force) + bytes(m.fixed) + bytes(m.mass) + bytes(m.gamma) +
         bytes(m.anchor_kappa) + bytes(m.node_kappa) + bytes(m.lower_bound) +
         bytes(m.incident_offset) + bytes(s.x) + bytes(s.v) + bytes(ws.force) +
         bytes(ws.upper_bound) + bytes(ws.gamma_eff) + bytes(ws.status) +
         bytes(ws.safe_row_sum) + bytes(ws.safe_bound) + bytes(ws.pass.rows);
}

/// Per spring: the spring, its kappa and its two incidence entries (the step keeps nothing
/// per spring).
size_t spring_bytes(const Model& m) {
  return bytes(m.springs) + bytes(m.spring_kappa) + bytes(m.incident);
}

/// Wall seconds per step of `threads` threads, over at least 0.5 s.
double seconds_per_step(const Model& model, const Params& p, const State& start, int threads,
                        StepWorkspace& ws) {
  State s = start;
  ws.pass.threads.set_threads(threads);
  step(model, p, s, ws);  // sizes the workspace, starts the threads
  int steps = 0;
  const auto t0 = Clock::now();
  double seconds = 0;
  while (seconds < 0.5) {
    step(model, p, s, ws);
    ++steps;
    seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  }
  return seconds / steps;
}

void measure(const char* kind, ModelSpec spec, int threads) {
  Params p;
  p.policy = DampingPolicy::clamp;
  const Model model = compile_model(std::move(spec), p);
  State s = rest_state(model);
  unsigned seed = 1;
  for (size_t i = 0; i < s.x.size(); ++i) {
    if (model.fixed[i]) continue;
    for (int k = 0; k < 3; ++k) {
      seed = seed * 1103515245u + 12345u;
      s.x[i][k] += 0.01 * (static_cast<double>((seed >> 8) & 0xffffu) / 65535.0 - 0.5);
    }
  }
  StepWorkspace ws;
  const double one = seconds_per_step(model, p, s, 1, ws);
  const double many = seconds_per_step(model, p, s, threads, ws);
  const double nodes = model.node_count(), springs = model.spring_count();
  const size_t nb = node_bytes(model, s, ws), sb = spring_bytes(model);
  std::printf("%-6s %8d nodes %8d springs  1 thread %7.1f ns/node-step  %d threads %7.1f "
              "ns/node-step  x%.2f  %5.0f B/node %4.0f B/spring  %7.1f MB\n",
              kind, model.node_count(), model.spring_count(), one * 1e9 / nodes, threads,
              many * 1e9 / nodes, one / many, nb / nodes, sb / springs, (nb + sb) / 1e6);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  long max_nodes = 1100000;
  int threads = 2;
  for (int a = 1; a + 1 < argc; a += 2) {
    const std::string flag = argv[a];
    if (flag == "--max-nodes") max_nodes = std::atol(argv[a + 1]);
    else if (flag == "--threads") threads = std::atoi(argv[a + 1]);
    else {
      std::fprintf(stderr, "step_scale_bench: unknown flag %s\n", argv[a]);
      return 2;
    }
  }
  if (threads < 1) {
    std::fprintf(stderr, "step_scale_bench: --threads must be >= 1\n");
    return 2;
  }
  for (int n : {32, 100, 317, 1000})
    if (long(n) * n <= max_nodes) measure("plane", bench::plane(n), threads);
  for (int n : {10, 22, 46, 100})
    if (long(n) * n * n <= max_nodes) measure("block", bench::tet_block(n, n, n), threads);
  return 0;
}
