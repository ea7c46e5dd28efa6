// An OpenMP program that links libdampbound_core.so, as a user's simulator would: its parallel
// regions keep their team size in the main thread and while a dampbound analysis (CHOLMOD,
// which runs its own OpenMP loops) runs on another thread, and the runtime's entry points are
// libgomp's, not the library's. Exit 0 when all holds; one line per failure otherwise.
#include <dlfcn.h>
#include <omp.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <thread>
#include <vector>

#include "dampbound/monitor.hpp"

namespace {

int failures = 0;
void expect(bool ok, const char* what) {
  if (!ok) {
    std::printf("openmp_host: FAILED: %s\n", what);
    ++failures;
  }
}

/// The team size a region of `wanted` threads gets here.
int team_of(int wanted) {
  int seen = 0;
#pragma omp parallel num_threads(wanted)
  {
#pragma omp single
    seen = omp_get_num_threads();
  }
  return seen;
}

/// An n x n plane of unit masses and springs, stretched a little: 3 n^2 unknowns, above
/// the size the analysis factors with CHOLMOD.
struct Plane {
  std::vector<double> mass, kappa, rest, x;
  std::vector<int> pairs;
  explicit Plane(int n) {
    auto id = [n](int i, int j) { return i * n + j; };
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        mass.push_back(1.0);
        x.insert(x.end(), {1.01 * i, 1.01 * j, 0.001 * ((i * 7 + j * 3) % 5)});
        if (j + 1 < n) pairs.insert(pairs.end(), {id(i, j), id(i, j + 1)});
        if (i + 1 < n) pairs.insert(pairs.end(), {id(i, j), id(i + 1, j)});
      }
    kappa.assign(pairs.size() / 2, 1.0);
    rest.assign(pairs.size() / 2, 1.0);
  }
};

}  // namespace

int main() {
  const char* where = "?";
  Dl_info info{};
  if (void* entry = dlsym(RTLD_DEFAULT, "GOMP_parallel"); entry && dladdr(entry, &info))
    where = info.dli_fname;
  expect(std::strstr(where, "libgomp") != nullptr,
         "GOMP_parallel is not libgomp's (another library interposes it)");
  std::printf("openmp_host: GOMP_parallel from %s\n", where);

  const int wanted = 3;
  expect(team_of(wanted) == wanted, "a region in the main thread lost its team");
  const int levels = omp_get_max_active_levels();

  using namespace dampbound;
  Plane plane(40);
  const Eigen::Index nodes = static_cast<Eigen::Index>(plane.mass.size());
  const Eigen::Index springs = static_cast<Eigen::Index>(plane.kappa.size());
  Monitor monitor(node_scalars(plane.mass.data(), nodes), spring_pairs(plane.pairs.data(), springs),
                  node_scalars(plane.kappa.data(), springs), node_scalars(plane.rest.data(), springs));
  std::vector<double> gamma(plane.mass.size(), 0.1);

  std::atomic<int> analyses{0};
  std::atomic<bool> done{false};
  std::thread analysis([&] {
    for (int k = 0; k < 3; ++k) {
      const MonitorLimits limits = monitor.exact_limits(
          node_vectors(plane.x.data(), nodes), node_scalars(gamma.data(), nodes), 0.01);
      if (limits.lambda_max > 0) ++analyses;
    }
    done = true;
  });
  long regions = 0, short_teams = 0;
  while (!done) {
    if (team_of(wanted) != wanted) ++short_teams;
    ++regions;
  }
  analysis.join();
  expect(analyses == 3, "the analysis beside the regions did not finish");
  expect(regions > 0 && short_teams == 0, "a region beside the analysis lost its team");
  expect(omp_get_max_active_levels() == levels, "the main thread's max-active-levels changed");
  expect(team_of(wanted) == wanted, "a region after the analysis lost its team");
  std::printf("openmp_host: %ld regions of %d threads beside %d analyses, %ld short\n", regions,
              wanted, analyses.load(), short_teams);
  return failures == 0 ? 0 : 1;
}
