// SPEC 11's mass scaling against dense references of its own: the local rule's masses from
// K and C assembled densely spring by spring, every row of 4M' - 2 dt_g C - dt_g^2 K dominant,
// the tightened s* from a dense eigenvalue bisection, the scaled model stable at dt* by the
// spectral radius of the dense amplification matrix, the cap and the two special answers.
#include "core/analysis/mass_scaling.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "core/analysis/damping_limits.hpp"
#include "core/analysis/mass_scaling_scene.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

/// SPEC 11's example: an 8 x 8 plane of the paper's kind (anchors, spacing 0.57), node 0
/// fixed, the 2 x 2 patch (3..4, 3..4) at mass_scale 0.1.
ModelSpec spec_plane(int n = 8) {
  ModelSpec s = make_grid({n, n, 0.57, true, true});
  s.fixed[0] = 1;
  for (int a : {3, 4})
    for (int b : {3, 4}) s.mass_scale[static_cast<size_t>(a * n + b)] = 0.1;
  return s;
}

Params spec_params(double kd = 0) {
  Params p;
  p.m = p.kappa = 0.001;
  p.gamma = 0.002;
  p.kd = kd;
  return p;
}

/// A plane with everything SPEC 10 has: random masses, stiffnesses and dashpot scales, two
/// fixed nodes, anchors on half the nodes.
ModelSpec mixed_plane(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.3, 2.0);
  ModelSpec s = make_grid({n, n, 0.5, true, false});
  for (size_t i = 0; i < s.rest.size(); ++i) {
    s.mass_scale[i] = u(rng);
    s.anchor_scale[i] = i % 2 ? u(rng) : 0.0;
    s.gamma_scale[i] = u(rng);
  }
  for (Spring& sp : s.springs) sp.kappa_scale = u(rng), sp.kd_scale = u(rng);
  s.fixed[0] = s.fixed[static_cast<size_t>(n * n - 1)] = 1;
  return s;
}

/// K and C' = C - alpha M at rest, dense over the free nodes, assembled here spring by spring
/// (SPEC 7's kappa d d^T, SPEC 10's kd d d^T and beta K, anchors isotropic).
struct Dense {
  Eigen::MatrixXd K, C;
  Eigen::VectorXd m;  // per free node
};
Dense dense(const Model& model) {
  const ModelSpec& s = model.spec();
  std::vector<int> block(s.rest.size(), -1);
  int n = 0;
  for (size_t i = 0; i < s.rest.size(); ++i)
    if (!s.fixed[i]) block[i] = n++;
  Dense d{Eigen::MatrixXd::Zero(3 * n, 3 * n), Eigen::MatrixXd::Zero(3 * n, 3 * n),
          Eigen::VectorXd(n)};
  const double beta = model.rayleigh_stiffness;
  for (size_t k = 0; k < s.springs.size(); ++k) {
    const Spring& sp = s.springs[k];
    Eigen::Vector3d dir = s.rest[size_t(sp.j)] - s.rest[size_t(sp.i)];
    dir.normalize();
    const Eigen::Matrix3d P = dir * dir.transpose();
    const double kappa = model.spring_kappa[k], kd = model.spring_kd[k];
    const int ends[2] = {block[size_t(sp.i)], block[size_t(sp.j)]};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        if (ends[a] < 0 || ends[b] < 0) continue;
        const double sign = a == b ? 1 : -1;
        d.K.block<3, 3>(3 * ends[a], 3 * ends[b]) += sign * kappa * P;
        d.C.block<3, 3>(3 * ends[a], 3 * ends[b]) += sign * (kd + beta * kappa) * P;
      }
  }
  for (size_t i = 0; i < s.rest.size(); ++i) {
    if (block[i] < 0) continue;
    const int b = block[i];
    const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
    d.K.block<3, 3>(3 * b, 3 * b) += model.anchor_kappa[i] * I;
    d.C.block<3, 3>(3 * b, 3 * b) +=
        (model.gamma[i] + model.anchor_kd[i] + beta * model.anchor_kappa[i]) * I;
    d.m(b) = model.mass[i];
  }
  return d;
}

