#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
#include "core/analysis/equilibrium.hpp"
#include "core/physics/detail/spring_block.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/analysis/detail/shifted_cholesky.hpp"
#include "core/io/format.hpp"
#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/physics/forces.hpp"

namespace dampbound {
namespace {

/// F_i(x) + f_i over the free nodes (3 rows each, in free_blocks order) and its NetForce.
NetForce residual(const Model& model, const std::vector<Vec3>& x, const std::vector<int>& block,
                  Eigen::VectorXd& r) {
  std::vector<Vec3> F;
  internal_forces(model, x, F);
  NetForce n;
  for (size_t i = 0; i < x.size(); ++i) {
    if (block[i] < 0) continue;
    const Vec3 net = F[i] + model.spec().external_force[i];
    r.segment<3>(3 * block[i]) = net;
    if (net.norm() > n.largest || n.node < 0) n.largest = net.norm(), n.node = static_cast<int>(i);
    n.scale = std::max({n.scale, model.spec().external_force[i].norm(),
                        model.anchor_kappa[i] * (x[i] - model.spec().rest[i]).norm()});
  }
  for (size_t k = 0; k < model.spec().springs.size(); ++k) {
    const Spring& s = model.spec().springs[k];
    const auto i = static_cast<size_t>(s.i), j = static_cast<size_t>(s.j);
    if (block[i] < 0 && block[j] < 0) continue;
    n.scale = std::max(n.scale, model.spring_kappa[k] * std::abs((x[j] - x[i]).norm() - s.rest_length));
  }
  return n;
}

/// The potential energy whose gradient is -(F + f) (SPEC 1): each spring's
/// kappa (l - l0)^2 / 2, each anchor's kappa_a |x - X|^2 / 2, less f . (x - X), in long
/// double (its decrease is what a step is judged by, a difference of large sums).
long double energy(const Model& model, const std::vector<Vec3>& x) {
  long double e = 0;
  for (size_t k = 0; k < model.spec().springs.size(); ++k) {
    const Spring& s = model.spec().springs[k];
    const double stretch = spring_geometry(x[static_cast<size_t>(s.i)].data(),
                                           x[static_cast<size_t>(s.j)].data(), s.rest_length)
                               .length -
                           s.rest_length;
    e += 0.5L * model.spring_kappa[k] * stretch * stretch;
  }
  for (size_t i = 0; i < x.size(); ++i) {
    const Vec3 u = x[i] - model.spec().rest[i];
    e += 0.5L * model.anchor_kappa[i] * u.squaredNorm() - model.spec().external_force[i].dot(u);
  }
  return e;
}

/// Newton's step on the energy, d = (K + sigma I)^-1 r with r = F + f: sigma = 0 where K is
/// positive definite, else the first of 1e-6, 1e-5, ... of K's largest diagonal entry that
/// makes K + sigma I so (CHOLMOD's Cholesky, one pattern analysis), so that d always goes
/// downhill in energy.
/// `chol` keeps the pattern analysis from one step to the next (K's pattern is the mesh's).
Eigen::VectorXd newton_step(std::optional<detail::ShiftedCholesky>& chol, const SparseMatrix& K,
                            const Eigen::VectorXd& r, double budget) {
  Eigen::VectorXd d(r.size());
  if (chol)
    chol->assign(-K);
  else
    chol.emplace(-K);  // factors sigma I + K
  chol->analyse(budget);
  const double diagonal = K.diagonal().cwiseAbs().maxCoeff();
  double sigma = 0;
  for (int tries = 0; !chol->factor(sigma); ++tries) {
    if (tries == 30) throw std::runtime_error("static equilibrium: K + sigma I never factored");
    sigma = sigma == 0 ? 1e-6 * diagonal : 10 * sigma;
  }
  chol->solve(r.data(), d.data());
  return d;
}

/// Every 3 x 3 block K can hold at some state (a free node's own, and each spring's between
/// two free nodes), as explicit zeros: K + this has one pattern at every state, where K alone
/// drops the entries that are 0 at the state (a flat mesh at rest couples no out-of-plane
/// row), so that the Newton steps share one pattern analysis.
SparseMatrix block_pattern(const Model& model, const std::vector<int>& block, int free) {
  std::vector<Eigen::Triplet<double>> t;
  auto add = [&t](int a, int b) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) t.emplace_back(3 * a + r, 3 * b + c, 0.0);
  };
  for (size_t i = 0; i < block.size(); ++i)
    if (block[i] >= 0) add(block[i], block[i]);
  for (const Spring& s : model.spec().springs) {
    const int a = block[static_cast<size_t>(s.i)], b = block[static_cast<size_t>(s.j)];
    if (a >= 0 && b >= 0) add(a, b), add(b, a);
  }
  SparseMatrix Z(3 * free, 3 * free);
  Z.setFromTriplets(t.begin(), t.end());
  return Z;
}

}  // namespace

