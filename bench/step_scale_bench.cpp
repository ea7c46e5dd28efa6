// The paper's step() on big meshes: nanoseconds per node-step on 1 thread and on more, and the
// memory the model, the state and the step's workspace hold per node and per spring, for
// planes (SPEC 5's geometry, anchors) and tetrahedral blocks (bench_meshes.hpp) of about 1k,
// 10k, 100k and 1M nodes.
//
//   step_scale_bench [--max-nodes N] [--threads T] [--repeats R] [--mesh plane|block|all]
//                    [--what step|monitor]   (defaults 1100000, 2, 5, all, step)
//
// --what monitor times, instead of a step, what a user's own simulator asks the Monitor for
// each step (include/dampbound/monitor.hpp: the internal forces, then check() with the positions under
// policy safe) on the same meshes and states, in ns per node-call.
//
// Each mesh starts with every free node moved by a small pseudo-random vector (all springs
// busy) and runs policy clamp (bounds of eq. 5 and eq. 6 and SPEC 9's row sums every step)
// at the paper's Fig. 1 parameters. A window steps for at least 0.3 s of wall time; R windows
// on 1 thread alternate with R on T threads (1, T, 1, T, ...), so that a busy spell on a
// shared machine falls on both. Printed per thread count: the fastest window (the least
// disturbed) and the median; the speed-up of the fastest windows, and the range of the R
// ratios of each 1-thread window to the T-thread window after it. The trajectories are the
// same bits on any thread count (tests/core/physics/step_test.cpp).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "bench/bench_meshes.hpp"
#include "dampbound/monitor.hpp"
#include "dampbound/physics/step.hpp"

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
  return bytes(m.spec().rest) + bytes(m.spec().mass_scale) + bytes(m.spec().gamma_scale) + bytes(m.spec().anchor_scale) +
         bytes(m.spec().external_force) + bytes(m.spec().fixed) + bytes(m.mass) + bytes(m.gamma) +
         bytes(m.anchor_kappa) + bytes(m.node_kappa) + bytes(m.lower_bound) +
         bytes(m.incident_offset) + bytes(s.x) + bytes(s.v) + bytes(ws.force) +
         bytes(ws.upper_bound) + bytes(ws.gamma_eff) + bytes(ws.status) +
         bytes(ws.safe_row_sum) + bytes(ws.safe_bound) + bytes(ws.pass.rows);
}

/// Per spring: the spring, its kappa and its two incidence entries (the step keeps nothing
/// per spring).
size_t spring_bytes(const Model& m) {
  return bytes(m.spec().springs) + bytes(m.spring_kappa) + bytes(m.incident);
}

/// Wall seconds per call of `once`, over at least 0.3 s after one call (which sizes the
/// buffers and starts the threads).
template <class F>
double seconds_per_call(F&& once) {
  once();
  int calls = 0;
  const auto t0 = Clock::now();
  double seconds = 0;
  while (seconds < 0.3) {
    once();
    ++calls;
    seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  }
  return seconds / calls;
}

/// The model as a user's simulator holds it, in a Monitor, and a state to check.
struct MonitorCase {
  std::vector<double> mass, stiffness, rest_length, anchor, gamma, out;
  std::vector<int> pairs;
  std::vector<Vec3> rest, x, v;
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> force;
  std::optional<Monitor> monitor;  // made once the arrays are filled

  MonitorCase(const Model& m, const State& s) : x(s.x), v(s.v) {
    const auto n = static_cast<Eigen::Index>(m.spec().node_count());
    const auto ns = static_cast<Eigen::Index>(m.spec().spring_count());
    mass = m.mass;
    anchor = m.anchor_kappa;
    gamma = m.gamma;
    rest = m.spec().rest;
    stiffness = m.spring_kappa;
    for (const Spring& sp : m.spec().springs) {
      pairs.insert(pairs.end(), {sp.i, sp.j});
      rest_length.push_back(sp.rest_length);
    }
    for (size_t i = 0; i < v.size(); ++i) v[i] = 100.0 * (x[i] - rest[i]);  // every node moving
    out.resize(mass.size());
    force.resize(n, 3);
    monitor.emplace(node_scalars(mass.data(), n), spring_pairs(pairs.data(), ns),
                     node_scalars(stiffness.data(), ns), node_scalars(rest_length.data(), ns));
    monitor->set_anchors(node_scalars(anchor.data(), n), node_vectors(rest[0].data(), n));
    monitor->set_fixed(m.spec().fixed.data(), n);
  }
  void call(double dt) {
    const auto n = static_cast<Eigen::Index>(mass.size());
    const NodeVectors xs = node_vectors(x[0].data(), n);
    monitor->internal_forces(xs, force);
    auto g = node_scalars_out(out.data(), n);
    monitor->check(xs, node_vectors(v[0].data(), n), node_vectors(force.data(), n),
                     node_scalars(gamma.data(), n), dt, DampingPolicy::safe, 1.0, &g);
  }
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t h = v.size() / 2;
  return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
}

