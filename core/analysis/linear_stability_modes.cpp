#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
#include "core/analysis/linear_stability_modes.hpp"

#include <Eigen/Dense>
#include <Eigen/IterativeLinearSolvers>
#include <Spectra/GenEigsSolver.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <tuple>
#include <utility>
#include <vector>

#include "core/analysis/detail/rk4_proofs.hpp"
#include "core/physics/detail/numbers.hpp"
#include "core/physics/integrate.hpp"

namespace dampbound {
namespace {

/// "Bounded" (stable) means rho <= 1 + kMarginal: an undamped symplectic step (rho = 1
/// exactly) counts as stable, as in SPEC 7's dt < 2/sqrt(lambda_max) at gamma = 0.
constexpr double kMarginal = 1e-12;
using detail::kRoundUp;

/// One step of an integrator on y'' = -A y - C y', written once for a scalar mode and for a
/// whole mesh. `ops` gives A y, C w, (1 + h C/2)^-1 r and (I + h C + h^2 A)^-1 r.
template <class V, class Ops>
void linear_step(Integrator integrator, const Ops& ops, double h, V& y, V& w) {
  auto accel = [&](const V& yy, const V& ww) -> V { return -(ops.A(yy) + ops.C(ww)); };
  switch (integrator) {
    case Integrator::semi_implicit_euler: {  // paper eqs. 3-4: v += a h; x += v_new h
      w = w + h * accel(y, w);
      y = y + h * w;
      return;
    }
    case Integrator::forward_euler: {  // x += v_old h; v += a h
      const V a = accel(y, w);
      y = y + h * w;
      w = w + h * a;
      return;
    }
    case Integrator::verlet: {  // integrate.cpp: kick h/2, drift h, kick h/2 (damping implicit)
      const V wh = w + (h / 2) * accel(y, w);
      y = y + h * wh;
      V r = wh - (h / 2) * ops.A(y);
      ops.explicit_damping(r, wh, h / 2);  // SPEC 10's C' at (x', v_h), as integrate.cpp
      w = ops.half_damp_solve(r, h);
      return;
    }
    case Integrator::rk4: {
      const V k1y = w, k1w = accel(y, w);
      const V k2y = w + (h / 2) * k1w, k2w = accel(V(y + (h / 2) * k1y), k2y);
      const V k3y = w + (h / 2) * k2w, k3w = accel(V(y + (h / 2) * k2y), k3y);
      const V k4y = w + h * k3w, k4w = accel(V(y + h * k3y), k4y);
      y = y + (h / 6) * (k1y + 2 * k2y + 2 * k3y + k4y);
      w = w + (h / 6) * (k1w + 2 * k2w + 2 * k3w + k4w);
      return;
    }
    case Integrator::implicit_euler: {  // (I + h C + h^2 A) w' = w - h A y; y' = y + h w'
      w = ops.implicit_solve(V(w - h * ops.A(y)), h);
      y = y + h * w;
      return;
    }
  }
}

struct ScalarOps {
  double lambda, c;
  double A(double y) const { return lambda * y; }
  double C(double w) const { return c * w; }
  void explicit_damping(double&, double, double) const {}  // c is nodal: no C' part
  double half_damp_solve(double r, double h) const { return r / (1 + c * h / 2); }
  double implicit_solve(double r, double h) const { return r / (1 + h * c + h * h * lambda); }
};

struct VectorOps {
  const SparseMatrix* K;
  const Eigen::VectorXd* rate;
  const SparseMatrix* Cp;  ///< SPEC 10's damping besides the nodal one, mass-weighted; or null
  SparseMatrix S;  ///< I + h C + h^2 A; the solver keeps a reference to it, so it lives here
  std::unique_ptr<Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper>> cg;
  VectorOps(Integrator integrator, const SparseMatrix& Kw, const Eigen::VectorXd& c, double h,
            const SparseMatrix* damping = nullptr)
      : K(&Kw), rate(&c), Cp(damping) {
    if (!integrator_traits(integrator).implicit) return;
    S = (h * h) * Kw;
    if (Cp) S += h * *Cp;  // integrate.cpp: implicit Euler takes C' into its matrix
    for (Eigen::Index i = 0; i < S.rows(); ++i) S.coeffRef(i, i) += 1 + h * c(i);
    cg = std::make_unique<Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper>>();
    cg->setTolerance(1e-13);
    cg->compute(S);
  }
  VectorOps(const VectorOps&) = delete;
  VectorOps& operator=(const VectorOps&) = delete;
  Eigen::VectorXd A(const Eigen::VectorXd& y) const { return *K * y; }
  Eigen::VectorXd C(const Eigen::VectorXd& w) const {
    if (!Cp) return rate->cwiseProduct(w);
    return rate->cwiseProduct(w) + *Cp * w;
  }
  /// Verlet's second half kick: r -= scale C' w (C' explicit there; the nodal part implicit).
  void explicit_damping(Eigen::VectorXd& r, const Eigen::VectorXd& w, double scale) const {
    if (Cp) r -= scale * (*Cp * w);
  }
  Eigen::VectorXd half_damp_solve(const Eigen::VectorXd& r, double h) const {
    return r.cwiseQuotient((1 + (h / 2) * rate->array()).matrix());
  }
  Eigen::VectorXd implicit_solve(const Eigen::VectorXd& r, double) const { return cg->solve(r); }
};

/// The amplification operator for Spectra: (y, w) stacked in one vector of 2n.
struct AmplificationOp {
  using Scalar = double;
  Integrator integrator;
  const VectorOps* ops;
  double h;
  Eigen::Index n;
  int power = 1;  ///< steps per product: G^power spreads clustered magnitudes apart
  Eigen::Index rows() const { return 2 * n; }
  Eigen::Index cols() const { return 2 * n; }
  /// Acts on (y, h w): the step's matrix in those coordinates is similar to the one on (y, w)
  /// (diag(I, h I)), so it has the same eigenvalues, and its blocks are all of the order of
  /// h^2 A and h C rather than spread over h^-1 .. h (badly scaled at extreme magnitudes, a
  /// dense eigensolver or Arnoldi loses the digits that decide |z| <= 1).
  void apply(const double* in, double* out) const {
    Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(in, n);
    Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(in + n, n) / h;
    for (int k = 0; k < power; ++k) linear_step(integrator, *ops, h, y, w);
    Eigen::Map<Eigen::VectorXd>(out, n) = y;
    Eigen::Map<Eigen::VectorXd>(out + n, n) = h * w;
  }
  void perform_op(const double* in, double* out) const { apply(in, out); }
};

/// rho estimated by the growth of ||G^k u|| over many steps: the fallback when Arnoldi does
/// not converge (clustered magnitudes). Averages over the last half of the steps.
double power_growth(const AmplificationOp& op, int steps) {
  Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(op.rows(), 0.3, 1.7).array().sin();
  Eigen::VectorXd next(op.rows());
  double log_growth = 0;
  for (int k = 0; k < steps; ++k) {
    u /= u.norm();
    op.apply(u.data(), next.data());
    if (k >= steps / 2) log_growth += std::log(next.norm());
    u.swap(next);
  }
  return std::exp(log_growth / (steps - steps / 2));
}

/// Arnoldi's largest |eigenvalue| of `op`, and whether Spectra converged and every Ritz pair
/// it returned has a residual ||op x - theta x|| within 1e-6 |theta| ||x|| (one product
/// each): Spectra's own test reads the residual from its factorisation, which can be wrong.
struct ArnoldiTop {
  double magnitude = 0;
  bool converged = false;
  bool checked = false;
};

ArnoldiTop arnoldi_largest_magnitude(AmplificationOp& op) {
  const Eigen::Index n2 = op.rows();
  Spectra::GenEigsSolver<AmplificationOp> eigs(op, 4, std::min<Eigen::Index>(n2, 40));
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestMagn, 200, 1e-8);
  ArnoldiTop top;
  top.converged = eigs.info() == Spectra::CompInfo::Successful;
  if (!top.converged) return top;
  const Eigen::VectorXcd theta = eigs.eigenvalues();
  const Eigen::MatrixXcd X = eigs.eigenvectors();
  top.magnitude = theta.cwiseAbs().maxCoeff();
  top.checked = true;
  Eigen::VectorXd re(n2), im(n2), op_re(n2), op_im(n2);
  for (Eigen::Index k = 0; k < theta.size(); ++k) {
    re = X.col(k).real();
    im = X.col(k).imag();
    op.apply(re.data(), op_re.data());
    op.apply(im.data(), op_im.data());
    const Eigen::VectorXcd r = op_re.cast<std::complex<double>>() +
                               std::complex<double>(0, 1) * op_im.cast<std::complex<double>>() -
                               theta(k) * X.col(k);
    if (!(r.norm() <= 1e-6 * std::abs(theta(k)) * X.col(k).norm())) top.checked = false;
  }
  return top;
}

}  // namespace

