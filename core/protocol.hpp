#pragma once
// The paper's experiment protocol (sec. 3, SPEC 5): perturb, step until restored, diverged,
// or the iteration limit.
#include <functional>

#include "core/step.hpp"

namespace dampbound {

/// When a run stops (SPEC 5). Thresholds are relative to the perturbation's magnitude.
struct StopRules {
  double reference = 5.0;          ///< the perturbation magnitude (cm)
  double restore_fraction = 0.01;  ///< restored when max_i |x_i - X_i| < fraction * reference
  double diverge_factor = 100;     ///< diverged when max_i |x_i - X_i| > factor * reference
  int max_iterations = 1000;       ///< not restored at this iteration
};

inline StopRules default_stop_rules() { return StopRules{}; }

enum class Outcome { running, restored, diverged, not_restored };

const char* to_string(Outcome o);

/// The verdict after one step: diverged (a non-finite coordinate or max displacement above
/// the divergence threshold), restored (below the restore threshold), not_restored at the
/// iteration limit, else running.
Outcome judge(const StopRules& rules, const StepStats& stats);

/// The result of one protocol run.
struct RunResult {
  Outcome outcome = Outcome::running;
  int iterations = 0;              ///< the iteration at which the outcome was reached
  double max_displacement = 0;     ///< max_i |x_i - X_i| at the last iteration (inf if not finite)
  long long violations = 0;        ///< node-steps whose effective gamma was outside the bounds
  long long unstabilisable = 0;    ///< node-steps with gamma_lo > gamma_hi
  long long clamped = 0;           ///< node-steps whose gamma the policy changed
  long long zero_length_springs = 0;
  double time = 0;                 ///< simulated seconds
  long long unguaranteed = 0;        ///< node-steps with gamma_lo > gamma_safe (SPEC 9)
  long long compressed_springs = 0;  ///< spring-steps with l < l0: K may be indefinite (SPEC 9)
};

/// Adds one step's counts to `result` and judges it (no-op on the verdict once latched).
void accumulate(RunResult& result, const StepStats& stats, const StopRules& rules);

using StepObserver = std::function<void(const StepStats&)>;

/// Steps `state` until judge() says anything but running. `on_step` sees every step.
RunResult run_protocol(const Model& model, const Params& params, State& state,
                       const StopRules& rules, int watched, const StepObserver& on_step = {});

}  // namespace dampbound
