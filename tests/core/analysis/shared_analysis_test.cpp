// SharedAnalysis (core/analysis/shared_analysis.hpp): exact analyses that share one model's
// certified spectrum and pattern analysis give the bits of analyses that compute everything
// anew, on every route the spectrum feeds (per mode, the symmetric index with its searches,
// SPEC 10's general damping), and take the spectrum only where A is the same matrix.
#include "core/analysis/shared_analysis.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "core/analysis/detail/shifted_cholesky.hpp"
#include "core/analysis/linear_stability_exact.hpp"
#include "dampbound/physics/model.hpp"

namespace dampbound {
namespace {

/// A flat n x n plane (spacing 0.57, diagonals, anchors) whose masses vary from node to node
/// (non-uniform gamma_i / m_i: the symmetric index and its limit searches).
ModelSpec plane(int n) {
  ModelSpec s;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const int i = add_node(s, Vec3(a * 0.57, 0, b * 0.57));
      s.anchor_scale[static_cast<size_t>(i)] = 1;
      s.mass_scale[static_cast<size_t>(i)] = 1 + 0.5 * ((a * 7 + b * 3) % 5) / 4.0;
    }
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const int i = a * n + b;
      if (a + 1 < n) add_spring(s, i, i + n);
      if (b + 1 < n) add_spring(s, i, i + 1);
      if (a + 1 < n && b + 1 < n) add_spring(s, i, i + n + 1);
    }
  return s;
}

/// Every number an analysis reports, bit for bit (NaN equal to NaN).
void expect_same_bits(const ExactStability& a, const ExactStability& b, const char* what) {
  const double got[] = {a.spectrum.lambda_min, a.spectrum.lambda_max, a.lambda_max_lo,
                        a.lambda_min_hi,       a.spectral_radius,      a.index,
                        a.gamma_lo,            a.gamma_hi,             a.dt_max,
                        a.general.index,       a.general.gamma_max,    a.general.dt_max,
                        a.general.damping_min};
  const double want[] = {b.spectrum.lambda_min, b.spectrum.lambda_max, b.lambda_max_lo,
                         b.lambda_min_hi,       b.spectral_radius,      b.index,
                         b.gamma_lo,            b.gamma_hi,             b.dt_max,
                         b.general.index,       b.general.gamma_max,    b.general.dt_max,
                         b.general.damping_min};
  for (size_t k = 0; k < sizeof(got) / sizeof(got[0]); ++k)
    EXPECT_EQ(std::memcmp(&got[k], &want[k], sizeof(double)), 0)
        << what << ": number " << k << " is " << got[k] << ", anew " << want[k];
  EXPECT_EQ(a.method, b.method) << what;
  EXPECT_EQ(a.stable, b.stable) << what;
}

TEST(SharedAnalysis, ASequenceOfChangesGivesTheBitsOfAnalysesAnew) {
  const ModelSpec spec = plane(14);  // 588 free dofs: factorisations, not the dense solver
  struct Change {
    const char* what;
    double gamma, dt, kd, alpha, beta;
  } changes[] = {
      {"the scene", 0.002, 0.05, 0, 0, 0},
      {"gamma", 0.004, 0.05, 0, 0, 0},
      {"dt", 0.004, 0.08, 0, 0, 0},
      {"dashpots", 0.004, 0.08, 0.0005, 0, 0},
      {"Rayleigh", 0.002, 0.05, 0.0005, 0.01, 0.01},
      {"no damping but gamma", 0.001, 0.05, 0, 0, 0},
  };
  ExactOptions shared;
  shared.shared = std::make_shared<SharedAnalysis>();
  int k = 0;
  for (const Change& c : changes) {
    Params p;
    p.m = 0.001;
    p.kappa = 0.001;
    p.gamma = c.gamma;
    p.dt = c.dt;
    p.kd = c.kd;
    p.rayleigh_mass = c.alpha;
    p.rayleigh_stiffness = c.beta;
    const Model model = compile_model(spec, p);
    const ExactStability with = exact_stability(model, model.spec().rest, p, shared);
    const ExactStability anew = exact_stability(model, model.spec().rest, p);
    expect_same_bits(with, anew, c.what);
    EXPECT_EQ(shared.shared->hits(), k++) << c.what;  // every change after the first: a hit
  }
  // Another state, another A: certified anew (no hit), and the same bits again.
  Params p;
  p.m = p.kappa = 0.001;
  p.gamma = 0.002;
  p.dt = 0.05;
  const Model model = compile_model(spec, p);
  std::vector<Vec3> x = model.spec().rest;
  for (Vec3& q : x) q *= 1.01;
  const int hits = shared.shared->hits();
  expect_same_bits(exact_stability(model, x, p, shared), exact_stability(model, x, p), "stretched");
  EXPECT_EQ(shared.shared->hits(), hits);
  // Another mass: another A.
  p.m = 0.002;
  const Model heavier = compile_model(spec, p);
  expect_same_bits(exact_stability(heavier, heavier.spec().rest, p, shared),
                   exact_stability(heavier, heavier.spec().rest, p), "heavier");
  EXPECT_EQ(shared.shared->hits(), hits);
}

TEST(SharedAnalysis, TakesOnlyTheSameMatrixFloorAndBudget) {
  SharedAnalysis s;
  SparseMatrix A(3, 3), B(3, 3);
  A.insert(0, 0) = 1;
  A.insert(1, 1) = 2;
  A.insert(2, 2) = 3;
  A.makeCompressed();
  B = A;
  B.coeffRef(2, 2) = 3 + 1e-15 * 3;
  CertifiedSpectrum ends;
  ends.largest = {3, 3};
  ends.smallest = {1, 1};
  std::unique_ptr<detail::ShiftedCholesky> factors;
  EXPECT_FALSE(s.take(A, std::nullopt, 1e9, ends, factors));  // nothing remembered yet
  s.remember(A, std::nullopt, 1e9, ends);
  CertifiedSpectrum got;
  EXPECT_FALSE(s.take(B, std::nullopt, 1e9, got, factors));  // one value's last bits
  EXPECT_FALSE(s.take(A, 0.5, 1e9, got, factors));           // another floor
  EXPECT_FALSE(s.take(A, std::nullopt, 2e9, got, factors));  // another budget
  EXPECT_TRUE(s.take(A, std::nullopt, 1e9, got, factors));
  EXPECT_EQ(got.largest.hi, 3);
  EXPECT_EQ(got.smallest.lo, 1);
  EXPECT_EQ(s.hits(), 1);
}

}  // namespace
}  // namespace dampbound