Eigen::Matrix2d mode_amplification(Integrator integrator, double lambda, double c, double h) {
  const ScalarOps ops{lambda, c};
  Eigen::Matrix2d G;
  for (int col = 0; col < 2; ++col) {
    double y = col == 0 ? 1 : 0, w = col == 1 ? 1 : 0;
    linear_step(integrator, ops, h, y, w);
    G(0, col) = y;
    G(1, col) = w;
  }
  return G;
}

double mode_spectral_radius(Integrator integrator, double lambda, double c, double h) {
  const Eigen::Matrix2d G = mode_amplification(integrator, lambda, c, h);
  const double tr = G.trace(), det = G.determinant();
  // tr^2 - 4 det, written without its cancellation: a mode near lambda = 0 has the real pair
  // 1 and about 1 - c h, and at small h tr^2 and 4 det agree to 1e-14 and more, so the
  // rounding of their difference (1e-16 of tr^2) would put the radius above 1 + 1e-12 and
  // make uniform_dt_max absurdly small (7.7e-7 s on two-node, stable up to 2 s).
  const double gap = G(0, 0) - G(1, 1);
  const double disc = gap * gap + 4 * G(0, 1) * G(1, 0);
  if (disc >= 0) return (std::abs(tr) + std::sqrt(disc)) / 2;  // real pair: max |z|
  return std::sqrt(det);                                        // complex pair: |z|^2 = det
}

