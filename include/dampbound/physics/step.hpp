#pragma once
// One step of the simulation: bounds from the state at t, the policy's effective damping,
// then the integrator (paper eqs. 3-4 by default). Every mode (GUI, run, figure, check,
// sweep tests) calls this one function.
#include "dampbound/physics/export.hpp"
#include <vector>

#include "dampbound/physics/bounds.hpp"
#include "dampbound/physics/forces.hpp"
#include "dampbound/physics/model.hpp"

namespace dampbound DAMPBOUND_API {

/// Per-node values of the last step, kept between steps to avoid allocation; the GUI reads
/// `status` to colour nodes.
struct StepWorkspace {
  std::vector<Vec3> force;          ///< F_i at t (internal force, SPEC 1)
  /// D'_i at t: the dashpot and Rayleigh force subtracted from F_i (SPEC 10, damping_forces());
  /// empty when the model has none (Model::spring_damping false).
  std::vector<Vec3> damping;
  std::vector<double> upper_bound;  ///< gamma_hi_i at t (eq. 6)
  std::vector<double> gamma_eff;    ///< effective damping used this step
  std::vector<NodeStatus> status;
  std::vector<double> safe_row_sum;  ///< R_i at t (SPEC 9; 1/s^2), 0 for fixed nodes
  std::vector<double> safe_bound;    ///< gamma_safe_i at t (SPEC 9); +inf for fixed nodes
  std::vector<Vec3> scratch[8];      ///< integrator temporaries
  /// The threads of the per-node loops (1 by default: pass.threads.set_threads(T)) and the
  /// per-spring buffers of the spring loops. Any thread count gives the same bits.
  SpringPass pass;
};

/// What one step reports about the whole model (SPEC 3): its maximum displacement and counts.
struct StepStats {
  int iteration = 0;   ///< steps completed, counting from 1
  double time = 0;     ///< s, after the step
  double max_displacement = 0;      ///< max_i |x_i - X_i| after the step (cm); inf if not finite
  int violating = 0;                ///< free nodes whose effective gamma is outside the bounds
  int unstabilisable = 0;           ///< free nodes with gamma_lo > gamma_hi
  int clamped = 0;                  ///< free nodes whose gamma the policy changed, within bounds
  int zero_length_springs = 0;      ///< springs skipped for having no direction
  bool finite = true;               ///< every coordinate finite after the step
  int unguaranteed = 0;             ///< free nodes with gamma_lo > gamma_safe (SPEC 9)
  int compressed_springs = 0;       ///< springs with l < l0 at t: K may be indefinite (SPEC 9)
};

/// How long step()'s threads poll for their next loop before they sleep (NodeThreads).
inline constexpr int kStepSpinMicroseconds = 500;

/// Advances `state` by params.dt: bounds from the state at t, the policy's effective damping
/// (SPEC 3-4), then params.integrator. Reads the model's m_i, gamma_i and lower_bound; leaves
/// every per-node value of the step in `ws`. Pure apart from `state` and `ws`.
StepStats step(const Model& model, const Params& params, State& state, StepWorkspace& ws);

/// What one node showed in the step just taken (mass units / s; displacement in cm).
struct NodeSample {
  double displacement = 0;  ///< |x_c - X_c| after the step; inf if not finite
  double lower = 0;         ///< gamma_lo
  double upper = 0;         ///< gamma_hi at t (may be +inf)
  double gamma = 0;         ///< the user's gamma
  double gamma_eff = 0;     ///< the effective gamma of the step
  double safe = 0;          ///< gamma_safe at t (SPEC 9)
};

/// Reads node `node`'s values of the step just taken from the model, state and workspace.
NodeSample sample_node(const Model& model, const State& state, const StepWorkspace& ws, int node);

/// One step as a run records it: the whole model's stats and the watched node's values.
struct StepSample : StepStats {
  NodeSample watched;
};

}  // namespace dampbound