void measure(const char* kind, ModelSpec spec, int threads, int repeats, bool monitor) {
  Params p;
  p.policy = DampingPolicy::clamp;
  const Model model = compile_model(std::move(spec), p);
  State s = rest_state(model);
  bench::shake(model, s);
  StepWorkspace ws;
  std::optional<MonitorCase> user;  // --what monitor
  if (monitor) user.emplace(model, s);
  auto seconds = [&](int t) {
    if (monitor) {
      user->monitor->set_threads(t);
      return seconds_per_call([&] { user->call(p.dt); });
    }
    ws.pass.threads.set_threads(t);
    State run = s;
    return seconds_per_call([&] { step(model, p, run, ws); });
  };
  std::vector<double> one, many, ratio;
  for (int r = 0; r < repeats; ++r) {
    one.push_back(seconds(1));
    many.push_back(seconds(threads));
    ratio.push_back(one.back() / many.back());
  }
  const double best1 = *std::min_element(one.begin(), one.end());
  const double bestT = *std::min_element(many.begin(), many.end());
  const double ns = 1e9 / model.spec().node_count(), springs = model.spec().spring_count();
  if (monitor) {
    std::printf("%-6s %8d nodes %8d springs  1 thread %6.1f (median %6.1f)  %d threads %6.1f "
                "(median %6.1f) ns/node-call  x%.2f (pairs x%.2f to x%.2f)  monitor\n",
                kind, model.spec().node_count(), model.spec().spring_count(), best1 * ns, median(one) * ns,
                threads, bestT * ns, median(many) * ns, best1 / bestT,
                *std::min_element(ratio.begin(), ratio.end()),
                *std::max_element(ratio.begin(), ratio.end()));
    std::fflush(stdout);
    return;
  }
  const double nb = static_cast<double>(node_bytes(model, s, ws));
  const double sb = static_cast<double>(spring_bytes(model));
  std::printf("%-6s %8d nodes %8d springs  1 thread %6.1f (median %6.1f)  %d threads %6.1f "
              "(median %6.1f) ns/node-step  x%.2f (pairs x%.2f to x%.2f)  %4.0f B/node "
              "%3.0f B/spring %6.1f MB\n",
              kind, model.spec().node_count(), model.spec().spring_count(), best1 * ns, median(one) * ns,
              threads, bestT * ns, median(many) * ns, best1 / bestT,
              *std::min_element(ratio.begin(), ratio.end()),
              *std::max_element(ratio.begin(), ratio.end()), nb / double(model.spec().node_count()),
              sb / springs, (nb + sb) / 1e6);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  long max_nodes = 1100000;
  int threads = 2, repeats = 5;
  std::string mesh = "all", what = "step";
  for (int a = 1; a < argc; a += 2) {
    const std::string flag = argv[a];
    if (a + 1 == argc) {
      std::fprintf(stderr, "step_scale_bench: %s needs a value\n", argv[a]);
      return 2;
    }
    if (flag == "--max-nodes") max_nodes = std::atol(argv[a + 1]);
    else if (flag == "--threads") threads = std::atoi(argv[a + 1]);
    else if (flag == "--repeats") repeats = std::atoi(argv[a + 1]);
    else if (flag == "--mesh") mesh = argv[a + 1];
    else if (flag == "--what") what = argv[a + 1];
    else {
      std::fprintf(stderr, "step_scale_bench: unknown flag %s\n", argv[a]);
      return 2;
    }
  }
  if (threads < 1 || repeats < 1) {
    std::fprintf(stderr, "step_scale_bench: --threads and --repeats must be >= 1\n");
    return 2;
  }
  if (mesh != "plane" && mesh != "block" && mesh != "all") {
    std::fprintf(stderr, "step_scale_bench: --mesh must be plane, block or all\n");
    return 2;
  }
  if (what != "step" && what != "monitor") {
    std::fprintf(stderr, "step_scale_bench: --what must be step or monitor\n");
    return 2;
  }
  const bool monitor = what == "monitor";
  for (int n : {32, 100, 317, 1000})
    if (mesh != "block" && long(n) * n <= max_nodes)
      measure("plane", bench::plane(n), threads, repeats, monitor);
  for (int n : {10, 22, 46, 100})
    if (mesh != "plane" && long(n) * n * n <= max_nodes)
      measure("block", bench::tet_block(n, n, n), threads, repeats, monitor);
  return 0;
}
