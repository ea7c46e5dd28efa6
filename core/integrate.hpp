#pragma once
// Integrators: advance (x, v) by dt given the effective damping chosen for this step.
// The paper's semi-implicit Euler (SPEC 2) is the reference.
//
// One entry per integrator (integrator_traits): its name, its step and what the analyses may
// say about it. Code asks these questions instead of comparing integrators by name. A new
// integrator is added in three files: the enum and kIntegrators (params.hpp), its step
// function and entry (integrate.cpp), and its linearised step and closed-form limits
// (core/analysis/linear_stability_modes.cpp, switches the compiler checks); docs/architecture.md.
#include <vector>

#include "core/model.hpp"
#include "core/step.hpp"

namespace dampbound {

struct IntegratorTraits {
  Integrator id;
  const char* name;  ///< what flags, menus and files say
  /// Advances every free node by dt; returns the zero-length springs met in extra force
  /// evaluations. `ws.force` holds F at t, `ws.gamma_eff` the damping held over the step.
  int (*advance)(const Model& model, double dt, State& state, StepWorkspace& ws);
  /// The paper's step: SPEC 7's predicate, the symmetric index at non-uniform damping, the
  /// safe bound (SPEC 9, 10) and the general damping matrix's limits apply.
  bool paper_step;
  /// The velocity update v' = v + a dt from the forces at t (the paper's step and forward
  /// Euler): eq. 6 is derived for it, and the radius over an interval of rates is decided at
  /// the interval's ends.
  bool euler_velocity_update;
  /// The sweep's batched kernel steps it lane by lane, bit-identical to step().
  bool batched_kernel;
  /// Backward Euler: unconditionally stable where K is positive semi-definite; it solves
  /// with K's compression clamped.
  bool implicit;
};

/// The entry of integrator i (every value of Integrator has one).
const IntegratorTraits& integrator_traits(Integrator i);

/// Advances every free node of `state` by params.dt with params.integrator. `ws.force` holds
/// F at the state at t; `ws.gamma_eff` the damping held constant over the step. Returns the
/// number of zero-length springs met in any extra force evaluations.
int advance(const Model& model, const Params& params, State& state, StepWorkspace& ws);

}  // namespace dampbound
