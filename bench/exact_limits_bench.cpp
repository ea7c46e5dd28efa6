// Exact limits of big meshes (SPEC 7, 9), timed: the certified lambda_max of M^-1 K (sparse
// Cholesky: Gershgorin, shift-and-invert, a factorisation as certificate), the semi-implicit
// step's exact_stability (both ends of the spectrum, the gamma interval, the dt limit) and
// every other integrator's limits from that spectrum. bench/exact_vs_scipy.py runs it beside
// SciPy's eigsh on the same matrix (--matrix writes it).
//
//   exact_limits_bench plane N | block N [--matrix FILE] [--threads T] [--repeats R]
//
// --threads: the Lanczos products' threads (default 0: one per CPU; the same bits on any).
// --repeats: every limit computed R times (default 1), for a machine shared with other jobs:
// all_limits_s is the first run, all_limits_best_s and all_limits_median_s over all R (the
// results are the same bits every time; the program stops if they are not).
// Prints one line of key=value pairs; times in seconds (wall clock).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "bench/bench_meshes.hpp"
#include "bench/matrix_file.hpp"
#include "core/analysis/linear_stability_cholesky.hpp"
#include "core/analysis/linear_stability_exact.hpp"

namespace {

using namespace dampbound;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
/// Processor time of this process (s): on a machine shared with other jobs, the fair measure.
double cpu_now() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || (std::string(argv[1]) != "plane" && std::string(argv[1]) != "block")) {
    std::fprintf(stderr,
                 "usage: exact_limits_bench plane N | block N [--matrix FILE] [--threads T] "
                 "[--repeats R]\n");
    return 2;
  }
  const std::string kind = argv[1];
  const int n = std::atoi(argv[2]);
  std::string matrix_path;
  int threads = 0, repeats = 1;
  for (int k = 3; k < argc; k += 2) {
    const std::string flag = argv[k];
    if (k + 1 >= argc || (flag != "--matrix" && flag != "--threads" && flag != "--repeats")) {
      std::fprintf(stderr, "exact_limits_bench: unknown or incomplete option %s\n", argv[k]);
      return 2;
    }
    if (flag == "--matrix") {
      matrix_path = argv[k + 1];
      continue;
    }
    char* end = nullptr;
    const long t = std::strtol(argv[k + 1], &end, 10);
    const long lowest = flag == "--threads" ? 0 : 1;
    if (end == argv[k + 1] || *end != '\0' || t < lowest || t > 1024) {
      std::fprintf(stderr, "exact_limits_bench: %s must be an integer in %ld..1024, not '%s'\n",
                   flag.c_str(), lowest, argv[k + 1]);
      return 2;
    }
    (flag == "--threads" ? threads : repeats) = static_cast<int>(t);
  }
  if (n < 2) {
    std::fprintf(stderr, "exact_limits_bench: N must be >= 2\n");
    return 2;
  }
  const Params p;  // m = kappa = 0.001, gamma = 0.002, dt = 0.05: the paper's Fig. 1 setting
  const Model model =
      compile_model(kind == "plane" ? bench::plane(n) : bench::tet_block(n, n, n), p);

  auto t = Clock::now();
  const SparseMatrix A =
      mass_weighted(model, tangent_stiffness(model, model.spec().rest, false, threads), threads);
  const double t_assemble = since(t);
  t = Clock::now();
  double c = cpu_now();
  const EigenInterval top = certified_largest_eigenvalue(A, nullptr, threads);
  const double t_lambda = since(t), c_lambda = cpu_now() - c;
  // Every limit: both ends of the spectrum (exact_stability), then the other integrators'.
  const auto every_limit = [&] {
    const ExactStability e = exact_stability(model, model.spec().rest, p, {false, threads});
    double worst = e.dt_max;  // keeps the other integrators' limits from being optimised away
    for (Integrator i : {Integrator::forward_euler, Integrator::verlet, Integrator::rk4,
                         Integrator::implicit_euler}) {
      const double rate = p.gamma / p.m;
      const RateInterval r = uniform_rate_interval(i, e.spectrum, p.dt);
      worst = std::min({worst, uniform_dt_max(i, e.spectrum, rate), r.hi});
    }
    return std::make_pair(e, worst);
  };
  std::vector<double> wall;
  double c_all = 0;
  ExactStability e;
  double worst = 0;
  for (int r = 0; r < repeats; ++r) {
    t = Clock::now();
    c = cpu_now();
    const auto [er, wr] = every_limit();
    wall.push_back(since(t));
    if (r == 0) {
      c_all = cpu_now() - c;
      e = er;
      worst = wr;
    } else if (std::memcmp(&wr, &worst, sizeof wr) != 0 || er.dt_max != e.dt_max ||
               er.gamma_hi != e.gamma_hi) {
      std::fprintf(stderr, "exact_limits_bench: run %d gave other limits than the first\n", r + 1);
      return 1;
    }
  }
  const double t_all = wall.front();
  std::sort(wall.begin(), wall.end());
  const double best = wall.front(), median = wall[wall.size() / 2];
  std::printf(
      "kind=%s n=%d threads=%d nodes=%d springs=%d rows=%lld nnz=%lld assemble_s=%.3f "
      "lambda_max_lo=%.12g lambda_max_hi=%.12g lambda_s=%.3f lambda_cpu_s=%.3f "
      "lanczos_steps=%d factorizations=%d solves=%d lambda_min=%.10g gamma_max=%.10g dt_max=%.10g "
      "all_limits_s=%.3f all_limits_cpu_s=%.3f all_limits_runs=%d all_limits_best_s=%.3f "
      "all_limits_median_s=%.3f check=%.3g\n",
      kind.c_str(), n, threads, model.spec().node_count(), model.spec().spring_count(),
      static_cast<long long>(A.rows()), static_cast<long long>(A.nonZeros()), t_assemble, top.lo,
      top.hi, t_lambda, c_lambda, top.lanczos_steps, top.factorizations, top.solves,
      e.spectrum.lambda_min, e.gamma_hi, e.dt_max, t_all, c_all, repeats, best, median, worst);
  if (!matrix_path.empty()) bench::write_matrix(A, matrix_path);
  return 0;
}