/// lambda_max(h^2 A + 2 h C^) with masses m, C^ = M^-1/2 C' M^-1/2 + alpha I (dense).
double dense_index(const Dense& d, const Eigen::VectorXd& m, double alpha, double h) {
  Eigen::VectorXd w(3 * m.size());
  for (long r = 0; r < w.size(); ++r) w(r) = 1 / std::sqrt(m(r / 3));
  const Eigen::MatrixXd S = w.asDiagonal() * (h * h * d.K + 2 * h * d.C) * w.asDiagonal();
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S, Eigen::EigenvaluesOnly)
             .eigenvalues()
             .maxCoeff() +
         2 * h * alpha;
}

/// The spectral radius of the paper's step v' = v + h M^-1 (-K x - C v), x' = x + h v'.
double dense_radius(const Dense& d, const Eigen::VectorXd& m, double alpha, double h) {
  const long n = d.K.rows();
  Eigen::VectorXd minv(n);
  for (long r = 0; r < n; ++r) minv(r) = 1 / m(r / 3);
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd MK = minv.asDiagonal() * d.K;
  const Eigen::MatrixXd MC = minv.asDiagonal() * d.C + alpha * I;
  Eigen::MatrixXd T(2 * n, 2 * n);
  T.topLeftCorner(n, n) = I - h * h * MK;
  T.topRightCorner(n, n) = h * (I - h * MC);
  T.bottomLeftCorner(n, n) = -h * MK;
  T.bottomRightCorner(n, n) = I - h * MC;
  return T.eigenvalues().cwiseAbs().maxCoeff();
}

Eigen::VectorXd vec(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), long(v.size()));
}

struct ScalingCase {
  const char* name;
  ModelSpec spec;
  Params params;
  double dt;
};

std::vector<ScalingCase> cases() {
  std::vector<ScalingCase> out;
  out.push_back({"SPEC 11's plane", spec_plane(), spec_params(), 0.3});
  Params p = spec_params(0.0004);
  p.rayleigh_mass = 0.5;
  p.rayleigh_stiffness = 0.05;
  out.push_back({"mixed plane, dashpots and Rayleigh", mixed_plane(6, 7), p, 0.3});
  Params q = spec_params(0.0002);
  q.kappa = 0.004;
  ModelSpec cube = test::cube_lattice(4, 0.5, [](ModelSpec& s, int i, int a, int, int c) {
    s.fixed[size_t(i)] = a == 0;
    s.mass_scale[size_t(i)] = c == 3 ? 0.2 : 1.0;
  });
  out.push_back({"cube lattice, light top layer", cube, q, 0.08});
  return out;
}

TEST(MassScaling, LocalRuleMatchesTheDenseRowSumsAndMakesEveryRowDominant) {
  for (const ScalingCase& c : cases()) {
    SCOPED_TRACE(c.name);
    const Model model = compile_model(c.spec, c.params);
    const Dense d = dense(model);
    const MassScalingProblem p = mass_scaling_problem(model);
    const double h = c.dt / 0.9, alpha = model.rayleigh_mass;
    const Eigen::MatrixXd N = 2 * h * d.C + h * h * d.K;
    const std::vector<double> req = required_masses(p, h);
    ASSERT_EQ(req.size(), size_t(d.m.size()));
    const MassScalingResult r = mass_scaling(p, c.dt);
    ASSERT_EQ(r.kind, MassScalingCase::scaled);
    Eigen::VectorXd m1 = d.m;
    int scaled = 0;
    for (long i = 0; i < d.m.size(); ++i) {
      const double want = N.middleRows(3 * i, 3).cwiseAbs().rowwise().sum().maxCoeff() /
                          (4 - 2 * h * alpha);
      EXPECT_NEAR(req[size_t(i)], want, 1e-12 * want) << "node " << i;
      if (d.m(i) <= want) m1(i) = want * (1 + 1e-6), ++scaled;
      EXPECT_NEAR(r.mass_local[size_t(i)], m1(i), 1e-12 * m1(i)) << "node " << i;
    }
    EXPECT_EQ(r.scaled_count, scaled);
    EXPECT_GT(scaled, 0);
    // Every row of (4 - 2 h alpha) M' - N is diagonally dominant: Gershgorin's guarantee.
    Eigen::MatrixXd Q = -N;
    for (long k = 0; k < Q.rows(); ++k) Q(k, k) += (4 - 2 * h * alpha) * m1(k / 3);
    for (long k = 0; k < Q.rows(); ++k)
      EXPECT_GT(2 * Q(k, k) - Q.row(k).cwiseAbs().sum(), 0) << "row " << k;
    EXPECT_LT(dense_index(d, m1, alpha, h), 4);
    EXPECT_TRUE(r.local_certified);
  }
}

