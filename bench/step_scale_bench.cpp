// The paper's step() on big meshes: nanoseconds per node-step and the memory the model, the
// state and the step's workspace hold per node and per spring, for planes (SPEC 5's geometry,
// anchors) and tetrahedral blocks (bench_meshes.hpp) of about 1k, 10k, 100k and 1M nodes.
//
//   step_scale_bench [--max-nodes N]     (default 1100000)
//
// Each mesh starts with every free node moved by a small pseudo-random vector (all springs
// busy) and runs policy clamp (bounds of eq. 5 and eq. 6 every step) at the paper's Fig. 1
// parameters; steps are repeated for at least 0.5 s of processor time, and the times are
// processor time (on a machine shared with other jobs, the fair measure). One thread.
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <string>

#include "bench/bench_meshes.hpp"
#include "core/step.hpp"

namespace {

using namespace dampbound;
double cpu_now() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

template <class T>
size_t bytes(const std::vector<T>& v) { return v.capacity() * sizeof(T); }

size_t model_bytes(const Model& m) {
  return bytes(m.rest) + bytes(m.mass_scale) + bytes(m.gamma_scale) + bytes(m.anchor_scale) +
         bytes(m.external_force) + bytes(m.fixed) + bytes(m.mass) + bytes(m.gamma) +
         bytes(m.anchor_kappa) + bytes(m.node_kappa) + bytes(m.lower_bound);
}

void measure(const char* kind, ModelSpec spec) {
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
  step(model, p, s, ws);  // sizes the workspace
  int steps = 0;
  const double t0 = cpu_now();
  double seconds = 0;
  while (seconds < 0.5) {
    step(model, p, s, ws);
    ++steps;
    seconds = cpu_now() - t0;
  }
  const double nodes = model.node_count();
  const size_t per_node = model_bytes(model) + bytes(s.x) + bytes(s.v) + bytes(ws.force) +
                          bytes(ws.upper_bound) + bytes(ws.gamma_eff) + bytes(ws.status);
  std::printf("%-6s %9d nodes %9d springs %6d steps  %8.2f ns/node-step  %7.1f ns/spring-step"
              "  %6.1f bytes/node + %zu bytes/spring = %7.1f MB\n",
              kind, model.node_count(), model.spring_count(), steps,
              seconds * 1e9 / (steps * nodes), seconds * 1e9 / (steps * double(model.spring_count())),
              static_cast<double>(per_node) / nodes, sizeof(Spring) + sizeof(double),
              static_cast<double>(per_node + bytes(model.springs) + bytes(model.spring_kappa)) /
                  1e6);
}

}  // namespace

int main(int argc, char** argv) {
  long max_nodes = 1100000;
  if (argc == 3 && std::string(argv[1]) == "--max-nodes") max_nodes = std::atol(argv[2]);
  for (int n : {32, 100, 317, 1000})
    if (long(n) * n <= max_nodes) measure("plane", bench::plane(n));
  for (int n : {10, 22, 46, 100})
    if (long(n) * n * n <= max_nodes) measure("block", bench::tet_block(n, n, n));
  return 0;
}
