// Every verdict of the exact analysis against what the step does, on random meshes: flat and
// solid point clouds of 170 to 270 nodes (above the dense-eigenvalue size, so the sparse
// Cholesky path runs), springs to the nearest neighbours, some nodes fixed, every free node
// anchored (no zero modes), masses uniform or up to 3x apart, a third damped unequally (0.5
// to 2 times gamma), under every integrator. At the scene's point and at points just inside
// and outside each limit:
//   - the exact verdict (stable, spectral radius) agrees with a run of step() from a random
//     perturbation: it decays where rho < 1 and grows where rho > 1 (run_growth);
//   - the exact limits are limits: 3 % inside is stable, 3 % outside is not (except the
//     frozen-rate estimates of forward Euler, Verlet and RK4 at non-uniform rates);
//   - SPEC 9's safe bound holds: just below every node's gamma_safe_i or dt_safe_i the paper's
//     step is stable;
//   - what is proved over the factorisation budget (ExactStability::unfactored) never
//     contradicts the exact analysis: each "proved stable" range holds stable points, each
//     "proved unstable" threshold unstable ones.
// The same at deformed equilibria: the mesh held pre-stretched (rest lengths shortened) or
// displaced (some springs stretched, some compressed, the tangent stiffness possibly
// indefinite) by external forces that balance its internal ones there, or loaded and at the
// equilibrium static_equilibrium finds; the analysis linearises at that state and the runs
// start from it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/analysis/equilibrium.hpp"
#include "core/analysis/linear_stability_exact.hpp"
#include "core/analysis/perturbation_growth.hpp"
#include "core/physics/safe_bound.hpp"
#include "dampbound/physics/forces.hpp"
#include "dampbound/physics/model.hpp"
#include "dampbound/physics/params.hpp"

