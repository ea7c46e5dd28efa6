// A user's own simulator, not dampbound's: a hand-written semi-implicit Euler loop over a
// cloth of n x n nodes (std::vector<std::array<double, 3>>), anchored to its rest positions,
// one node pulled 5 cm out of its plane, m = kappa = 0.001, dt = 0.05 s (the paper's Fig. 1
// values). The loop has no damping (gamma = 0, below the lower bound 2 sqrt(m kappa) = 0.002
// of paper eq. 5). The same loop runs twice: plain, and guarded by dampbound's monitor, which
// reads the loop's arrays in place each step and returns the safe policy's damping
// (SPEC 9: gamma clamped into [gamma_lo_i, gamma_safe_i]). Prints both; exits 1 unless only the guarded one settles within 1000 steps.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <dampbound/monitor.hpp>
#include <dampbound/version.hpp>
#include <vector>

namespace {

using Vec = std::array<double, 3>;
constexpr int n = 12;
constexpr double h = 0.57, m = 0.001, kappa = 0.001, dt = 0.05, gamma_user = 0.0;

struct Cloth {
  std::vector<Vec> rest;
  std::vector<int> pairs;  // spring i, j, flattened
  std::vector<double> mass, stiffness, rest_length, anchor;

  Cloth() {
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) rest.push_back({a * h, 0.0, b * h});
    auto spring = [&](int i, int j) {
      pairs.insert(pairs.end(), {i, j});
      double l2 = 0;
      for (int c = 0; c < 3; ++c) l2 += (rest[j][c] - rest[i][c]) * (rest[j][c] - rest[i][c]);
      rest_length.push_back(std::sqrt(l2));
      stiffness.push_back(kappa);
    };
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) {
        if (a + 1 < n) spring(a * n + b, (a + 1) * n + b);
        if (b + 1 < n) spring(a * n + b, a * n + b + 1);
        if (a + 1 < n && b + 1 < n) spring(a * n + b, (a + 1) * n + b + 1);
      }
    mass.assign(rest.size(), m);
    anchor.assign(rest.size(), kappa);
  }

  /// The loop's own force code: springs and anchors (paper eq. 1).
  void forces(const std::vector<Vec>& x, std::vector<Vec>& f) const {
    for (size_t i = 0; i < x.size(); ++i)
      for (int c = 0; c < 3; ++c) f[i][c] = -anchor[i] * (x[i][c] - rest[i][c]);
    for (size_t s = 0; s < rest_length.size(); ++s) {
      const int i = pairs[2 * s], j = pairs[2 * s + 1];
      Vec d;
      double l2 = 0;
      for (int c = 0; c < 3; ++c) {
        d[c] = x[j][c] - x[i][c];
        l2 += d[c] * d[c];
      }
      const double l = std::sqrt(l2), scale = stiffness[s] * (l - rest_length[s]) / l;
      for (int c = 0; c < 3; ++c) f[i][c] += scale * d[c], f[j][c] -= scale * d[c];
    }
  }
};

/// Steps until max |x - X| < 0.05 cm; returns the iteration, or 0 when 1000 steps did not do.
int run(const Cloth& cloth, const dampbound::Monitor* guard) {
  const int count = static_cast<int>(cloth.rest.size());
  std::vector<Vec> x = cloth.rest, v(x.size(), Vec{}), f(x.size());
  x[(n / 2) * n + n / 2][1] += 5.0;
  std::vector<double> user_gamma(x.size(), gamma_user), g = user_gamma;
  for (int it = 1; it <= 1000; ++it) {
    cloth.forces(x, f);
    if (guard) {  // the monitor reads x, v, f and gamma in place and writes g
      auto out = dampbound::node_scalars_out(g.data(), count);
      const auto report = guard->check(dampbound::node_vectors(x[0].data(), count),
                                       dampbound::node_vectors(v[0].data(), count),
                                       dampbound::node_vectors(f[0].data(), count),
                                       dampbound::node_scalars(user_gamma.data(), count), dt,
                                       dampbound::DampingPolicy::safe, 1.0, &out);
      if (report.unguaranteed > 0 && it == 1)
        std::printf("%d nodes: critical damping cannot be guaranteed at this dt\n",
                    report.unguaranteed);
    }
    double worst = 0;
    for (size_t i = 0; i < x.size(); ++i) {
      double e2 = 0;
      for (int c = 0; c < 3; ++c) {
        v[i][c] += (f[i][c] - g[i] * v[i][c]) / cloth.mass[i] * dt;  // eq. 3
        x[i][c] += v[i][c] * dt;                                     // eq. 4
        e2 += (x[i][c] - cloth.rest[i][c]) * (x[i][c] - cloth.rest[i][c]);
      }
      worst = std::max(worst, std::sqrt(e2));
    }
    if (worst < 0.05) return it;
  }
  return 0;
}

}  // namespace

int main() {
  static_assert(sizeof(Vec) == 3 * sizeof(double), "rows of 3 packed doubles");
  const Cloth cloth;
  const int count = static_cast<int>(cloth.rest.size());
  const int springs = static_cast<int>(cloth.rest_length.size());
  dampbound::Monitor monitor(dampbound::node_scalars(cloth.mass.data(), count),
                             dampbound::spring_pairs(cloth.pairs.data(), springs),
                             dampbound::node_scalars(cloth.stiffness.data(), springs),
                             dampbound::node_scalars(cloth.rest_length.data(), springs));
  monitor.set_anchors(dampbound::node_scalars(cloth.anchor.data(), count),
                      dampbound::node_vectors(cloth.rest[0].data(), count));
  const int plain = run(cloth, nullptr), guarded = run(cloth, &monitor);
  std::printf("dampbound %s: gamma = %g, eq. 5 lower bound %g\n", DAMPBOUND_VERSION, gamma_user,
              monitor.model().lower_bound[0]);
  std::printf("plain loop:   %s %d\n", plain ? "restored at" : "not restored in",
              plain ? plain : 1000);
  std::printf("guarded loop: %s %d\n", guarded ? "restored at" : "not restored in",
              guarded ? guarded : 1000);
  return plain == 0 && guarded > 0 ? 0 : 1;
}
