#include "core/analysis/detail/definite_root.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "core/analysis/detail/lanczos.hpp"
#include "core/analysis/detail/shifted_cholesky.hpp"
#include "core/physics/detail/numbers.hpp"

namespace dampbound::detail {
namespace {

/// The interval's relative width, as the bisection on certified eigenvalues had it.
constexpr double kWidth = 1e-10;
/// Lanczos steps per run (full reorthogonalisation), and its tolerance on the top Ritz value.
/// A run far from the root meets a clustered top and does not converge in 60 steps either
/// (the damped 40k plane: each of 60 steps cost 25 ms there, half of it reorthogonalisation);
/// close to the root the top stands apart and a run converges in 5 to 25.
constexpr int kLanczosSteps = 30;
constexpr double kRitzTolerance = 1e-12;
/// Or the top Ritz value has settled: it moved by at most this (relative) over the last two
/// steps. A run that starts from a vector already at the top (the index's own top vector,
/// IndexFamily::start) sits at the residual's rounding floor, 1e-12 to 1e-11, and would take
/// every step (the damped 40k plane: theta the same to 15 digits over 30 steps); the probe
/// below a converged estimate goes 0.4 of the width (4e-11) below it.
constexpr double kRitzSettled = 1e-13;
/// After an estimate whose Lanczos run did not converge, the first probe's step back from it,
/// as a fraction of the way back to the last stable point.
constexpr double kFirstStepBack = 1e-5;

class Search {
 public:
  Search(const IndexFamily& family, std::unique_ptr<ShiftedCholesky>* factors, double budget)
      : family_(family), f_(factors ? *factors : own_), budget_(budget) {}

  /// Whether lambda_max(S(x)) < 4 is proved: sigma I - S(x) factors and sigma plus the
  /// factorisation's rounding bound is below 4. sigma starts 4e-11 below 4 and is lowered to
  /// 4 - 2 delta where a bound delta is wider than that.
  bool stable(double x) {
    S_ = family_.S(x);
    if (!f_) {
      f_ = std::make_unique<ShiftedCholesky>(S_, true);
    } else {
      f_->assign(S_);
    }
    f_->analyse(budget_);  // once per pattern: the budget is checked before any factorisation
    factored_ = std::numeric_limits<double>::quiet_NaN();
    for (int k = 0; k < 4; ++k) {
      if (!f_->factor(sigma_)) return false;
      const double proved = f_->proved_above();
      if (proved < 4) {
        factored_ = x;
        return true;
      }
      sigma_ = 4 - 2 * (proved - sigma_);
    }
    return false;
  }

  /// After stable(a): a + t_u, the root from above (module comment). +inf when no direction
  /// of D + t Q grows.
  double estimate(double a) {
    converged_ = false;
    if (!(factored_ == a) && !stable(a)) return a;  // (not reached: a was proved stable)
    const SparseMatrix D = family_.D(a);
    const bool quadratic = family_.Q.rows() > 0;
    double t = 0;
    for (int round = 0; round < 12; ++round) {
      top_vector(D, quadratic ? t : 0.0);
      const Eigen::VectorXd Bu = sigma_ * u_ - S_ * u_;
      const double c = u_.dot(Bu), b = u_.dot(D * u_);
      const double q = quadratic ? u_.dot(family_.Q * u_) : 0.0;
      if (!(b > 0) && !(q > 0)) return kInf;
      // The positive root of c - b t - q t^2, without cancellation.
      const double next = 2 * c / (b + std::sqrt(b * b + 4 * q * c));
      // Settled to the digits that place a probe: a root close to a has t at the noise of
      // u^T B u, and would not settle to 1e-13 of t in the twelve rounds.
      const bool settled =
          std::abs(next - t) <= std::max(1e-13 * next, 1e-3 * kWidth * (a + next));
      t = next;
      if (!quadratic || settled) break;
      // A Lanczos run that did not converge (a clustered top, far from the root: the damped
      // 40k plane's dt search from dt = 0.05 took 12 such rounds, 720 solves, to move t by
      // 1.5e-5) gives an upper estimate all the same: the probes just below it and the
      // estimate from there, close to the root where the top separates, cost less than
      // another round here (a second round moved the plane's t by 1.2e-5 for 60 solves).
      if (!converged_) break;
      if (round == 11) converged_ = false;
    }
    return a + t;
  }

  /// Whether the last estimate's Lanczos run (and t, where S is quadratic) converged.
  bool converged() const { return converged_; }
  int factorizations() const { return f_ ? f_->factorizations - factorizations_before_ : 0; }
  int solves() const { return f_ ? f_->solves - solves_before_ : 0; }