namespace {

// (1 + eps)^2 - 1 and (2 + eps)^2, rounded up (e1 - 1 is exact).
constexpr double kE1 = 1 + kMarginal;
constexpr double kGrow = (kE1 - 1) * (kE1 + 1) * kRoundUp;
constexpr double kTwoPlus = (kE1 + 1) * (kE1 + 1) * kRoundUp;

ModeInstability forward_euler_instability(double lambda_0, double c, double h) {
  ModeInstability m;
  // d > (1 + eps)^2  <=>  h^2 lambda - c h - grow > 0.
  m.lambda_from = (c * h + kGrow) / (h * h) * kRoundUp;
  m.dt_from = lambda_0 > 0 ? (c + std::sqrt(c * c + 4 * lambda_0 * kGrow)) / (2 * lambda_0) * kRoundUp
                           : kInf;
  const double r = (h * h * lambda_0 - kGrow) / h;
  m.rate_below = r > 0 ? r / kRoundUp : -kInf;
  return m;
}

ModeInstability verlet_instability(double lambda_0, double c, double h) {
  // With q = 1 - h^2 lambda/2 < -1: (1 + c h/2)(z^2 - |t| z + d) at z = 1 + eps is
  // (1 + eps)^2 (1 + c h/2) + (1 - c h/2) - 2 (1 + eps)(h^2 lambda/2 - 1) < 0, that is
  // A h^2 - B h - C > 0 with A = (1 + eps) lambda, B = c grow/2, C = (2 + eps)^2; from
  // lambda_from on, q <= 1 - C/(2 (1 + eps)) < -1.
  ModeInstability m;
  const double C = kTwoPlus;
  m.lambda_from = (C + c * kGrow / 2 * h) / (kE1 * h * h) * kRoundUp;
  const double A = kE1 * lambda_0, B = c * kGrow / 2;
  m.dt_from = A > 0 ? (B + std::sqrt(B * B + 4 * A * C)) / (2 * A) * kRoundUp : kInf;
  const double r = (A * h * h - C) / (h * kGrow / 2);
  m.rate_below = r > 0 ? r / kRoundUp : -kInf;
  return m;
}

}  // namespace

