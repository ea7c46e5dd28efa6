#pragma once
// The exact limits of SPEC 10 in a few factorisations: the largest x at which
// 4 I - S(x) is proved positive definite, for an index matrix S(x) that is positive
// semi-definite, increasing and convex in x (the paper's step is stable iff
// lambda_max(dt^2 A + 2 dt C^) < 4, SPEC 10): a damping coefficient's limit (S linear in it)
// and the dt limit (S quadratic in dt).
//
// Definiteness is what the criterion needs, and a factorisation decides it: one pattern
// analysis for the whole search (every S(x) has one pattern), then each probe is one numeric
// factorisation of sigma I - S(x), sigma just below 4, whose rounding bound
// (cholesky_rounding.hpp) must prove lambda_max(S(x)) < 4. Between probes the factor of the
// last stable point a places the next one: with B = sigma I - S(a) and
// S(a + t) = S(a) + t D + t^2 Q, B - t D - t^2 Q is singular first at the root t*, and for
// any vector u the positive root t_u of u^T (B - t D - t^2 Q) u is >= t* (each such quadratic
// decreases in t), with equality for the null vector. Lanczos on B^-1 (D + t Q), self-adjoint
// in B's inner product, gives that vector (t updated from t_u until it settles: one run when
// Q = 0), so a + t_u is the root from above to the Lanczos run's accuracy, and the next probe
// is placed just below it. docs/criteria.md ("The general damping matrix") has the argument.
#include <functional>
#include <limits>
#include <memory>

#include "dampbound/physics/stiffness.hpp"

namespace dampbound::detail {

/// S(x) and D(x) = S'(x) at any x >= 0, with S(a + t) = S(a) + t D(a) + t^2 Q for every a, t
/// (Q = S'' / 2 constant; empty, 0 x 0, where S is linear). Every S(x) has the same pattern;
/// D(x) and Q positive semi-definite for x >= 0.
struct IndexFamily {
  std::function<SparseMatrix(double)> S, D;
  SparseMatrix Q;
  /// Where the first Lanczos run starts (empty: Lanczos's usual start): the top eigenvector
  /// of an index matrix nearby, for example.
  Eigen::VectorXd start;
};

/// Where the search ended: `stable` proved (a successful factorisation of sigma I - S, sigma
/// + its rounding bound < 4), `unstable` not provable so, unstable - stable <= 1e-10 unstable
/// (as the eigenvalue bisection it replaces: its interval). `stable` = 0 when x = `from` = 0
/// is not proved stable; both +inf when S never reaches 4 (D + t Q has no direction that
/// grows).
struct DefiniteRoot {
  double stable = 0, unstable = 0;
  int factorizations = 0;  ///< numeric factorisations, one pattern analysis
  int solves = 0;          ///< solves with a factor
};

class ShiftedCholesky;

/// From x = `from` (> 0: halved until proved stable, at most 200 times; 0: that point alone).
/// `factors`, when given, holds the factorisations between searches: a second search on the
/// same pattern (the dt limit after the gamma limit) keeps the first one's pattern analysis.
/// `max_factor_flops`: throws FactorisationOverBudget (linear_stability_cholesky.hpp) when
/// the pattern analysis predicts one factorisation over it, before any is done.
DefiniteRoot definite_root(const IndexFamily& family, double from,
                           std::unique_ptr<ShiftedCholesky>* factors = nullptr,
                           double max_factor_flops = std::numeric_limits<double>::infinity());

}  // namespace dampbound::detail
