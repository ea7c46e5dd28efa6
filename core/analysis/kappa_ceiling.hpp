#pragma once
// Stiffness ceilings (docs/criteria.md, "Stiffness ceilings"): how stiff springs may be made
// with the step and the damping held. Two answers:
// - the largest factor on a set of springs and anchors (every one, or a region's) that keeps
//   the paper's step stable, by SPEC 10's exact index: with K(s) = K_0 + s K_S and the
//   stiffness-proportional damping beta K(s) following it,
//     index(s) = lambda_max(dt^2 A_0 + 2 dt (C^_0 + s (dt / 2 + beta) A_S)) < 4,
//   which grows with s (A_S positive semi-definite at rest), so the largest stable s is one
//   root, found by damping_limits.hpp's largest_stable_coefficient;
// - the contact ceiling of each node: the largest stiffness k of one extra zero-length spring
//   from node i to a fixed point (a penalty contact; its dashpot kd) that keeps node i's rows
//   of SPEC 10's Q = 4 I - 2 dt C^ - dt^2 A diagonally dominant. The spring adds k / m_i to
//   A's diagonal and (kd + beta k) / m_i to C^'s on node i's rows and nothing elsewhere, so
//   every margin falls by (dt^2 + 2 dt beta) k / m_i + 2 dt kd / m_i, and with node i's
//   smallest margin (2 dt / m_i)(gamma_safe_i - gamma_i) (safe_bound.hpp):
//     k_i = 2 (gamma_safe_i - gamma_i - kd) / (dt + 2 beta),   clipped at 0.
#include <functional>
#include <string>
#include <vector>

#include "core/analysis/damping_limits.hpp"
#include "core/analysis/suggest.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {

/// The springs and anchors a stiffness factor multiplies.
struct StiffnessSelection {
  std::string label;         ///< "all springs and anchors", or the region's label
  std::vector<int> springs;  ///< spring indices
  std::vector<int> anchors;  ///< nodes whose anchor (anchor_scale_i > 0) is scaled
};

/// Every spring and anchor of the spec.
StiffnessSelection whole_selection(const ModelSpec& spec);
/// A region's springs (both ends in it, as the scene file's kappa_scale takes them) and its
/// nodes' anchors.
StiffnessSelection region_selection(const ModelSpec& spec, const SceneRegion& region);
/// The spec with the selection's kappa_scale_ij and anchor_scale_i multiplied by `factor`.
ModelSpec scaled_stiffness(ModelSpec spec, const StiffnessSelection& selection, double factor);

/// One selection's ceiling at the scene's dt and damping, linearised at rest.
struct StiffnessCeiling {
  std::string label;
  int springs = 0, anchors = 0;  ///< what the factor multiplies
  /// The step is stable for every factor in [0, factor) (exclusive; the index at the answer is
  /// certified below 4, to 1e-10 relative); +inf when the selection has no stiffness on a free
  /// node; 0 when the step is unstable even without the selection.
  double factor = 0;
  double index = 0;  ///< SPEC 10's index lambda_max(dt^2 A + 2 dt C^) at factor 1
  /// Runs of the scene with the selection at 0.98 and 1.02 times `factor` (settled rule,
  /// SPEC 8), in the linear regime the ceiling is about: the perturbation and the band's
  /// reference times `run_scale` = min(1, 1e-3 shortest rest length / reference); `ran` false
  /// with no runs (or factor 0 or +inf).
  bool ran = false;
  double run_scale = 1;
  VerifiedRun below, above;
};

/// The ceiling of `selection` for the paper's step at params (zeta resolved: gamma_i held),
/// each factor's damping beta K(s) following the stiffness. `verify` runs the scene at 0.98 and
/// 1.02 times the answer with `rules`. Throws InputError when params.integrator is not the
/// paper's step, std::runtime_error when K is not positive semi-definite at rest (a spring
/// under compression: no factor is stable, SPEC 9). `progress`, when given, is called before
/// each stage (the index bisection, each verifying run) with what runs next; returning false
/// stops the call with SuggestCancelled (the tuner's Cancel). `max_factor_flops`: as
/// general_limits (damping_limits.hpp), FactorisationOverBudget before any factorisation over it.
StiffnessCeiling stiffness_ceiling(const SceneSpec& scene, const Params& params,
                                   const StiffnessSelection& selection, const StopRules& rules,
                                   bool verify,
                                   const std::function<bool(const std::string&)>& progress = {},
                                   double max_factor_flops = kUnboundedFactor);

/// The contact ceiling of every node (mass unit / s^2): the closed form above at positions x,
/// step dt, contact dashpot kd (the scene's uniform kd); NaN at fixed nodes.
struct ContactCeilings {
  std::vector<double> k_max;  ///< per node
  double min = 0, median = 0; ///< over the free nodes
  std::vector<int> worst;     ///< free nodes with the smallest k_max, smallest first
  int zero = 0;               ///< free nodes whose rows are not dominant even without contact
};
ContactCeilings contact_ceilings(const Model& model, const std::vector<Vec3>& x, double dt,
                                 double kd, int worst_count = 5);

}  // namespace dampbound