ModeInstability mode_instability(Integrator integrator, double lambda_0, double c, double h) {
  switch (integrator) {
    case Integrator::rk4: {
      ModeInstability m;
      m.lambda_from = detail::rk4_lambda_from(c, h, 1 + kMarginal);
      return m;
    }
    case Integrator::forward_euler: return forward_euler_instability(lambda_0, c, h);
    case Integrator::verlet: return verlet_instability(lambda_0, c, h);
    case Integrator::semi_implicit_euler:  // the symmetric index and SPEC 7 decide
    case Integrator::implicit_euler:       // unconditional where K is positive semi-definite
      return {};
  }
  return {};
}

ModeStability mode_stability(Integrator integrator, double lambda_hi, double c, double h) {
  ModeStability m;
  switch (integrator) {
    case Integrator::rk4:
      m.proved = true;
      std::tie(m.rate_lo, m.rate_hi) = detail::rk4_rate_range(lambda_hi, c, h, 1 + kMarginal);
      m.stable = m.rate_lo <= c && c <= m.rate_hi;  // a range from another rate leaves c out
      m.dt_up_to = detail::rk4_dt_up_to(lambda_hi, c, 1 + kMarginal);
      return m;
    case Integrator::forward_euler:
      m.proved = true;
      m.stable = c * h * kRoundUp <= 2 && lambda_hi * h * kRoundUp <= c;
      m.dt_up_to = c > 0 ? std::min(c / lambda_hi, 2 / c) / kRoundUp : 0;
      m.rate_lo = h * lambda_hi * kRoundUp;
      m.rate_hi = 2 / h / kRoundUp;
      return m;
    case Integrator::verlet:
      m.proved = true;
      m.stable = lambda_hi * h * h * kRoundUp <= 4;
      m.dt_up_to = 2 / std::sqrt(lambda_hi) / kRoundUp;
      m.rate_lo = 0;
      m.rate_hi = m.stable ? kInf : -kInf;
      return m;
    case Integrator::semi_implicit_euler:  // the symmetric index and SPEC 7 decide
    case Integrator::implicit_euler:
      return m;
  }
  return m;
}

double spectrum_spectral_radius(Integrator integrator, const StiffnessSpectrum& s, double c,
                                double h) {
  double rho = 0;
  const int samples = s.lambda_max > s.lambda_min ? 64 : 1;
  for (int k = 0; k <= samples; ++k) {
    const double lambda = s.lambda_min + (s.lambda_max - s.lambda_min) * k / samples;
    rho = std::max(rho, mode_spectral_radius(integrator, lambda, c, h));
  }
  return rho;
}

double uniform_dt_max(Integrator integrator, const StiffnessSpectrum& s, double c) {
  switch (integrator) {
    case Integrator::implicit_euler: return kInf;
    case Integrator::semi_implicit_euler: return semi_implicit_dt_max(s.lambda_max, c);
    case Integrator::forward_euler:
      // Undamped: |z|^2 = 1 + lambda h^2 > 1 for every h > 0 and lambda > 0.
      if (c <= 0 && s.lambda_max > 0) return 0;
      break;
    case Integrator::verlet:
    case Integrator::rk4:
      break;  // searched on the spectrum's radius below
  }
  auto stable = [&](double h) { return spectrum_spectral_radius(integrator, s, c, h) <= 1 + kMarginal; };
  const double scale = 1.0 / std::sqrt(std::max({s.lambda_max, c * c, 1e-300}));
  double lo = 1e-6 * scale;
  if (!stable(lo)) return 0;
  double hi = lo;
  while (stable(hi)) {
    lo = hi;
    hi *= 1.25;
    if (hi > 1e6 * scale) return kInf;
  }
  for (int k = 0; k < 200 && hi - lo > 1e-13 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (stable(mid) ? lo : hi) = mid;
  }
  return lo;
}