TEST(MassScaling, TightenedPointIsTheDenseEigenvalueBisectionsAndStableAtTheTarget) {
  for (const ScalingCase& c : cases()) {
    SCOPED_TRACE(c.name);
    const Model model = compile_model(c.spec, c.params);
    const Dense d = dense(model);
    const double h = c.dt / 0.9, alpha = model.rayleigh_mass;
    const MassScalingResult r = mass_scaling(mass_scaling_problem(model), c.dt);
    const Eigen::VectorXd m0 = d.m, m1 = vec(r.mass_local);
    ASSERT_GE(dense_index(d, m0, alpha, h), 4);
    double lo = 0, hi = 1;
    while (hi - lo > 1e-3) {
      const double mid = 0.5 * (lo + hi);
      (dense_index(d, m0 + mid * (m1 - m0), alpha, h) < 4 ? hi : lo) = mid;
    }
    EXPECT_EQ(r.s_star, hi);
    const Eigen::VectorXd ms = vec(r.mass);
    EXPECT_NEAR((ms - (m0 + hi * (m1 - m0))).cwiseAbs().maxCoeff(), 0, 1e-15 * ms.maxCoeff());
    EXPECT_NEAR(r.added, (ms - m0).sum(), 1e-12 * r.added);
    EXPECT_LT(r.added, r.added_local);
    // Stable at dt* and at dt_g by the amplification matrix; not at dt_g one step of the
    // bisection below s*.
    EXPECT_LE(dense_radius(d, ms, alpha, c.dt), 1 + 1e-12);
    EXPECT_LE(dense_radius(d, ms, alpha, h), 1 + 1e-12);
    EXPECT_GT(dense_radius(d, m0 + lo * (m1 - m0), alpha, h), 1);
    // The scaled model's exact dt limit, bracketed by the dense radius and matching the
    // exact analysis of SPEC 10 (general_limits on the same matrices).
    EXPECT_GE(r.dt_limit, h);
    EXPECT_LE(dense_radius(d, ms, alpha, r.dt_limit), 1 + 1e-12);
    EXPECT_GT(dense_radius(d, ms, alpha, r.dt_limit * (1 + 1e-4)), 1);
    EXPECT_GT(dense_radius(d, m0, alpha, r.dt_limit_before * (1 + 1e-4)), 1);
    EXPECT_LE(dense_radius(d, m0, alpha, r.dt_limit_before), 1 + 1e-12);
  }
}

TEST(MassScaling, SpecElevenPlaneGivesTheSpecsNumbers) {
  const Model model = compile_model(spec_plane(), spec_params());
  const MassScalingResult r = mass_scaling(mass_scaling_problem(model), 0.3);
  EXPECT_EQ(r.scaled_count, 4);
  EXPECT_NEAR(100 * r.added_local_fraction(), 3.25, 0.005);
  EXPECT_NEAR(100 * r.added_fraction(), 2.77, 0.005);
  EXPECT_NEAR(r.s_star, 0.851, 0.001);
  EXPECT_NEAR(r.dt_limit, 0.3334, 0.0003);  // SPEC 11 gives 0.3333; the bracket's width
  EXPECT_FALSE(r.over_cap);
  EXPECT_LT(r.dt_limit_before, 0.3 / 0.9);
  // The exact analysis of the model as given agrees with general_limits (SPEC 10).
  Params p = spec_params();
  p.dt = 0.3 / 0.9;
  EXPECT_NEAR(r.dt_limit_before, general_limits(model, model.spec().rest, p).dt_max,
              1e-5 * r.dt_limit_before);
}