NetForce net_force(const Model& model, const std::vector<Vec3>& x) {
  int free = 0;
  const std::vector<int> block = free_blocks(model, &free);
  Eigen::VectorXd r(3 * free);
  return residual(model, x, block, r);
}

std::string rest_not_in_equilibrium(const NetForce& net) {
  return "the rest state is not an equilibrium: a net force of " + format_human(net.largest) +
         " at node " + std::to_string(net.node) + " (largest force term " +
         format_human(net.scale) + ")";
}

std::string no_equilibrium(const Equilibrium& e) {
  if (e.converged) return "";
  return "no static equilibrium found in " + std::to_string(e.iterations) +
         " Newton steps (net force " + format_human(e.net.largest) + " at node " +
         std::to_string(e.net.node) + ", largest force term " + format_human(e.net.scale) + ")";
}

std::string equilibrium_summary(const Equilibrium& e) {
  return std::to_string(e.iterations) + " Newton steps, net force " +
         format_digits(e.net.largest, 3) + " against a largest force term of " +
         format_human(e.net.scale);
}

std::string equilibrium_over_budget(const FactorisationOverBudget& over) {
  return std::string("Newton's method on the tangent stiffness needs factorisations, and ") +
         over.what();
}

Equilibrium static_equilibrium(const Model& model, const EquilibriumOptions& options) {
  int free = 0;
  const std::vector<int> block = free_blocks(model, &free);
  Equilibrium e;
  e.x = model.spec().rest;
  Eigen::VectorXd r(3 * free), trial_r(3 * free);
  std::optional<detail::ShiftedCholesky> chol;
  SparseMatrix pattern;  // built at the first step
  e.net = residual(model, e.x, block, r);
  while (!(e.converged = e.net.balanced(options.tolerance)) &&
         e.iterations < options.max_iterations) {
    if (e.iterations == 0) pattern = block_pattern(model, block, free);
    const SparseMatrix K = tangent_stiffness(model, e.x) + pattern;
    const Eigen::VectorXd d = newton_step(chol, K, r, options.max_factor_flops);
    ++e.iterations;
    // Halve the step until the energy falls enough (Armijo: its slope along d is -r . d),
    // or, once rounding hides the energy's change, until the net force falls.
    const long double e0 = energy(model, e.x);
    const double slope = -r.dot(d), before = r.norm();
    std::vector<Vec3> trial = e.x;
    double t = 1;
    NetForce n;
    for (int halvings = 0;; ++halvings, t /= 2) {
      for (size_t i = 0; i < trial.size(); ++i)
        if (block[i] >= 0) trial[i] = e.x[i] + t * d.segment<3>(3 * block[i]);
      n = residual(model, trial, block, trial_r);
      if (energy(model, trial) <= e0 + 1e-4L * t * slope || trial_r.norm() < 0.5 * before) break;
      if (halvings == 60) return e;  // no descent along Newton's step: not converged
    }
    e.x.swap(trial);
    r.swap(trial_r);
    e.net = n;
  }
  return e;
}

}  // namespace dampbound