namespace dampbound {
namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr unsigned kDefaultSeeds = 1;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr unsigned kDefaultSeeds = 1;
#else
constexpr unsigned kDefaultSeeds = 8;
#endif
#else
constexpr unsigned kDefaultSeeds = 8;
#endif

/// A linear congruential sequence: the same meshes on every machine.
struct Lcg {
  unsigned s;
  double uniform() {  // in [0, 1)
    s = s * 1103515245u + 12345u;
    return static_cast<double>((s >> 8) & 0xffffu) / 65536.0;
  }
  double in(double lo, double hi) { return lo + (hi - lo) * uniform(); }
};

struct RandomMesh {
  ModelSpec spec;
  std::string what;
};

RandomMesh random_mesh(unsigned seed, bool gamma_scales = true) {
  Lcg r{seed};
  RandomMesh out;
  ModelSpec& spec = out.spec;
  const int n = 170 + static_cast<int>(r.uniform() * 100);
  const bool flat = r.uniform() < 0.5;
  const bool masses = r.uniform() < 0.5;
  const int k = 3 + static_cast<int>(r.uniform() * 4);  // neighbours per node
  for (int i = 0; i < n; ++i)
    add_node(spec, Vec3(r.in(0, 10), r.in(0, 10), flat ? 0.0 : r.in(0, 10)));
  std::set<std::pair<int, int>> springs;
  for (int i = 0; i < n; ++i) {
    std::vector<std::pair<double, int>> d;
    for (int j = 0; j < n; ++j)
      if (j != i) d.push_back({(spec.rest[i] - spec.rest[j]).squaredNorm(), j});
    std::partial_sort(d.begin(), d.begin() + k, d.end());
    for (int a = 0; a < k; ++a) {
      const int j = d[static_cast<size_t>(a)].second;
      if (springs.insert({std::min(i, j), std::max(i, j)}).second)
        add_spring(spec, std::min(i, j), std::max(i, j), r.in(0.5, 2.0));
    }
  }
  for (int i = 0; i < n; ++i) {
    if (r.uniform() < 0.07) spec.fixed[static_cast<size_t>(i)] = 1;
    spec.anchor_scale[static_cast<size_t>(i)] = r.in(0.05, 1.0);
    if (masses) spec.mass_scale[static_cast<size_t>(i)] = r.in(1.0, 3.0);
  }
  // A third of the meshes damp their nodes unequally (gamma_i = gamma * 0.5 to 2), drawn from
  // a sequence of their own so that the rest of the mesh stays as it was.
  Lcg g{seed * 104729u};
  const bool unequal = gamma_scales && g.uniform() < 1.0 / 3;
  if (unequal)
    for (double& s : spec.gamma_scale) s = g.in(0.5, 2.0);
  char buf[200];
  std::snprintf(buf, sizeof buf, "seed %u: %d nodes, %zu springs, %s, masses %s, damping %s", seed,
                n, springs.size(), flat ? "flat" : "solid", masses ? "1 to 3" : "uniform",
                unequal ? "0.5 to 2" : "uniform");
  out.what = buf;
  return out;
}

/// The run's verdict: growth after enough steps that rho^steps is 1e-4, or 1e8 where rho > 1
/// (at most 6000): a random perturbation can give the growing mode a small part (4e-5 of
/// the start on a forward Euler mesh at rho 1.06: decayed to 0.46 after 100 steps, 3.7
/// after 200).
double run_growth(const ModelSpec& spec, const std::vector<Vec3>& x, const Params& q, double rho) {
  const Model m = compile_model(spec, q);
  const double rate = std::abs(std::log(rho));
  const double factor = rho > 1 ? 1e8 : 1e4;
  const int steps = static_cast<int>(std::min(6000.0, std::ceil(std::log(factor) / rate)));
  return perturbation_growth(m, x, q, steps, 1e-6);
}

/// A mesh and the positions where its verdicts are taken: an equilibrium (F_i + f_i = 0 at
/// every free node), where the analysis linearises and the runs start.
struct RandomCase {
  ModelSpec spec;
  std::vector<Vec3> x;
  std::string what;
  int compressed = 0;  ///< springs shorter than their rest length at x
};

RandomCase at_rest(const RandomMesh& mesh) {
  return {mesh.spec, mesh.spec.rest, mesh.what, 0};
}

/// How a mesh is held away from rest: pre-stretched (every rest length 0.7 to 0.95 of its
/// spring, x = X: all springs in tension, K >= 0), nudged (every free node moved by up to 0.5
/// to 3 % of the mean spring length: some springs compressed, K mostly still positive
/// definite) or displaced (by up to 5 to 20 %: K indefinite on most meshes, and then no
/// damping makes an explicit step stable, and the runs grow).
enum class Held { pre_stretched, nudged, displaced, loaded };

/// The mesh held at x by external forces f_i = -F_i(x).
RandomCase held_deformed(const RandomMesh& mesh, unsigned seed, Held how) {
  RandomCase c{mesh.spec, mesh.spec.rest, mesh.what, 0};
  Lcg r{seed * 15485863u + static_cast<unsigned>(how)};
  double mean = 0;
  for (const Spring& s : c.spec.springs) mean += s.rest_length / c.spec.spring_count();
  if (how == Held::loaded) {
    // Loaded: every free node pushed by up to 0.05 kappa times the mean spring length, and
    // the equilibrium where the load is balanced found by static_equilibrium.
    const double f = 0.05 * Params{}.kappa * mean;
    for (size_t i = 0; i < c.x.size(); ++i)
      if (!c.spec.fixed[i])
        c.spec.external_force[i] = f * Vec3(r.in(-1, 1), r.in(-1, 1), r.in(-1, 1));
    const Equilibrium e = static_equilibrium(compile_model(c.spec, Params{}));
    EXPECT_TRUE(e.converged) << c.what << ": net force " << e.net.largest << " of "
                             << e.net.scale << " after " << e.iterations << " steps";
    c.x = e.x;
    for (const Spring& s : c.spec.springs)
      if ((c.x[static_cast<size_t>(s.j)] - c.x[static_cast<size_t>(s.i)]).norm() < s.rest_length)
        ++c.compressed;
    char buf[120];
    std::snprintf(buf, sizeof buf, ", loaded (%d of %d springs compressed, %d Newton steps)",
                  c.compressed, c.spec.spring_count(), e.iterations);
    c.what += buf;
    return c;
  }
  if (how == Held::pre_stretched) {
    for (Spring& s : c.spec.springs) s.rest_length *= r.in(0.7, 0.95);
  } else {
    const double a = (how == Held::nudged ? r.in(0.005, 0.03) : r.in(0.05, 0.2)) * mean;
    for (size_t i = 0; i < c.x.size(); ++i)
      if (!c.spec.fixed[i]) c.x[i] += a * Vec3(r.in(-1, 1), r.in(-1, 1), r.in(-1, 1));
  }
  const Model m = compile_model(c.spec, Params{});  // F depends on kappa, not gamma or dt
  std::vector<Vec3> F;
  internal_forces(m, c.x, F);
  for (size_t i = 0; i < F.size(); ++i)
    c.spec.external_force[i] = c.spec.fixed[i] ? Vec3::Zero() : Vec3(-F[i]);
  for (const Spring& s : c.spec.springs)
    if ((c.x[static_cast<size_t>(s.j)] - c.x[static_cast<size_t>(s.i)]).norm() < s.rest_length)
      ++c.compressed;
  char buf[120];
  const char* name[] = {"pre-stretched", "nudged", "displaced"};
  std::snprintf(buf, sizeof buf, ", held %s (%d of %d springs compressed)",
                name[static_cast<int>(how)], c.compressed, c.spec.spring_count());
  c.what += buf;
  return c;
}

struct Checked {
  int runs = 0, claims = 0;
};

/// The exact analysis at q, its verdict checked by a run where rho is 2e-3 or more from 1.
ExactStability exact_at(const RandomCase& c, const Params& q, const std::string& where,
                        Checked& checked) {
  const Model m = compile_model(c.spec, q);
  const ExactStability e = exact_stability(m, c.x, q);
  EXPECT_TRUE(e.computed()) << where;
  if (!std::isfinite(e.spectral_radius)) return e;
  EXPECT_EQ(e.stable, e.spectral_radius <= 1) << where << " rho " << e.spectral_radius;
  if (std::abs(e.spectral_radius - 1) >= 2e-3 && e.radius_converged) {
    const double g = run_growth(c.spec, c.x, q, e.spectral_radius);
    ++checked.runs;
    if (e.spectral_radius < 1)
      EXPECT_LT(g, 1.0) << where << ": rho " << e.spectral_radius << " but the run grew " << g;
    else
      EXPECT_GT(g, 1.0) << where << ": rho " << e.spectral_radius << " but the run decayed " << g;
  }
  return e;
}

/// Every verdict at one case, for every integrator at a random gamma and dt (drawn from r).
void check_case(const RandomCase& c, Lcg& r, Checked& checked) {
  for (Integrator in : {Integrator::semi_implicit_euler, Integrator::forward_euler,
                        Integrator::verlet, Integrator::rk4, Integrator::implicit_euler}) {
    Params p;
    p.policy = DampingPolicy::fixed;
    p.integrator = in;
    p.gamma = r.in(0.0005, 0.02);
    p.dt = r.in(0.01, 0.3);
    const std::string where = c.what + ", " + to_string(in);
    char at[96];
    std::snprintf(at, sizeof at, ", gamma %.6g, dt %.6g", p.gamma, p.dt);
    const ExactStability e = exact_at(c, p, where + at, checked);
    // Just inside and just outside each exact limit.
    auto probe = [&](const char* what, Params q, bool stable) {
      std::snprintf(at, sizeof at, ", %s: gamma %.9g, dt %.9g", what, q.gamma, q.dt);
      const ExactStability eq = exact_at(c, q, where + at, checked);
      // Frozen-rate limits are estimates, labelled so (docs/criteria.md): a few per cent off
      // on a wide range of rates. Their points still check Arnoldi's verdict against a run.
      if (e.method != ExactMethod::frozen_estimate) {
        EXPECT_EQ(eq.stable, stable) << where << at;
      }
    };
    if (std::isfinite(e.dt_max) && e.dt_max > 0) {
      Params q = p;
      q.dt = 0.97 * e.dt_max;
      probe("0.97 dt_max", q, true);
      q.dt = 1.03 * e.dt_max;
      probe("1.03 dt_max", q, false);
    }
    if (e.gamma_lo < e.gamma_hi && std::isfinite(e.gamma_hi)) {
      Params q = p;
      q.gamma = 0.97 * e.gamma_hi;
      probe("0.97 gamma_hi", q, true);
      q.gamma = 1.03 * e.gamma_hi;
      probe("1.03 gamma_hi", q, false);
    }
    if (e.gamma_lo > 0 && e.gamma_lo < e.gamma_hi) {
      Params q = p;
      q.gamma = 0.97 * e.gamma_lo;
      probe("0.97 gamma_lo", q, false);
      q.gamma = std::min(1.03 * e.gamma_lo, 0.5 * (e.gamma_lo + e.gamma_hi));
      probe("above gamma_lo", q, true);
    }
    const Model m = compile_model(c.spec, p);
    // SPEC 9: below every node's gamma_safe_i, or dt_safe_i, the paper's step is stable
    // where no spring is compressed (with one, K may be indefinite: no promise).
    const SafeBoundSummary safe = safe_bound_summary(m, c.x, p.dt);
    EXPECT_EQ(safe.compressed_springs, c.compressed) << where;
    if (in == Integrator::semi_implicit_euler && c.compressed == 0) {
      // The user's gamma with gamma_i = gamma * scale_i < gamma_safe_i at every free node.
      std::vector<double> R;
      safe_row_sums(m, c.x, R);
      double gamma_safe = std::numeric_limits<double>::infinity();
      for (size_t i = 0; i < R.size(); ++i)
        if (!m.spec().fixed[i])
          gamma_safe = std::min(gamma_safe, safe_gamma(m.mass[i], p.dt, R[i]) / m.spec().gamma_scale[i]);
      EXPECT_EQ(safe.gamma_safe, gamma_safe) << where;  // the summary's is the user's gamma
      if (gamma_safe > 0) {
        Params q = p;
        q.gamma = 0.999 * gamma_safe;
        probe("0.999 gamma_safe (SPEC 9)", q, true);
        ++checked.claims;
      }
      Params q = p;
      q.dt = 0.999 * safe.dt_safe;
      probe("0.999 dt_safe (SPEC 9)", q, true);
      ++checked.claims;
    }
    // Over the budget: what is proved must hold in the exact analysis.
    ExactOptions tight;
    tight.max_factor_flops = 1;
    const ExactStability o = exact_stability(m, c.x, p, tight);
    if (o.computed()) continue;  // 400 free rows or fewer: dense eigenvalues, no budget
    const auto& u = o.unfactored;
    auto claim = [&](const char* what, Params q, bool stable) {
      ++checked.claims;
      const Model mq = compile_model(c.spec, q);
      const ExactStability eq = exact_stability(mq, c.x, q);
      std::snprintf(at, sizeof at, ", over the budget %s: gamma %.9g, dt %.9g", what, q.gamma,
                    q.dt);
      EXPECT_EQ(eq.stable, stable)
          << where << at << " (exact rho " << eq.spectral_radius << ", exact gamma_hi "
          << std::setprecision(17) << e.gamma_hi << " dt_max " << e.dt_max << " lambda_max ["
          << e.lambda_max_lo << ", " << e.spectrum.lambda_max << "], lower bound "
          << u.lambda_max_lo << ")";
    };
    if (o.stable) claim("the scene's point, proved stable", p, true);
    EXPECT_LE(u.lambda_max_lo, e.spectrum.lambda_max) << where;
    EXPECT_GE(u.lambda_max_hi, e.lambda_max_lo) << where;
    if (u.index_at_least >= 4) claim("index at least 4", p, false);
    if (std::isfinite(u.mode_unstable_from) && u.lambda_max_lo >= u.mode_unstable_from)
      claim("a mode proved unstable", p, false);
    if (std::isfinite(u.dt_stable_up_to) && u.dt_stable_up_to > 0) {
      Params q = p;
      q.dt = u.dt_stable_up_to;
      claim("dt_stable_up_to", q, true);
    }
    if (std::isfinite(u.gamma_stable_lo) && u.gamma_stable_lo <= u.gamma_stable_hi) {
      Params q = p;
      q.gamma = u.gamma_stable_lo;
      claim("gamma_stable_lo", q, true);
      q.gamma = u.gamma_stable_hi;
      if (std::isfinite(q.gamma)) claim("gamma_stable_hi", q, true);
    }
    if (std::isfinite(u.dt_unstable_from)) {
      Params q = p;
      q.dt = u.dt_unstable_from;
      claim("dt_unstable_from", q, false);
    }
    if (std::isfinite(u.gamma_unstable_from)) {
      Params q = p;
      q.gamma = u.gamma_unstable_from;
      claim("gamma_unstable_from", q, false);
    }
    if (std::isfinite(u.gamma_unstable_below) && u.gamma_unstable_below >= 0) {
      Params q = p;
      q.gamma = u.gamma_unstable_below;
      claim("gamma_unstable_below", q, false);
    }
    if (u.unconditional) claim("unconditional", p, true);
  }
}

/// DAMPBOUND_VERDICT_SEEDS=N: meshes 1..N (default 8, 1 under ASan, where 8 took over 220 s;
/// docs/criteria.md gives a longer run).
unsigned seed_count() {
  const char* env = std::getenv("DAMPBOUND_VERDICT_SEEDS");
  return env != nullptr && std::atoi(env) > 0 ? static_cast<unsigned>(std::atoi(env))
                                              : kDefaultSeeds;
}

TEST(VerdictsOnRandomMeshes, TheExactAnalysisAndWhatIsProvedOverTheBudgetAgreeWithTheRuns) {
  Checked checked;
  const unsigned seeds = seed_count();
  for (unsigned seed = 1; seed <= seeds; ++seed) {
    Lcg r{seed * 7919u};
    check_case(at_rest(random_mesh(seed)), r, checked);
  }
  std::printf("runs checked: %d, claims checked (SPEC 9, over the budget): %d\n", checked.runs,
              checked.claims);
  EXPECT_GE(checked.runs, 10 * static_cast<int>(seeds));
  EXPECT_GE(checked.claims, 10 * static_cast<int>(seeds));
}

TEST(VerdictsOnRandomMeshes, AtDeformedEquilibriaTheAnalysisAgreesWithTheRuns) {
  Checked checked;
  const unsigned seeds = seed_count();
  int indefinite = 0, compressed = 0;
  for (unsigned seed = 1; seed <= seeds; ++seed) {
    const RandomMesh mesh = random_mesh(seed);
    for (Held how : {Held::pre_stretched, Held::nudged, Held::displaced, Held::loaded}) {
      const RandomCase c = held_deformed(mesh, seed, how);
      if (how == Held::pre_stretched) {
        EXPECT_EQ(c.compressed, 0) << c.what;
      }
      compressed += c.compressed > 0;
      const Model m = compile_model(c.spec, Params{});
      indefinite += exact_stability(m, c.x, Params{}).indefinite;
      Lcg r{seed * 7919u + 1u + static_cast<unsigned>(how)};
      check_case(c, r, checked);
    }
  }
  std::printf("runs checked: %d, claims checked (SPEC 9, over the budget): %d; of %u states %d "
              "with compressed springs, %d with K indefinite\n",
              checked.runs, checked.claims, 4 * seeds, compressed, indefinite);
  EXPECT_GE(checked.runs, 10 * static_cast<int>(seeds));
  EXPECT_GT(compressed, indefinite);  // some compressed states keep K >= 0
  EXPECT_GT(indefinite, 0);
}

// What the random meshes found: Spectra's Arnoldi on G^4 reported success with Ritz pairs
// whose residual was as large as theta (|theta|^(1/4) = 1.856, the steps decay: dense
// eigenvalues give 0.99381944), so Verlet was called unstable where it decays. Each pair is now
// checked by a product, and G^2 or G taken when one fails (linear_stability_modes.cpp).
TEST(VerdictsOnRandomMeshes, ArnoldiRitzPairsAreCheckedBeforeTheyAreBelieved) {
  const RandomMesh mesh = random_mesh(117, false);
  Params q;
  q.policy = DampingPolicy::fixed;
  q.integrator = Integrator::verlet;
  q.gamma = 0.0014581;
  q.dt = 0.169076;
  const Model m = compile_model(mesh.spec, q);
  const ExactStability e = exact_stability(m, m.spec().rest, q);
  EXPECT_EQ(e.method, ExactMethod::frozen_estimate);
  EXPECT_TRUE(e.radius_converged);
  EXPECT_NEAR(e.spectral_radius, 0.99381944, 1e-7);  // dense: 0.993819438386
  EXPECT_TRUE(e.stable);
  EXPECT_LT(perturbation_growth(m, q, 640, 1e-6), 0.05);  // 0.009
}

}  // namespace
}  // namespace dampbound
