#include "core/analysis/linear_limits.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>

#include "core/physics/safe_bound.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound {
namespace {

std::string shown(double v) {
  std::ostringstream o;
  o << std::setprecision(6) << v;
  return o.str();
}

/// A matrix of the model (K or C): 3N x 3N, finite, symmetric to 1e-12 of its largest entry.
void check_matrix(const SparseMatrix& K, const std::string& name, size_t n) {
  if (K.rows() != K.cols())
    throw InputError(name + ": must be square, not " + std::to_string(K.rows()) + " x " +
                     std::to_string(K.cols()));
  if (size_t(K.rows()) != 3 * n)
    throw InputError(name + ": must be 3N x 3N for the N = " + std::to_string(n) +
                     " masses given, not " + std::to_string(K.rows()) + " x " +
                     std::to_string(K.cols()));
  double largest = 0;
  for (int k = 0; k < K.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(K, k); it; ++it) {
      if (!std::isfinite(it.value()))
        throw InputError(name + ": entry (" + std::to_string(it.row()) + ", " +
                         std::to_string(it.col()) + ") is not finite");
      largest = std::max(largest, std::abs(it.value()));
    }
  const SparseMatrix asym = K - SparseMatrix(K.transpose());
  for (int k = 0; k < asym.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(asym, k); it; ++it)
      if (std::abs(it.value()) > 1e-12 * largest)
        throw InputError(name + ": not symmetric: entries (" + std::to_string(it.row()) + ", " +
                         std::to_string(it.col()) + ") and (" + std::to_string(it.col()) + ", " +
                         std::to_string(it.row()) + ") differ by " + shown(std::abs(it.value())));
}

void check(const MatrixModel& m) {
  if (!m.K) throw InputError("K: no stiffness matrix given");
  const size_t n = m.mass.size();
  if (n == 0) throw InputError("mass: no node (give one mass per node)");
  check_matrix(*m.K, "K", n);
  if (m.C) check_matrix(*m.C, "C", n);
  for (size_t i = 0; i < n; ++i)
    if (!(std::isfinite(m.mass[i]) && m.mass[i] > 0))
      throw InputError("mass: node " + std::to_string(i) + " has mass " + shown(m.mass[i]) +
                       "; every mass must be finite and > 0");
  if (m.gamma.size() != 1 && m.gamma.size() != n)
    throw InputError("gamma: give one value or one per node (" + std::to_string(n) + "), not " +
                     std::to_string(m.gamma.size()));
  for (size_t i = 0; i < m.gamma.size(); ++i)
    if (!(std::isfinite(m.gamma[i]) && m.gamma[i] >= 0))
      throw InputError("gamma: entry " + std::to_string(i) + " must be finite and >= 0");
  if (!(std::isfinite(m.dt) && m.dt > 0)) throw InputError("dt: must be finite and > 0");
}

/// M^-1/2 X M^-1/2 for a 3N x 3N X.
SparseMatrix weighted(SparseMatrix X, const std::vector<double>& inv_sqrt_m) {
  X.makeCompressed();
  for (int k = 0; k < X.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(X, k); it; ++it)
      it.valueRef() *= inv_sqrt_m[size_t(it.row())] * inv_sqrt_m[size_t(it.col())];
  return X;
}

/// The largest absolute row sum of X: a bound on its eigenvalues' magnitude.
double gershgorin_bound(const SparseMatrix& X) {
  Eigen::VectorXd rows = Eigen::VectorXd::Zero(X.rows());
  for (int k = 0; k < X.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(X, k); it; ++it) rows(it.row()) += std::abs(it.value());
  return rows.size() ? rows.maxCoeff() : 0.0;
}

/// Where the safe bound guarantees nothing: no gamma is safe, and no dt (`dt` = 0) or none
/// computed (NaN).
void no_safe_bound(MatrixLimits& out, double dt) {
  const double none = std::isnan(dt) ? dt : -std::numeric_limits<double>::infinity();
  std::fill(out.gamma_safe.begin(), out.gamma_safe.end(), none);
  std::fill(out.dt_safe.begin(), out.dt_safe.end(), dt);
}

}  // namespace

