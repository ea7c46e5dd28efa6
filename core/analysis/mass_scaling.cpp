#include "core/analysis/mass_scaling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/analysis/detail/shifted_cholesky.hpp"
#include "core/analysis/linear_stability_cholesky.hpp"
#include "core/analysis/suggest.hpp"
#include "core/physics/detail/numbers.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound {
namespace {


/// The margin SPEC 11 adds to a scaled node: m'_i = m_req_i (1 + 1e-6).
constexpr double kLocalMargin = 1e-6;

/// Lanczos steps at most for the top mode that places a dt limit's first bracket (it stops
/// once its Ritz value settles to 1e-6).
constexpr int kLanczosSteps = 300;

}  // namespace

const char* to_string(MassScalingCase c) {
  switch (c) {
    case MassScalingCase::nothing_to_add: return "nothing_to_add";
    case MassScalingCase::no_mass_helps: return "no_mass_helps";
    case MassScalingCase::scaled: return "scaled";
  }
  return "?";
}

/// K and C' on the union of their patterns, entry for entry, so that N(h) = h^2 K + 2 h C'
/// and its weighting by M^-1/2 keep one pattern for every h and every m (one analysis).
struct IndexCertifier::Impl {
  SparseMatrix pattern;             // the union; its values are rewritten for each call
  std::vector<double> k, c;         // K's and C''s values on it
  std::vector<Eigen::Index> row;    // each entry's row
  double alpha = 0;
  double budget = 0;
  std::unique_ptr<detail::ShiftedCholesky> chol;

  Impl(const MassScalingProblem& p, double max_factor_flops)
      : alpha(p.alpha), budget(max_factor_flops) {
    SparseMatrix K = p.K + 0.0 * p.C, C = 0.0 * p.K + p.C;
    K.makeCompressed();
    C.makeCompressed();
    // Both sums run over the union of the two patterns in the same order (no entry pruned).
    if (K.nonZeros() != C.nonZeros() ||
        !std::equal(K.innerIndexPtr(), K.innerIndexPtr() + K.nonZeros(), C.innerIndexPtr()) ||
        !std::equal(K.outerIndexPtr(), K.outerIndexPtr() + K.outerSize() + 1, C.outerIndexPtr()))
      throw std::logic_error("IndexCertifier: K and C' on different patterns");
    pattern = K;
    k.assign(K.valuePtr(), K.valuePtr() + K.nonZeros());
    c.assign(C.valuePtr(), C.valuePtr() + C.nonZeros());
    for (Eigen::Index j = 0; j < pattern.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(pattern, j); it; ++it) row.push_back(it.row());
  }

  /// The h at which Lanczos's top Ritz vector y of M^-1/2 N(hint) M^-1/2 meets the index's
  /// bound: h^2 a + 2 h (c + alpha) = 4, a = y^T A y, c = y^T M^-1/2 C' M^-1/2 y (0: none).
  double mode_limit(const std::vector<double>& mass, double hint) {
    if (pattern.rows() == 0) return 0;
    fill(mass, hint);
    Eigen::VectorXd y;
    unfactored_largest_eigenvalue(pattern, &y, 1, kLanczosSteps);
    if (y.size() != pattern.rows() || !y.allFinite()) return 0;
    double a = 0, cy = 0;
    size_t e = 0;
    for (Eigen::Index j = 0; j < pattern.outerSize(); ++j)
      for (int q = pattern.outerIndexPtr()[j]; q < pattern.outerIndexPtr()[j + 1]; ++q, ++e) {
        const size_t r = static_cast<size_t>(row[e]);
        const double yy = y(row[e]) * y(j) / std::sqrt(mass[r / 3] * mass[static_cast<size_t>(j) / 3]);
        a += yy * k[e];
        cy += yy * c[e];
      }
    const double b = cy + alpha;
    if (a > 0) return (std::sqrt(b * b + 4 * a) - b) / a;
    return b > 0 ? 2 / b : 0;
  }

  /// pattern := M^-1/2 N(h) M^-1/2.
  void fill(const std::vector<double>& mass, double h) {
    std::vector<double> w(static_cast<size_t>(pattern.rows()));
    for (size_t r = 0; r < w.size(); ++r) w[r] = 1.0 / std::sqrt(mass[r / 3]);
    double* v = pattern.valuePtr();
    size_t e = 0;
    for (Eigen::Index j = 0; j < pattern.outerSize(); ++j)
      for (int q = pattern.outerIndexPtr()[j]; q < pattern.outerIndexPtr()[j + 1]; ++q, ++e)
        v[e] = (h * h * k[e] + 2 * h * c[e]) * w[static_cast<size_t>(row[e])] *
               w[static_cast<size_t>(j)];
  }
};

IndexCertifier::IndexCertifier(const MassScalingProblem& p, double max_factor_flops)
    : impl_(std::make_unique<Impl>(p, max_factor_flops)) {}
IndexCertifier::~IndexCertifier() = default;

int IndexCertifier::factorizations() const {
  return impl_->chol ? impl_->chol->factorizations : 0;
}

