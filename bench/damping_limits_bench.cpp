// SPEC 10's exact limits of a scene, timed: general_limits (the index at the scene's gamma and
// dt, lambda_min(C^), and the gamma and dt limits by definiteness, detail/definite_root.hpp).
// bench/damping_limits_vs_scipy.py runs it beside an independent SciPy route on the same
// matrices (--matrix writes them).
//
//   damping_limits_bench SCENE [--matrix PREFIX] [--repeats R]
//
// --matrix: PREFIX.A, PREFIX.Cp, PREFIX.G in exact_limits_bench's format (A = M^-1/2 K M^-1/2,
// Cp the damping besides the nodal one, G the nodal damping per unit gamma, all weighted).
// Prints one line of key=value pairs; times in seconds (wall clock, and processor time).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "bench/matrix_file.hpp"
#include "core/analysis/damping_limits.hpp"
#include "core/io/scene_file.hpp"
#include "dampbound/physics/stiffness.hpp"

namespace {

using namespace dampbound;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
double cpu_now() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: damping_limits_bench SCENE [--matrix PREFIX] [--repeats R]\n");
    return 2;
  }
  std::string prefix;
  int repeats = 1;
  for (int k = 2; k < argc; k += 2) {
    const std::string flag = argv[k];
    if (k + 1 >= argc || (flag != "--matrix" && flag != "--repeats")) {
      std::fprintf(stderr, "damping_limits_bench: unknown or incomplete option %s\n", argv[k]);
      return 2;
    }
    if (flag == "--matrix") {
      prefix = argv[k + 1];
    } else {
      repeats = std::atoi(argv[k + 1]);
      if (repeats < 1 || repeats > 100) {
        std::fprintf(stderr, "damping_limits_bench: --repeats must be in 1..100\n");
        return 2;
      }
    }
  }
  SceneSpec scene;
  try {
    scene = load_scene(argv[1]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "damping_limits_bench: %s\n", e.what());
    return 2;
  }
  const Params p = scene.params;
  const Model model = compile_model(scene.model, p);
  const std::vector<Vec3>& x = model.spec().rest;
  std::vector<double> wall, cpu;
  GeneralLimits g;
  for (int r = 0; r < repeats; ++r) {
    const auto t = Clock::now();
    const double c = cpu_now();
    const GeneralLimits run = general_limits(model, x, p);
    wall.push_back(since(t));
    cpu.push_back(cpu_now() - c);
    if (r > 0 && (run.dt_max != g.dt_max || run.gamma_max != g.gamma_max)) {
      std::fprintf(stderr, "damping_limits_bench: run %d gave other limits than the first\n", r + 1);
      return 1;
    }
    g = run;
  }
  std::sort(wall.begin(), wall.end());
  std::sort(cpu.begin(), cpu.end());
  const SparseMatrix A = mass_weighted(model, tangent_stiffness(model, x));
  std::printf(
      "scene=%s rows=%lld dt=%.17g gamma=%.17g index=%.12g gamma_max=%.12g dt_max=%.12g "
      "commuting=%d limits_best_s=%.3f limits_cpu_best_s=%.3f runs=%d\n",
      argv[1], static_cast<long long>(A.rows()), p.dt, p.gamma, g.index, g.gamma_max, g.dt_max,
      g.commuting ? 1 : 0, wall.front(), cpu.front(), repeats);
  if (!prefix.empty()) {
    const SparseMatrix Cp =
        weighted_damping(model, x, std::vector<double>(model.spec().rest.size(), 0.0));
    std::vector<double> unit(model.spec().rest.size());
    for (size_t i = 0; i < unit.size(); ++i) unit[i] = model.spec().gamma_scale[i];
    const SparseMatrix G = weighted_damping(model, x, unit) - Cp;
    bench::write_matrix(A, prefix + ".A");
    bench::write_matrix(Cp, prefix + ".Cp");
    bench::write_matrix(G, prefix + ".G");
  }
  return 0;
}
