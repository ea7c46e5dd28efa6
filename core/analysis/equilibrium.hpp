#pragma once
// The static equilibrium of a model: positions where every free node's internal force
// balances its external force, F_i(x) + f_i = 0 (SPEC 1). A scene with external forces, or
// with springs whose rest lengths differ from its rest geometry, is not in equilibrium at
// rest: a damped run leaves X and settles where this is, and the linear analysis (SPEC 7, 9)
// of such a mesh belongs there, not at X.
#include <limits>
#include <string>
#include <vector>

#include "core/analysis/linear_stability_cholesky.hpp"  // FactorisationOverBudget
#include "dampbound/physics/model.hpp"

namespace dampbound {

/// The largest net force max_i |F_i(x) + f_i| over the free nodes (0 at an equilibrium), the
/// node where it is (-1 when no node is free), and the force scale it is judged against: the
/// largest single term of the balance (an external force, one spring's kappa |l - l0|, one
/// anchor's kappa_a |x - X|).
struct NetForce {
  double largest = 0;
  int node = -1;
  double scale = 0;
  /// largest <= tolerance * scale: x balances to rounding (every force 0 counts too).
  bool balanced(double tolerance = 1e-10) const { return largest <= tolerance * scale; }
};
NetForce net_force(const Model& model, const std::vector<Vec3>& x);

/// "the rest state is not an equilibrium: a net force of 0.0005 at node 1 (largest force term
/// 0.0005)", for `net` at rest: the one wording of bounds', suggest's and the tuner's note.
std::string rest_not_in_equilibrium(const NetForce& net);

struct EquilibriumOptions {
  int max_iterations = 200;  ///< quadratic near a minimum: 5 to 10 on smooth loads
  double tolerance = 1e-10;  ///< NetForce::balanced's
  /// The most one sparse factorisation may take (CHOLMOD's prediction, as
  /// ExactOptions::max_factor_flops): over it FactorisationOverBudget is thrown.
  double max_factor_flops = std::numeric_limits<double>::infinity();
};

struct Equilibrium {
  std::vector<Vec3> x;  ///< positions (fixed nodes at X)
  NetForce net;         ///< at x
  int iterations = 0;   ///< Newton steps taken
  bool converged = false;
};

/// Newton's method from the rest state X on the potential energy (springs, anchors, less
/// the external forces' work), whose minima are the equilibria a damped run settles at: each
/// step solves (K(x) + sigma I) d = F(x) + f with the tangent stiffness K
/// (linear_stability.hpp), sigma = 0 where K is positive definite and the smallest of 1e-6,
/// 1e-5, ... of its largest diagonal entry that makes it so elsewhere (a slack chain at
/// rest, an indefinite K), by CHOLMOD's Cholesky; the step is halved until the energy falls
/// (Armijo) or, near the end, the net force does. Where a load has several minima (a
/// pre-stretched sheet that wrinkles) it finds one, and a run may settle at another.
Equilibrium static_equilibrium(const Model& model, const EquilibriumOptions& options = {});

/// Why `e` is not an equilibrium to analyse at, "" when it is (converged): "no static
/// equilibrium found in 200 Newton steps (net force ... at node ..., largest force term ...)".
/// The one wording of `bounds --equilibrium` and the tuner.
std::string no_equilibrium(const Equilibrium& e);

/// "6 Newton steps, net force 2.4e-15 against a largest force term of 0.0005": how `e` was
/// reached (bounds' state line, the tuner's).
std::string equilibrium_summary(const Equilibrium& e);

/// Why Newton's method could not run: a factorisation over the budget (`over`'s words).
std::string equilibrium_over_budget(const FactorisationOverBudget& over);

}  // namespace dampbound