bool IndexCertifier::stable(const std::vector<double>& mass, double h) {
  Impl& d = *impl_;
  // lambda_max(h^2 A + 2 h C^) = lambda_max(M^-1/2 N M^-1/2) + 2 h alpha < 4 (C^ = M^-1/2 C'
  // M^-1/2 + alpha I): a factorisation of t I - M^-1/2 N M^-1/2 at a shift just below
  // t = 4 - 2 h alpha, whose rounding bound still leaves it below t, certifies it.
  const double t = 4 - 2 * h * d.alpha;
  if (!(t > 0)) return false;
  if (d.pattern.rows() == 0) return true;
  d.fill(mass, h);
  if (!d.chol)
    d.chol = std::make_unique<detail::ShiftedCholesky>(d.pattern);
  else
    d.chol->assign(d.pattern);
  d.chol->analyse(d.budget);  // once per pattern, before any factorisation
  double sigma = t * (1 - 1e-10);
  for (int k = 0; k < 3; ++k) {
    if (!d.chol->factor(sigma)) return false;
    const double above = d.chol->proved_above();
    if (above <= t) return true;
    sigma = t - 2 * (above - sigma);  // the rounding bound was wider than the room left
    if (!(sigma > 0)) return false;
  }
  return false;
}

double IndexCertifier::dt_limit(const std::vector<double>& mass, double hint, double relative) {
  // First the top mode's own limit: Lanczos's top Ritz vector y of the index matrix at `hint`
  // gives a = y^T A y and c = y^T C^ y, and h^2 a + 2 h c = 4 at h_y. A vector's quotient is at
  // most the largest eigenvalue, so h_y is at or above the limit, and at it where that mode
  // stays on top: two factorisations around it then bracket the limit. Else bisection.
  // The top mode at `hint` need not be the one on top at the limit (damping weighs more at a
  // smaller dt): the mode's limit is taken again at the last one until it settles, a few
  // Lanczos runs and no factorisation, like Newton's steps from the unstable side.
  double guess = hint;
  for (int k = 0; k < 8; ++k) {
    const double next = impl_->mode_limit(mass, guess);
    if (!(next > 0 && std::isfinite(next))) break;
    const bool settled = std::abs(next - guess) <= relative / 4 * next;
    guess = next;
    if (settled) break;
  }
  if (guess > 0 && std::isfinite(guess) && guess != hint) {
    const double lo = guess / (1 + relative / 2), hi = guess * (1 + relative / 2);
    if (stable(mass, lo) && !stable(mass, hi)) return lo;
    hint = guess;  // bisection from the nearest point known
  }
  double lo = hint, hi = hint;
  if (stable(mass, hint)) {
    hi = hint * 1.01;
    for (int k = 0; stable(mass, hi); ++k) {
      if (k == 60) return kInf;
      lo = hi;
      hi *= 2;
    }
  } else {
    lo = hint / 2;
    for (int k = 0; !stable(mass, lo); ++k) {
      if (k == 60) return 0;
      hi = lo;
      lo /= 2;
    }
  }
  while (hi - lo > relative * lo) {
    const double mid = 0.5 * (lo + hi);
    (stable(mass, mid) ? lo : hi) = mid;
  }
  return lo;
}

std::vector<double> required_masses(const MassScalingProblem& p, double h) {
  const double denominator = 4 - 2 * h * p.alpha;
  std::vector<double> rows(static_cast<size_t>(p.K.rows()), 0.0);
  const SparseMatrix N = (h * h) * p.K + (2 * h) * p.C;
  for (Eigen::Index j = 0; j < N.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(N, j); it; ++it)
      rows[static_cast<size_t>(it.row())] += std::abs(it.value());
  std::vector<double> m(p.mass.size());
  for (size_t i = 0; i < m.size(); ++i)
    m[i] = std::max({rows[3 * i], rows[3 * i + 1], rows[3 * i + 2]}) / denominator;
  return m;
}

