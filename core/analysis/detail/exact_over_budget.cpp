// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/detail/exact_over_budget.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "core/analysis/detail/index_patch.hpp"
#include "core/analysis/linear_stability_modes.hpp"
#include "core/physics/detail/numbers.hpp"
#include "core/physics/integrate.hpp"
#include "core/physics/safe_bound.hpp"

namespace dampbound::detail {
namespace {


/// The long double sum of n non-negative terms u_i^2 R_i over u^T u, less a bound on its
/// rounding (gamma_{n+1} of itself, twice, and the conversion): a lower bound on the true
/// quotient.
double weighted_mean_below(const Eigen::VectorXd& u, const Eigen::VectorXd& R) {
  long double uRu = 0, uu = 0;
  for (Eigen::Index i = 0; i < u.size(); ++i) {
    const long double s = static_cast<long double>(u(i)) * u(i);
    uRu += s * R(i);
    uu += s;
  }
  const long double unit = std::numeric_limits<long double>::epsilon() / 2;
  const long double terms = static_cast<long double>(u.size()) + 2;
  const long double gamma = terms * unit / (1 - terms * unit);
  const double q = static_cast<double>(uRu / uu);
  const double rounding = static_cast<double>(3 * gamma) + std::numeric_limits<double>::epsilon();
  return std::max(0.0, q - rounding * q);
}

/// Over the budget, forward Euler, Verlet and RK4 at a uniform rate (`r` = gamma_i/(gamma
/// m_i)): their modes decouple, so the closed forms of linear_stability_modes.hpp prove
/// instability from the Rayleigh quotient `top.lo` (mode_instability) and, where SPEC 9's
/// floor proves K >= 0, stability from `top.hi` (mode_stability), the lower of Gershgorin's
/// bound and the splitting's (splitting_ceilings).
void per_mode_proofs(double r, const EigenInterval& top, std::optional<double> floor,
                     const Params& params, ExactStability& e) {
  ExactStability::Unfactored& b = e.unfactored;
  const double h = params.dt, c = params.gamma * r;
  if (floor && *floor >= 0) {                // K >= 0: every mode in [0, hi]
    const double hi = top.hi * (1 + 1e-12);  // room for the rounding of the bound's sums
    const ModeStability m = mode_stability(params.integrator, hi, c, h);
    if (m.proved) {
      b.stable_lambda_hi = hi;
      b.dt_stable_up_to = m.dt_up_to;
      if (r > 0) {  // rounded inwards
        auto inward = [](double v, double to) {
          return std::isinf(v) || v == 0 ? v : std::nextafter(v, to);  // 0: exact
        };
        b.gamma_stable_lo = inward(m.rate_lo / r, kInf);
        b.gamma_stable_hi = inward(m.rate_hi / r, -kInf);
      } else {  // gamma changes nothing: every gamma or none
        b.gamma_stable_lo = m.stable ? 0 : kInf;
        b.gamma_stable_hi = m.stable ? kInf : 0;
      }
      e.stable = m.stable;
    }
  }
  const ModeInstability m = mode_instability(params.integrator, top.lo, c, h);
  if (std::isnan(m.lambda_from)) return;
  b.mode_unstable_from = m.lambda_from;
  b.dt_unstable_from = m.dt_from;
  // Rounded down: the unstable side. With no damping rate anywhere gamma changes nothing:
  // every gamma is unstable (inf) or none is proved (-inf).
  if (std::isnan(m.rate_below))  // RK4: no threshold in gamma
    b.gamma_unstable_below = kNaN;
  else if (r > 0)
    b.gamma_unstable_below =
        std::isfinite(m.rate_below) ? std::nextafter(m.rate_below / r, -kInf) : -kInf;
  else
    b.gamma_unstable_below = m.rate_below >= 0 ? kInf : -kInf;
}

/// What a per-node bound on the index matrix proves for the paper's step (below).
struct IndexProof {
  double top = 0, gamma_hi = kInf, dt_hi = kInf;
};

/// From per-node bounds r_i with lambda_max(S) <= max_i (h^2 r_i + 2 h c_i) for the index
/// matrix S = h^2 A + 2 h C and every h, c >= 0: the index at the user's gamma and dt, every
/// gamma up to min_i (2 m_i/h - m_i h r_i/2) / gamma_scale_i at dt and every dt up to the
/// root of h^2 r_i + 2 h c_i = 4 at gamma, with r_i raised and the limits lowered (by the
/// caller) by 1e-12 of themselves for rounding.
IndexProof index_proof(const Model& model, const Params& params, const std::vector<double>& bound) {
  IndexProof p;
  const double h = params.dt;
  for (size_t i = 0; i < bound.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    const double r = bound[i] * (1 + 1e-12), m = model.mass[i], scale = model.spec().gamma_scale[i];
    const double gamma_i = params.gamma * scale, safe = safe_gamma(m, h, r);
    p.top = std::max(p.top, h * h * r + 2 * h * gamma_i / m);
    if (scale > 0)
      p.gamma_hi = std::min(p.gamma_hi, safe / scale);
    else if (safe <= 0)
      p.gamma_hi = -kInf;  // an undamped node past the index already: no gamma helps
    // safe_dt's root without its cancellation: (sqrt(c^2 + 4 R) - c) / R, SPEC 9's form that
    // the reports print, loses 1e-11 of itself at c = 1000, R = 9, more than 1e-12 allows.
    const double c = gamma_i / m;
    if (r > 0 || c > 0) p.dt_hi = std::min(p.dt_hi, 4 / (c + std::sqrt(c * c + 4 * r)));
  }
  return p;
}

/// Over the budget, the paper's step with SPEC 10's dashpot or Rayleigh damping and K >= 0:
/// Gershgorin on the whole index matrix S = h^2 A + 2 h (Gamma + C')^ (SPEC 10's safe rows,
/// NodeSafeBounds). Row r of node i is at most 4 - margin_r, and the rows' gamma_safe_i =
/// m_i / (2h) min_r (margin_r without the nodal term) make that 4 - 2h (gamma_safe_i -
/// gamma_i) / m_i; every gamma below min_i gamma_safe_i / scale_i and every dt below
/// min_i dt_safe_i keeps each row inside. The splitting and the nodal rows ignore C' and
/// prove nothing here.
void damped_step_ceilings(const Model& model, const std::vector<Vec3>& x, const Params& params,
                          ExactStability& e) {
  ExactStability::Unfactored& b = e.unfactored;
  constexpr double kIn = 1 - 1e-12;
  const double h = params.dt;
  const NodeSafeBounds rows(model, x);
  double top = 0, gamma_hi = kInf, dt_hi = kInf;
  for (size_t i = 0; i < model.mass.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    const int node = static_cast<int>(i);
    const double m = model.mass[i], scale = model.spec().gamma_scale[i];
    const double gamma_i = params.gamma * scale, g = rows.gamma_safe(node, h);
    top = std::max(top, 4 - 2 * h * (g - gamma_i) / m);
    gamma_hi = std::min(gamma_hi, safe_user_gamma(g, scale));
    dt_hi = std::min(dt_hi, rows.dt_safe(node, gamma_i));
  }
  b.index_gershgorin = b.index_at_most = top * (1 + 1e-12);
  if (gamma_hi > 0) {
    b.gamma_stable_lo = 0;
    b.gamma_stable_hi = std::isinf(gamma_hi) ? gamma_hi : gamma_hi * kIn;
  }
  b.dt_stable_up_to = std::isinf(dt_hi) ? dt_hi : dt_hi * kIn;
  e.stable = b.index_at_most < 4;
}

/// Over the budget, the paper's step with K >= 0 (SPEC 9's floor), from two per-node bounds on
/// the index matrix S = h^2 A + 2 h C, each a proof: SPEC 9's safe bound (core/physics/safe_bound.hpp),
/// Gershgorin node by node (R_i, safe_row_sums), and the splitting of K into node blocks
/// (splitting_ceilings). An index below 4 is stability (SPEC 7, 9), so the exact rows prove
/// what the safe rows judge, or more where the splitting is tighter: the user's point, and
/// each limit from whichever bound proves more.
void paper_step_ceilings(const Model& model, const std::vector<Vec3>& x,
                         const std::vector<double>& ceiling, const Params& params,
                         ExactStability& e) {
  ExactStability::Unfactored& b = e.unfactored;
  constexpr double kIn = 1 - 1e-12;
  if (model.spring_damping) {
    damped_step_ceilings(model, x, params, e);
    return;
  }
  std::vector<double> R;
  safe_row_sums(model, x, R);
  const IndexProof g = index_proof(model, params, R), s = index_proof(model, params, ceiling);
  b.index_gershgorin = g.top * (1 + 1e-12);
  b.index_at_most = std::min(g.top, s.top) * (1 + 1e-12);
  const double gamma_hi = std::max(g.gamma_hi, s.gamma_hi), dt_hi = std::max(g.dt_hi, s.dt_hi);
  if (gamma_hi > 0) {
    b.gamma_stable_lo = 0;
    b.gamma_stable_hi = std::isinf(gamma_hi) ? gamma_hi : gamma_hi * kIn;
  }
  b.dt_stable_up_to = std::isinf(dt_hi) ? dt_hi : dt_hi * kIn;
  e.stable = b.index_at_most < 4;
}

/// The index's lower bound from a vector u (zero outside `patch`): h^2 a + 2 h gamma rho with
/// a and rho its quotients less their rounding, less 4 eps of itself.
double index_below(const IndexPatch& patch, const Eigen::VectorXd& u, const ExactInputs& in,
                   double gamma, double h) {
  const double index =
      h * h * patch.rayleigh_below(u) + 2 * h * gamma * weighted_mean_below(u, in.R);
  return index - 4 * std::numeric_limits<double>::epsilon() * std::abs(index);
}

/// The patch around the top of S = h^2 A + 2 h gamma diag(R) (A itself at gamma 0, h 1) that
/// index_patch.hpp describes, or none: first a pilot, the nodes of the largest node-by-node
/// bound and 2 rings, whose principal submatrix's top vector proves a lower bound that may
/// prune the seeds more than `at_least` (where Lanczos's vector was aimed elsewhere, or a
/// stiff region's top lies far above the rest's bounds); then the smallest of 3, 6 and 12
/// rings whose two bounds meet to 1e-9 at (gamma, h) (`at_most`, where given, receives its
/// upper bound), else the largest found. A patch whose dense factorisation exceeds the budget
/// is not used.
std::optional<IndexPatch> choose_patch(const Model& model, const std::vector<Vec3>& x,
                                       const ExactInputs& in, const std::vector<double>& ceiling,
                                       double gamma, double h, double at_least, double budget,
                                       double* at_most) {
  int nfree = 0;
  const std::vector<int> block = free_blocks(model, &nfree);
  double largest = 0;
  for (size_t i = 0; i < block.size(); ++i)
    if (block[i] >= 0)
      largest = std::max(largest, h * h * ceiling[i] + 2 * h * gamma * in.R(3 * block[i]));
  const IndexPatch pilot(model, x, in.A, in.R, ceiling, gamma, h, largest, 2);
  if (pilot.found() && pilot.flops() <= budget)
    at_least = std::max(at_least, index_below(pilot, pilot.vector(gamma, h), in, gamma, h));
  std::optional<IndexPatch> patch;
  for (const int layers : IndexPatch::kLayers) {
    IndexPatch p(model, x, in.A, in.R, ceiling, gamma, h, at_least, layers);
    if (!p.found() || p.flops() > budget) break;
    patch.emplace(std::move(p));
    if (!at_most) break;
    *at_most = patch->index_at_most(gamma, h);
    if (*at_most - at_least <= 1e-9 * at_least) break;
  }
  return patch;
}

/// Where A's own top is local (a stiff or finely meshed region), a patch around it (gamma 0,
/// dt 1) narrows the bracket of lambda_max from both sides.
void lambda_patch(const Model& model, const std::vector<Vec3>& x, const ExactInputs& in,
                  const std::vector<double>& ceiling, double budget, EigenInterval& bracket,
                  ExactStability::Unfactored& b) {
  double at_most = kInf;
  const std::optional<IndexPatch> patch =
      choose_patch(model, x, in, ceiling, 0, 1, bracket.lo, budget, &at_most);
  if (!patch) return;
  const double lo = patch->rayleigh_below(patch->vector(0, 1));
  if (lo <= bracket.lo && at_most >= bracket.hi) return;
  b.lambda_patch_nodes = patch->node_count();
  bracket.lo = std::max(bracket.lo, lo);
  bracket.hi = std::min(bracket.hi, at_most);
}

/// Over the budget, the paper's step, where the index's top is local (detail/index_patch.hpp)
/// and one dense factorisation of the patch is within the budget: a patch of nodes around it
/// proves the index from below (its principal submatrix's top
/// vector, through `unstable_from`) at the user's gamma and dt and at each limit found, and,
/// with K >= 0 (`psd`), from above: the index at the user's point, and by bisection the largest
/// gamma (at dt) and dt (at gamma) it proves stable. The true index grows with gamma, and with
/// dt where A >= 0, so a point proved stable proves every gamma in [0, it] or dt up to it.
template <class UnstableFrom>
void patch_proofs(const Model& model, const std::vector<Vec3>& x, const ExactInputs& in,
                  const std::vector<double>& ceiling, const Params& params, bool psd,
                  double max_factor_flops, const UnstableFrom& unstable_from, ExactStability& e) {
  ExactStability::Unfactored& b = e.unfactored;
  const double h = params.dt, gamma = params.gamma;
  double at_most = kInf;
  const std::optional<IndexPatch> patch =
      choose_patch(model, x, in, ceiling, gamma, h, b.index_at_least, max_factor_flops,
                   psd ? &at_most : nullptr);
  if (!patch) return;
  b.patch_nodes = patch->node_count();
  const auto from_vector = [&](double g, double t) {
    const Eigen::VectorXd u = patch->vector(g, t);
    unstable_from(patch->rayleigh_below(u), weighted_mean_below(u, in.R), false);
  };
  from_vector(gamma, h);
  if (!psd) return;
  if (at_most < b.index_at_most) {
    b.index_patch = at_most;
    b.index_at_most = at_most;
    e.stable = at_most < 4;
  }
  // lo proved stable, hi not (proved unstable, or not proved): halve [lo, hi] down to 1e-13
  // of hi; a bound that proves nothing at lo leaves it.
  const auto bisect = [](double lo, double hi, const auto& stable) {
    for (int k = 0; k < 200 && hi - lo > 1e-13 * hi; ++k) {
      const double mid = lo + (hi - lo) / 2;
      (stable(mid) ? lo : hi) = mid;
    }
    return std::pair<double, double>{lo, hi};
  };
  const auto stable_gamma = [&](double g) { return patch->proved_below(4, g, h); };
  double gamma_lo = std::isnan(b.gamma_stable_hi) ? 0 : b.gamma_stable_hi;
  if (!std::isinf(gamma_lo) && stable_gamma(gamma_lo)) {
    // Nothing proved unstable (the vectors saw no damping): from 2 / (h max_r R_r) on some
    // diagonal entry of the index matrix, a Rayleigh quotient, is at least 4.
    const double gamma_hi = std::isinf(b.gamma_unstable_from) && in.r_max > 0
                                ? 2 / (h * in.r_max)
                                : b.gamma_unstable_from;
    if (gamma_hi > gamma_lo && !std::isinf(gamma_hi)) {
      const auto [lo, hi] = bisect(gamma_lo, gamma_hi, stable_gamma);
      if (std::isnan(b.gamma_stable_hi) || lo > b.gamma_stable_hi) {
        b.gamma_stable_lo = 0;
        b.gamma_stable_hi = lo;
      }
      from_vector(hi, h);
    }
  }
  const auto stable_dt = [&](double t) { return patch->proved_below(4, gamma, t); };
  const double dt_lo = std::isnan(b.dt_stable_up_to) ? 0 : b.dt_stable_up_to;
  if (dt_lo > 0 && !std::isinf(dt_lo) && stable_dt(dt_lo) && !std::isinf(b.dt_unstable_from)) {
    const auto [lo, hi] = bisect(dt_lo, b.dt_unstable_from, stable_dt);
    if (lo > b.dt_stable_up_to) b.dt_stable_up_to = lo;
    from_vector(gamma, hi);
  }
}

}  // namespace

ExactStability over_budget(const Model& model, const std::vector<Vec3>& x, const ExactInputs& in,
                           const Params& params, const ExactOptions& options,
                           const FactorisationOverBudget& over) {
  const std::optional<double> floor = psd_floor(model, x);
  ExactStability e;
  e.integrator = params.integrator;
  e.method = ExactMethod::over_budget;
  e.spectrum = {kNaN, kNaN};
  e.decaying = e.spectrum;
  e.lambda_max_lo = e.rate_min = e.rate_max = e.index = kNaN;
  e.uniform_rate = uniform_rates(in);
  e.spectral_radius = e.gamma_lo = e.gamma_hi = e.dt_max = kNaN;
  e.radius_converged = false;
  e.stable = false;
  e.factor_flops = over.flops;
  e.factor_bytes = over.bytes;
  e.factor_budget = over.budget;
  e.not_computed_reason = over.what();
  if (options.unfactored_steps < 1 || in.A.rows() == 0) return e;
  // The paper's step: the vector is aimed at the index matrix S = h^2 A + 2 h gamma diag(R)
  // at the user's gamma and dt, whose top decides stability (SPEC 7); others: at A.
  const double h = params.dt, gamma = params.gamma;
  const bool paper_step = integrator_traits(params.integrator).paper_step;
  Eigen::VectorXd u;
  const Eigen::VectorXd d = (2 * h * gamma) * in.R;
  const EigenInterval top =
      paper_step
          ? unfactored_largest_eigenvalue(in.A, &u, options.threads, options.unfactored_steps,
                                          h * h, &d)
          : unfactored_largest_eigenvalue(in.A, &u, options.threads, options.unfactored_steps);
  ExactStability::Unfactored& b = e.unfactored;
  // The upper end: Gershgorin's bound or the splitting's, whichever is lower.
  std::vector<double> ceiling;
  splitting_ceilings(model, x, ceiling);
  EigenInterval bracket = top;  // a fixed node's ceiling is 0
  if (!ceiling.empty())
    bracket.hi = std::min(top.hi, *std::max_element(ceiling.begin(), ceiling.end()));
  lambda_patch(model, x, in, ceiling, options.max_factor_flops, bracket, b);
  b.lambda_max_lo = bracket.lo;
  b.lambda_max_hi = bracket.hi;
  b.gershgorin = top.hi;
  b.lanczos_steps = top.lanczos_steps;
  // Implicit Euler needs no lambda_max: with K positive semidefinite (SPEC 9's floor proves
  // lambda_min >= 0, to the same rounding allowance as the computed route) it is stable for
  // every dt and gamma (unconditional()).
  if (integrator_traits(params.integrator).implicit && floor &&
      *floor >= -1e-12 * std::max(1.0, std::abs(top.hi))) {
    b.unconditional = true;
    e.stable = true;
  }
  // The per-mode proofs know the nodal rate only: with SPEC 10's damping they prove nothing.
  if (!paper_step && !model.spring_damping && in.r_max - in.r_min <= 1e-12 * in.r_max)
    per_mode_proofs(in.r_max, bracket, floor, params, e);
  if (!paper_step) return e;
  // index(gamma', h') >= u^T (h'^2 A + 2 h' gamma' diag(R)) u / u^T u
  //                  >= h'^2 a + 2 h' gamma' rho  (a, rho: the quotients less their rounding),
  // and index >= 4 is instability (SPEC 7), so each threshold below proves it; a second
  // vector (the patch's, below) keeps whichever proves more.
  const auto unstable_from = [&](double a, double rho, bool first) {
    constexpr double kUp = 1 + 4 * std::numeric_limits<double>::epsilon();
    const double index = h * h * a + 2 * h * gamma * rho;
    const double at_least = index - 4 * std::numeric_limits<double>::epsilon() * std::abs(index);
    double gamma_from = kInf;
    if (h * h * a >= 4 * kUp)
      gamma_from = 0;
    else if (rho > 0)
      gamma_from = (4 - h * h * a) / (2 * h * rho) * kUp;
    // dt: a t^2 + 2 c t >= 4 from its positive root on, when a > 0 (c >= 0).
    const double c = gamma * rho;
    const double dt_from = a > 0 ? 4 / (c + std::sqrt(c * c + 4 * a)) * kUp * kUp : kInf;
    b.index_at_least = first ? at_least : std::max(b.index_at_least, at_least);
    b.gamma_unstable_from = first ? gamma_from : std::min(b.gamma_unstable_from, gamma_from);
    b.dt_unstable_from = first ? dt_from : std::min(b.dt_unstable_from, dt_from);
  };
  unstable_from(top.lo, weighted_mean_below(u, in.R), true);
  if (floor && *floor >= 0) paper_step_ceilings(model, x, ceiling, params, e);
  // The patch's upper bound sees the nodal damping only; its lower bound holds with C' >= 0.
  patch_proofs(model, x, in, ceiling, params, floor && *floor >= 0 && !model.spring_damping,
               options.max_factor_flops, unstable_from, e);
  return e;
}

}  // namespace dampbound::detail