RateInterval uniform_rate_interval(Integrator integrator, const StiffnessSpectrum& s, double h) {
  switch (integrator) {
    case Integrator::implicit_euler: return {0, kInf};
    case Integrator::semi_implicit_euler:  // SPEC 7; empty when lambda h^2 >= 4
      return {0, std::max(0.0, (4 - s.lambda_max * h * h) / (2 * h))};
    case Integrator::forward_euler:
    case Integrator::verlet:
    case Integrator::rk4:
      break;  // sampled and refined on the spectrum's radius below
  }
  auto stable = [&](double c) { return spectrum_spectral_radius(integrator, s, c, h) <= 1 + kMarginal; };
  // No explicit step damps a mode with c h > 8; sample [0, 8/h] and refine the first run.
  const int samples = 2000;
  const double cap = 8 / h;
  int first = -1, last = -1;
  for (int k = 0; k <= samples; ++k) {
    const bool ok = stable(cap * k / samples);
    if (ok && first < 0) first = k;
    if (ok) last = k;
    if (!ok && first >= 0) break;
  }
  if (first < 0) return {0, 0};
  auto refine = [&](double good, double bad) {
    for (int k = 0; k < 200 && std::abs(bad - good) > 1e-13 * std::abs(bad); ++k) {
      const double mid = 0.5 * (good + bad);
      (stable(mid) ? good : bad) = mid;
    }
    return good;
  };
  RateInterval r;
  r.lo = first == 0 ? 0 : refine(cap * first / samples, cap * (first - 1) / samples);
  r.hi = last == samples ? kInf : refine(cap * last / samples, cap * (last + 1) / samples);
  return r;
}

Eigen::VectorXd damping_rates(const Model& model, const std::vector<double>& gamma) {
  std::vector<double> rates;
  for (size_t i = 0; i < model.spec().rest.size(); ++i)
    if (!model.spec().fixed[i])
      for (int r = 0; r < 3; ++r) rates.push_back(gamma[i] / model.mass[i]);
  return Eigen::Map<Eigen::VectorXd>(rates.data(), static_cast<Eigen::Index>(rates.size()));
}

SpectralRadius amplification_spectral_radius(Integrator integrator,
                                             const SparseMatrix& K_weighted,
                                             const Eigen::VectorXd& rate, double h,
                                             const SparseMatrix* damping) {
  const Eigen::Index n = K_weighted.rows();
  if (n == 0) return {0, true};
  if (2 * n <= 24) {  // tiny: the dense matrix is exact and cheap
    const Eigen::MatrixXd G = amplification_matrix_dense(integrator, K_weighted, rate, h, damping);
    return {G.eigenvalues().cwiseAbs().maxCoeff(), true};
  }
  const VectorOps ops(integrator, K_weighted, rate, h, damping);
  // Arnoldi on G^4: |z|^4 spreads the magnitudes of lightly damped modes, which all sit near
  // the circle |z| = sqrt(1 - c h), four times further apart, for the price of cheap products.
  // Spectra 1.0.1 can report success with Ritz pairs that are no eigenpairs at all (residual
  // as large as theta), as on random meshes under Verlet and RK4 where G^4 squeezes the
  // overdamped modes towards 0: each pair is checked, and G^2, then G, tried when one fails.
  AmplificationOp op{integrator, &ops, h, n, 4};
  for (int power : {4, 2, 1}) {
    op.power = power;
    const ArnoldiTop top = arnoldi_largest_magnitude(op);
    if (top.checked) return {std::pow(top.magnitude, 1.0 / power), true};
    if (!top.converged) break;  // the clustered case: more restarts would not help
  }
  op.power = 4;
  return {std::pow(power_growth(op, 200), 1.0 / op.power), false};
}

Eigen::MatrixXd amplification_matrix_dense(Integrator integrator, const SparseMatrix& K_weighted,
                                           const Eigen::VectorXd& rate, double h,
                                           const SparseMatrix* damping) {
  const Eigen::Index n = K_weighted.rows();
  const VectorOps ops(integrator, K_weighted, rate, h, damping);
  const AmplificationOp op{integrator, &ops, h, n};
  Eigen::MatrixXd G(2 * n, 2 * n);
  Eigen::VectorXd e = Eigen::VectorXd::Zero(2 * n), col(2 * n);
  for (Eigen::Index k = 0; k < 2 * n; ++k) {
    e(k) = 1;
    op.apply(e.data(), col.data());
    G.col(k) = col;
    e(k) = 0;
  }
  return G;
}

}  // namespace dampbound
