#pragma once
// SPEC 11: the added mass that makes a target step stable, with a guarantee. Over the free
// degrees of freedom (3 per free node, fixed nodes have no rows and no columns), at rest:
// design for dt_g = dt* / f, N = 2 dt_g C' + dt_g^2 K with C' = C - alpha M; the local rule
// (Gershgorin on 4M - 2 dt_g C - dt_g^2 K) gives each node the mass m_req_i that makes its
// rows dominant, and the exact index of SPEC 10 shrinks that answer along the same direction
// to the least that is certified stable. docs/criteria.md, "Mass scaling", derives the rule.
// This file works on matrices (a scene's model or a user's own, linear_limits' route);
// mass_scaling_scene.hpp adds what a scene needs (its nodes, the run, the scaled scene).
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "dampbound/physics/stiffness.hpp"

namespace dampbound {

/// The linearised model the rule and the index read, over the free degrees of freedom.
struct MassScalingProblem {
  SparseMatrix K;            ///< stiffness (3n x 3n, symmetric, mass unit / s^2)
  SparseMatrix C;            ///< C' = C - alpha M: nodal, dashpot, beta K, anchor dashpots
  std::vector<double> mass;  ///< m_i of each of the n free nodes (> 0)
  double alpha = 0;          ///< Rayleigh's mass-proportional damping (1/s), scales with m
};

struct MassScalingOptions {
  double safety = 0.9;     ///< f in (0, 1]: design for dt_g = dt* / f (LS-DYNA's TSSFAC)
  double max_added = 0.05; ///< the cap: added mass as a fraction of the free mass
  double tolerance = 1e-3; ///< the bisection on s (and, relative, on dt* under the cap)
  /// The most one factorisation may cost (flops): FactorisationOverBudget
  /// (linear_stability_cholesky.hpp) before any over it. Infinite: no limit.
  double max_factor_flops = std::numeric_limits<double>::infinity();
  /// Called before each stage with what runs next; returning false stops the call with
  /// SuggestCancelled (suggest.hpp).
  std::function<bool(const std::string& next)> progress;
};

enum class MassScalingCase {
  nothing_to_add,  ///< already stable at dt_g by the exact index
  no_mass_helps,   ///< 2 dt_g alpha >= 4: mass-proportional damping alone is unstable
  scaled,          ///< mass added (within the cap or not: `over_cap`)
};
const char* to_string(MassScalingCase c);

struct MassScalingResult {
  MassScalingCase kind = MassScalingCase::scaled;
  double dt_target = 0, safety = 0, dt_design = 0;  ///< dt*, f, dt_g = dt* / f (s)
  double free_mass = 0;            ///< sum of m_i over the free nodes
  double dt_limit_before = 0;      ///< exact dt limit with the masses as given (s; inf: none)
  double dt_no_mass = std::numeric_limits<double>::infinity();  ///< 2 f / alpha (s)
  /// Per free node (the problem's order): the local rule's m'_i, the answer m_i(s*) and
  /// whether the node is scaled (m_i <= m_req_i). Empty unless `scaled`.
  std::vector<double> mass_local, mass;
  std::vector<char> scaled;
  int scaled_count = 0;
  double added_local = 0, added = 0;  ///< sum of m'_i - m_i and of m_i(s*) - m_i
  double s_star = 1;                  ///< the tightened point on [0, 1]
  bool local_certified = true;        ///< the index at s = 1 certified below 4 (Gershgorin
                                      ///< proves it; false only where rounding defeats it)
  double dt_limit = 0;                ///< exact dt limit with m(s*) (s), at least dt_g
  double cap = 0;                     ///< max_added as given
  bool over_cap = false;              ///< added > cap x free_mass
  /// Over the cap: the largest dt* within it (to `tolerance` relative), and the added mass
  /// certified stable there (at most the cap; the answer at dt_cap adds no more).
  double dt_cap = std::numeric_limits<double>::quiet_NaN();
  double dt_cap_added = std::numeric_limits<double>::quiet_NaN();
  int factorizations = 0;             ///< numeric factorisations (one pattern analysis)
  double added_fraction() const { return free_mass > 0 ? added / free_mass : 0; }
  double added_local_fraction() const { return free_mass > 0 ? added_local / free_mass : 0; }
};

/// m_req_i = max over node i's rows r of sum_s |N_rs| / (4 - 2 dt_g alpha), per free node,
/// N = 2 dt_g C' + dt_g^2 K (all columns, the diagonal too). `4 - 2 dt_g alpha` must be > 0.
std::vector<double> required_masses(const MassScalingProblem& p, double dt_design);

/// SPEC 10's index lambda_max(h^2 A + 2 h C^) with masses m, certified below 4 or not, by one
/// sparse Cholesky factorisation of (4 - 2 h alpha) I - M^-1/2 N(h) M^-1/2 (congruent to
/// 4M - 2hC - h^2 K) with a bound on its rounding. Every call shares one pattern analysis.
class IndexCertifier {
 public:
  /// `max_factor_flops`: FactorisationOverBudget before the first factorisation over it.
  explicit IndexCertifier(const MassScalingProblem& p,
                          double max_factor_flops = std::numeric_limits<double>::infinity());
  ~IndexCertifier();
  IndexCertifier(const IndexCertifier&) = delete;
  IndexCertifier& operator=(const IndexCertifier&) = delete;
  /// True when lambda_max(h^2 A + 2 h C^) < 4 is certified at masses `mass` (per free node).
  bool stable(const std::vector<double>& mass, double h);
  /// The largest h certified stable at `mass` to `relative` (the exact limit lies in
  /// [result, result (1 + relative))): two factorisations around the limit of Lanczos's top
  /// mode at `hint` where they bracket it, else bisection from `hint`; inf where none up to
  /// 2^60 hint is unstable (no stiffness), 0 where none down to 2^-60 hint is stable.
  double dt_limit(const std::vector<double>& mass, double hint, double relative = 1e-5);
  int factorizations() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// SPEC 11 on the problem for the target step dt* (s). InputError where dt*, the safety or
/// the cap is out of range.
MassScalingResult mass_scaling(const MassScalingProblem& p, double dt_target,
                               const MassScalingOptions& options = {});

}  // namespace dampbound
