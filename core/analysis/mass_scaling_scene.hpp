#pragma once
// SPEC 11 on a scene: its model at rest as mass_scaling()'s problem, the answer in the
// scene's nodes (the nodes with the most added mass and why, in --worst's words), the report's
// other figures (the lowest frequency, the lower bounds of eq. 5), the check by running (the
// settled rule at dt* with the scaled masses) and the scene with those masses. What
// `dampbound suggest --mass-scale`, Python's mass_scaling and the tuner's Suggest tab share.
#include <limits>
#include <string>
#include <vector>

#include "core/analysis/mass_scaling.hpp"
#include "core/analysis/suggest.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {

/// The model's problem at rest: K, C' = C - alpha M with the nodal gamma_i (the user's,
/// before any policy), the free nodes' masses and alpha.
MassScalingProblem mass_scaling_problem(const Model& model);

/// One node of the report.
struct ScaledNode {
  int node = -1;
  double before = 0, after = 0;  ///< m_i and m_i(s*) (mass unit)
  double factor = 1;             ///< after / before
  std::string cause;             ///< what makes the node limit the step (worst_nodes' words)
};

struct SceneMassScalingOptions : MassScalingOptions {
  bool verify = true;  ///< run the scaled scene at dt* (settled rule)
  int top = 20;        ///< nodes listed
};

struct SceneMassScaling {
  MassScalingResult result;
  Params params;                     ///< the scene's, policy fixed, dt = dt*
  /// Per node (every node; fixed nodes keep theirs): the masses as given, the answer's and
  /// the mass scales that give the answer (m_i = params.m x scale_i exactly, each at least
  /// m_i(s*): rounded up by an ulp where the quotient does not give it back).
  std::vector<double> mass_before, mass_after, mass_scale;
  std::vector<ScaledNode> top;       ///< most added mass first
  /// The lowest frequency sqrt(lambda_min(M^-1 K)) before and after (1/s; NaN where
  /// lambda_min <= 0: a zero mode) and its change in percent.
  double frequency_before = std::numeric_limits<double>::quiet_NaN();
  double frequency_after = std::numeric_limits<double>::quiet_NaN();
  double frequency_change = std::numeric_limits<double>::quiet_NaN();
  /// The largest change of a node's lower bound 2 sqrt(m_i kappa_i) (eq. 5), in percent, and
  /// its node (-1: none changed).
  double lower_bound_change = 0;
  int lower_bound_node = -1;
  bool ran = false;
  VerifiedRun run;                   ///< at dt* with the answer's masses
  /// The scene with the answer's masses (mass_scale), zeta resolved into gamma_scale, at dt*
  /// with the fixed policy, its iteration limit covering the scene's simulated time as the
  /// substeps' runs do (verify_iterations); its [[run]]s and [[expect]]s dropped (they were
  /// measured with the masses as given). What --write-scene writes and the run ran.
  SceneSpec scene;
};

/// SPEC 11 on the scene with params (zeta resolved, any policy judged as fixed) for dt*.
SceneMassScaling scene_mass_scaling(const SceneSpec& scene, const Params& params,
                                    const StopRules& rules, double dt_target,
                                    const SceneMassScalingOptions& options = {});

}  // namespace dampbound