MatrixLimits linear_limits(const MatrixModel& model, const ExactOptions& options) {
  check(model);
  const size_t n = model.mass.size();
  const auto gamma_of = [&](size_t i) {
    return model.gamma.size() == 1 ? model.gamma[0] : model.gamma[i];
  };
  MatrixLimits out;
  out.gamma_ref = *std::max_element(model.gamma.begin(), model.gamma.end());
  // A = M^-1/2 K M^-1/2 and the rate per dof per unit of gamma_ref, as for a model whose
  // gamma_i = gamma * gamma_scale_i (mass_weighted, damping_rates).
  std::vector<double> inv_sqrt_m(3 * n);
  Eigen::VectorXd R(Eigen::Index(3 * n));
  for (size_t i = 0; i < n; ++i)
    for (size_t r = 0; r < 3; ++r) {
      inv_sqrt_m[3 * i + r] = 1.0 / std::sqrt(model.mass[i]);
      const double scale = out.gamma_ref > 0 ? gamma_of(i) / out.gamma_ref : 1.0;
      R(Eigen::Index(3 * i + r)) = scale / model.mass[i];
    }
  const SparseMatrix A = weighted(*model.K, inv_sqrt_m);
  Params p;
  p.dt = model.dt;
  p.gamma = out.gamma_ref;
  p.integrator = Integrator::semi_implicit_euler;
  // No floor: nothing about K is known beyond the matrix, so lambda_min is certified by a
  // factorisation as for any model with a compressed spring.
  out.exact = exact_stability(A, R, std::nullopt, p, options);
  out.lambda_max_lo = out.exact.lambda_max_lo;
  out.lambda_max_hi = out.exact.spectrum.lambda_max;
  out.dt_max = out.exact.dt_max;
  out.gamma_min = out.exact.gamma_lo;
  out.gamma_max = out.exact.gamma_hi;
  out.stable = out.exact.stable;
  // SPEC 9 on the same A: the Gershgorin row sums of each node's three rows.
  std::vector<double> rows(3 * n, 0.0);
  for (int k = 0; k < A.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(A, k); it; ++it)
      rows[size_t(it.row())] += std::abs(it.value());
  out.row_sum.resize(n);
  out.gamma_safe.resize(n);
  out.dt_safe.resize(n);
  for (size_t i = 0; i < n; ++i) {
    out.row_sum[i] = std::max({rows[3 * i], rows[3 * i + 1], rows[3 * i + 2]});
    out.gamma_safe[i] = safe_gamma(model.mass[i], model.dt, out.row_sum[i]);
    out.dt_safe[i] = safe_dt(model.mass[i], gamma_of(i), out.row_sum[i]);
  }
  if (out.exact.indefinite) {  // SPEC 9: no damping bound helps a growing mode
    out.reason = "K is not positive semi-definite (lambda_min = " + shown(out.exact.spectrum.lambda_min) +
                 " < 0): a mode grows whatever gamma and dt";
    no_safe_bound(out, 0.0);
  }
  if (!model.C) return out;
  // SPEC 10: the index with C^ = M^-1/2 (Gamma + C) M^-1/2 (general_limits on matrices), the
  // nodal part per unit of gamma_ref as R above, and the generalised safe bound.
  out.damping_matrix = true;
  const SparseMatrix Cp = weighted(*model.C, inv_sqrt_m);
  SparseMatrix G(A.rows(), A.cols());
  G.reserve(Eigen::VectorXi::Constant(A.cols(), 1));
  for (Eigen::Index r = 0; r < A.rows(); ++r) G.insert(r, r) = R(r);
  G.makeCompressed();
  const GeneralLimits g = general_limits(A, Cp, G, out.gamma_ref, model.dt);
  out.index = g.index;
  out.damping_min = g.damping_min;
  out.dt_max = g.dt_max;
  out.gamma_min = 0;
  out.gamma_max = g.gamma_max;
  out.stable = g.index < 4 && g.damping_min > 0;
  if (out.exact.indefinite) {  // the index criterion needs K >= 0: the nodal verdict stands
    out.dt_max = out.gamma_max = 0;
    out.stable = false;
    return out;
  }
  if (g.damping_min < -1e-12 * gershgorin_bound(Cp + out.gamma_ref * G)) {
    // SPEC 10's index decides stability only with C^ >= 0; a negative rate can make a mode
    // grow or not, and nothing here decides which.
    out.reason = "C is not positive semi-definite (lambda_min(C^) = " + shown(g.damping_min) +
                 " < 0): the limits and the safe bound are not computed for this damping";
    out.dt_max = out.gamma_min = out.gamma_max = std::numeric_limits<double>::quiet_NaN();
    out.stable = false;
    no_safe_bound(out, std::numeric_limits<double>::quiet_NaN());
    return out;
  }
  const DampedSafeRows damped(A, Cp, model.mass);
  for (size_t i = 0; i < n; ++i) {
    out.gamma_safe[i] = damped.gamma_safe(int(i), model.dt);
    out.dt_safe[i] = damped.dt_safe(int(i), gamma_of(i));
  }
  return out;
}

MassScalingProblem mass_scaling_problem(const MatrixModel& model, double alpha) {
  check(model);
  if (!(std::isfinite(alpha) && alpha >= 0))
    throw InputError("rayleigh_mass: must be finite and >= 0");
  const size_t n = model.mass.size();
  MassScalingProblem p;
  p.K = *model.K;
  p.mass = model.mass;
  p.alpha = alpha;
  SparseMatrix G(Eigen::Index(3 * n), Eigen::Index(3 * n));
  std::vector<Eigen::Triplet<double>> t;
  for (size_t i = 0; i < n; ++i) {
    const double g = model.gamma.size() == 1 ? model.gamma[0] : model.gamma[i];
    for (size_t r = 0; r < 3; ++r)
      if (g != 0) t.emplace_back(Eigen::Index(3 * i + r), Eigen::Index(3 * i + r), g);
  }
  G.setFromTriplets(t.begin(), t.end());
  p.C = model.C ? SparseMatrix(*model.C + G) : G;
  p.K.makeCompressed();
  p.C.makeCompressed();
  return p;
}

}  // namespace dampbound