namespace {

void check(const MassScalingProblem& p, double dt_target, const MassScalingOptions& o) {
  const Eigen::Index n = 3 * static_cast<Eigen::Index>(p.mass.size());
  if (p.K.rows() != n || p.K.cols() != n || p.C.rows() != n || p.C.cols() != n)
    throw std::invalid_argument("mass_scaling: K and C must be 3n x 3n for n masses");
  if (!(dt_target > 0) || !std::isfinite(dt_target))
    throw InputError("mass scaling: the target dt must be finite and > 0 (got " +
                     std::to_string(dt_target) + ")");
  if (!(o.safety > 0 && o.safety <= 1))
    throw InputError("mass scaling: the safety factor must lie in (0, 1] (got " +
                     std::to_string(o.safety) + ")");
  if (!(o.max_added >= 0) || !std::isfinite(o.max_added))
    throw InputError("mass scaling: the cap on the added mass must be finite and >= 0 (got " +
                     std::to_string(o.max_added) + ")");
  if (!(o.tolerance > 0 && o.tolerance < 1))
    throw std::invalid_argument("mass_scaling: tolerance must lie in (0, 1)");
  if (!(p.alpha >= 0)) throw std::invalid_argument("mass_scaling: alpha must be >= 0");
  for (double m : p.mass)
    if (!(m > 0) || !std::isfinite(m))
      throw std::invalid_argument("mass_scaling: every mass must be finite and > 0");
}

/// The local rule at dt_g: m'_i where m_i <= m_req_i (scaled), else m_i.
void local_rule(const MassScalingProblem& p, double h, MassScalingResult& r) {
  const std::vector<double> req = required_masses(p, h);
  r.mass_local = p.mass;
  r.scaled.assign(p.mass.size(), 0);
  r.scaled_count = 0;
  r.added_local = 0;
  for (size_t i = 0; i < req.size(); ++i)
    if (p.mass[i] <= req[i]) {
      r.mass_local[i] = req[i] * (1 + kLocalMargin);
      r.scaled[i] = 1;
      ++r.scaled_count;
      r.added_local += r.mass_local[i] - p.mass[i];
    }
}

std::vector<double> along(const std::vector<double>& m, const std::vector<double>& m1, double s) {
  std::vector<double> out(m.size());
  for (size_t i = 0; i < m.size(); ++i) out[i] = m[i] + s * (m1[i] - m[i]);
  return out;
}

/// The smallest s in [0, 1] (to tol) at which m(s) is certified stable at h; m(0) is not.
double tighten(IndexCertifier& index, const std::vector<double>& m, const std::vector<double>& m1,
               double h, double tol, bool& certified_at_one) {
  certified_at_one = index.stable(m1, h);
  double lo = 0, hi = 1;
  while (hi - lo > tol) {
    const double mid = 0.5 * (lo + hi);
    (index.stable(along(m, m1, mid), h) ? hi : lo) = mid;
  }
  return hi;
}

}  // namespace

MassScalingResult mass_scaling(const MassScalingProblem& p, double dt_target,
                               const MassScalingOptions& o) {
  check(p, dt_target, o);
  const auto stage = [&](const std::string& next) {
    if (o.progress && !o.progress(next)) throw SuggestCancelled();
  };
  MassScalingResult r;
  r.dt_target = dt_target;
  r.safety = o.safety;
  r.dt_design = dt_target / o.safety;
  r.cap = o.max_added;
  for (double m : p.mass) r.free_mass += m;
  const double h = r.dt_design;
  if (p.alpha > 0) r.dt_no_mass = 2 * o.safety / p.alpha;
  IndexCertifier index(p, o.max_factor_flops);
  if (2 * h * p.alpha >= 4) {
    r.kind = MassScalingCase::no_mass_helps;
    return r;
  }
  stage("the exact dt limit as given");
  r.dt_limit_before = index.dt_limit(p.mass, h);
  if (index.stable(p.mass, h)) {
    r.kind = MassScalingCase::nothing_to_add;
    r.factorizations = index.factorizations();
    return r;
  }
  r.kind = MassScalingCase::scaled;
  local_rule(p, h, r);
  stage("tightening the local rule with the exact index");
  r.s_star = tighten(index, p.mass, r.mass_local, h, o.tolerance, r.local_certified);
  r.mass = along(p.mass, r.mass_local, r.s_star);
  r.added = 0;
  for (size_t i = 0; i < p.mass.size(); ++i) r.added += r.mass[i] - p.mass[i];
  stage("the exact dt limit of the scaled model");
  // Certified at dt_g by the bisection's last point, so the limit is at least dt_g.
  r.dt_limit = std::max(index.dt_limit(r.mass, h), h);
  r.over_cap = r.added > o.max_added * r.free_mass;
  if (r.over_cap && r.dt_limit_before > 0) {
    // The largest dt* within the cap: at dt* the cap's mass along the local rule's direction,
    // m + s_c (m' - m) with s_c = cap / added', certified stable (the least along it is then
    // within the cap). Between f x the limit as given (nothing to add) and the target.
    stage("the largest dt* within the cap");
    const double cap_mass = o.max_added * r.free_mass;
    const auto within = [&](double dt) {
      const double hg = dt / o.safety;
      if (2 * hg * p.alpha >= 4) return false;
      MassScalingResult at;
      local_rule(p, hg, at);
      if (at.added_local <= cap_mass) return true;
      return index.stable(along(p.mass, at.mass_local, cap_mass / at.added_local), hg);
    };
    double lo = o.safety * r.dt_limit_before, hi = dt_target;
    while (hi - lo > o.tolerance * lo) {
      const double mid = 0.5 * (lo + hi);
      (within(mid) ? lo : hi) = mid;
    }
    r.dt_cap = lo;
    // What was certified there: the cap's mass along the rule's direction, or the rule's own
    // where that is less (nothing where lo is the limit as given).
    MassScalingResult at;
    local_rule(p, lo / o.safety, at);
    r.dt_cap_added = index.stable(p.mass, lo / o.safety) ? 0.0 : std::min(cap_mass, at.added_local);
  }
  r.factorizations = index.factorizations();
  return r;
}

}  // namespace dampbound