TEST(MassScaling, DashpotsNeedMoreThanTheCapAndTheCapGivesTheLargestStepWithinIt) {
  const Model model = compile_model(spec_plane(), spec_params(0.001));
  const MassScalingProblem p = mass_scaling_problem(model);
  const MassScalingResult r = mass_scaling(p, 0.3);
  ASSERT_EQ(r.kind, MassScalingCase::scaled);
  EXPECT_TRUE(r.over_cap);
  EXPECT_GT(r.added_fraction(), 0.5);  // mass scaling is the wrong tool with these dashpots
  ASSERT_TRUE(r.dt_cap > r.safety * r.dt_limit_before && r.dt_cap < 0.3);
  EXPECT_LE(r.dt_cap_added, 0.05 * r.free_mass);
  // At the largest dt* within the cap the answer is within it; a little above, it is not.
  const MassScalingResult at = mass_scaling(p, r.dt_cap);
  EXPECT_FALSE(at.over_cap);
  EXPECT_LE(at.added, r.dt_cap_added * (1 + 1e-12));  // the least is within what was certified
  EXPECT_TRUE(mass_scaling(p, r.dt_cap * 1.01).over_cap);
  // A cap of 100% lets it through.
  MassScalingOptions wide;
  wide.max_added = 1.0;
  EXPECT_FALSE(mass_scaling(p, 0.3, wide).over_cap);
}

TEST(MassScaling, NothingToAddWhereTheStepIsAlreadyStable) {
  const Model model = compile_model(spec_plane(), spec_params());
  const MassScalingResult r = mass_scaling(mass_scaling_problem(model), 0.05);
  EXPECT_EQ(r.kind, MassScalingCase::nothing_to_add);
  EXPECT_TRUE(r.mass.empty());
  EXPECT_EQ(r.added, 0);
  const Dense d = dense(model);
  EXPECT_LE(dense_radius(d, d.m, 0, r.dt_limit_before), 1 + 1e-12);
  EXPECT_GT(dense_radius(d, d.m, 0, r.dt_limit_before * (1 + 1e-4)), 1);
  EXPECT_GE(r.dt_limit_before, 0.05 / 0.9);
}

TEST(MassScaling, NoMassHelpsWhereMassProportionalDampingAloneIsUnstable) {
  Params p = spec_params();
  p.rayleigh_mass = 10;  // 2 dt_g alpha = 2 (0.2 / 0.9) 10 = 4.4 >= 4
  const Model model = compile_model(spec_plane(), p);
  const MassScalingResult r = mass_scaling(mass_scaling_problem(model), 0.2);
  EXPECT_EQ(r.kind, MassScalingCase::no_mass_helps);
  EXPECT_DOUBLE_EQ(r.dt_no_mass, 2 * 0.9 / 10);
  // Below 2 f / alpha mass helps again.
  EXPECT_NE(mass_scaling(mass_scaling_problem(model), 0.17).kind, MassScalingCase::no_mass_helps);
}

TEST(MassScaling, RefusesATargetSafetyOrCapOutOfRange) {
  const Model model = compile_model(spec_plane(), spec_params());
  const MassScalingProblem p = mass_scaling_problem(model);
  MassScalingOptions o;
  o.safety = 0;
  EXPECT_NE(test::input_error([&] { mass_scaling(p, 0.3, o); }).find("safety"), std::string::npos);
  o.safety = 1.5;
  EXPECT_NE(test::input_error([&] { mass_scaling(p, 0.3, o); }).find("safety"), std::string::npos);
  o = {};
  o.max_added = -1;
  EXPECT_NE(test::input_error([&] { mass_scaling(p, 0.3, o); }).find("cap"), std::string::npos);
  EXPECT_NE(test::input_error([&] { mass_scaling(p, 0); }).find("target"), std::string::npos);
}

}  // namespace
}  // namespace dampbound