 private:
  /// u_: the top Ritz vector of B^-1 M, M = D + t Q, by Lanczos in B's inner product (B =
  /// sigma I - S at the factored point), from the last u_ (or Lanczos's usual start).
  void top_vector(const SparseMatrix& D, double t) {
    const Eigen::Index n = S_.rows();
    if (u_.size() != n) u_ = family_.start.size() == n ? family_.start : lanczos_start(n);
    const auto B = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return sigma_ * v - S_ * v; };
    const auto M = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
      return t > 0 ? Eigen::VectorXd(D * v + t * (family_.Q * v)) : Eigen::VectorXd(D * v);
    };
    const int k = static_cast<int>(std::min<Eigen::Index>(kLanczosSteps, n));
    // The bases live as long as the search: a fresh 2 x 57 MB on the 40k plane at every run
    // cost a seventh of the search in page faults.
    if (V_.rows() != n || V_.cols() != k) {
      V_.resize(n, k);
      BV_.resize(n, k);
    }
    Eigen::MatrixXd& V = V_;
    Eigen::MatrixXd& BV = BV_;
    Eigen::VectorXd Bv = B(u_);
    double norm = std::sqrt(std::max(u_.dot(Bv), 0.0));
    if (!(norm > 0)) return;
    V.col(0) = u_ / norm;
    BV.col(0) = Bv / norm;
    Eigen::MatrixXd T = Eigen::MatrixXd::Zero(k, k);
    Eigen::VectorXd w(n), z(n);
    double theta_before[2] = {0, 0};  // the top Ritz value one and two steps back
    for (int j = 0; j < k; ++j) {
      w = M(V.col(j));
      f_->solve(w.data(), z.data());  // z = B^-1 M v_j
      const auto basis = V.leftCols(j + 1);
      const auto Bbasis = BV.leftCols(j + 1);
      // Orthogonal in B's inner product, twice: <z, v_i>_B = (B v_i)^T z.
      const Eigen::VectorXd h = Bbasis.transpose() * z;
      z -= basis * h;
      const Eigen::VectorXd h2 = Bbasis.transpose() * z;
      z -= basis * h2;
      T(j, j) = h(j) + h2(j);
      Bv = B(z);
      const double beta = std::sqrt(std::max(z.dot(Bv), 0.0));
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(T.topLeftCorner(j + 1, j + 1));
      const double theta = es.eigenvalues()(j);
      const Eigen::VectorXd y = es.eigenvectors().col(j);
      const bool last = j + 1 == k || !(beta > 0);
      const double settled = kRitzSettled * std::abs(theta);
      converged_ = beta * std::abs(y(j)) < kRitzTolerance * std::abs(theta) ||
                   (j >= 2 && std::abs(theta - theta_before[0]) <= settled &&
                    std::abs(theta - theta_before[1]) <= settled);
      theta_before[1] = theta_before[0];
      theta_before[0] = theta;
      if (last || converged_) {
        u_ = basis * y;
        return;
      }
      T(j, j + 1) = T(j + 1, j) = beta;
      V.col(j + 1) = z / beta;
      BV.col(j + 1) = Bv / beta;
    }
  }

  const IndexFamily& family_;
  std::unique_ptr<ShiftedCholesky> own_;
  std::unique_ptr<ShiftedCholesky>& f_;
  double budget_;
  int factorizations_before_ = f_ ? f_->factorizations : 0;
  int solves_before_ = f_ ? f_->solves : 0;
  SparseMatrix S_;
  Eigen::VectorXd u_;
  Eigen::MatrixXd V_, BV_;  ///< top_vector's Lanczos basis and B times it
  double sigma_ = 4 * (1 - 1e-11);
  bool converged_ = false;
  double factored_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace

DefiniteRoot definite_root(const IndexFamily& family, double from,
                           std::unique_ptr<ShiftedCholesky>* factors, double max_factor_flops) {
  Search search(family, factors, max_factor_flops);
  DefiniteRoot r;
  const auto done = [&](double stable, double unstable) {
    r.stable = stable;
    r.unstable = unstable;
    r.factorizations = search.factorizations();
    r.solves = search.solves();
    return r;
  };
  double a = from, b = kInf;
  bool found = search.stable(a);
  for (int k = 0; k < 200 && !found && a > 0; ++k) {
    b = a;
    a /= 2;
    found = search.stable(a);
  }
  if (!found) return done(0, a);
  // a proved stable, b not (or +inf). Each round estimates the root from above at the latest
  // stable point and probes just below the estimate, then just above what that proves; where
  // a probe goes the other way (the estimate was off by more than the width), bisection in
  // [a, b] takes over until the next stable point, whose estimate is closer.
  bool fresh = true;  // the factor in hand is a's
  double back = 0;    // after an estimate that did not converge: the last step back from it
  for (int round = 0; round < 100 && (std::isinf(b) || b - a > kWidth * b); ++round) {
    double c;
    if (fresh) {
      const double above = search.estimate(a);
      if (std::isinf(above) && std::isinf(b)) return done(kInf, kInf);
      const double target = std::min(above, b);
      const double width = kWidth * target;
      // Just below a converged estimate: proved stable where the estimate is within 0.4 of
      // the width. An estimate whose Lanczos run did not converge may lie further above the
      // root: the probe steps back from it by kFirstStepBack of the way to a, then a hundred
      // times further at each probe that fails (at most two fail before one a tenth of the
      // way back). A probe close to the root is worth a factorisation or two: there the top
      // of B^-1 D stands apart and the next run converges in a few steps, where one a
      // thousandth of the way back took a whole run that did not.
      back = search.converged() ? 0.0 : std::max(0.4 * width, kFirstStepBack * (target - a));
      c = target - (back > 0 ? back : 0.4 * width);
      if (!(c > a)) c = a + 0.5 * (target - a);  // the estimate is within the width of a
      if (!(c > a)) return done(a, target);
    } else if (back > 0 && !std::isinf(b)) {
      back *= 100;
      c = std::max(b - back, a + 0.5 * (b - a));
    } else {
      c = std::isinf(b) ? 2 * a : a + 0.5 * (b - a);
    }
    if (!(c < b)) c = a + 0.5 * (b - a);
    const bool close = fresh && search.converged();
    if (search.stable(c)) {
      a = c;
      fresh = true;
      // A converged estimate put the root within 0.4 widths above c: the probe just above a.
      const double above = a + 0.9 * kWidth * a;
      if (close && above < b) {
        if (search.stable(above)) {
          a = above;
        } else {
          b = above;
          fresh = false;
        }
      }
    } else {
      b = c;
      fresh = false;
    }
  }
  return done(a, b);
}

}  // namespace dampbound::detail
