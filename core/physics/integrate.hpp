#pragma once
// Integrators: advance (x, v) by dt given the effective damping chosen for this step.
// The paper's semi-implicit Euler (SPEC 2) is the reference.
//
// An integrator's name and traits are its row of kIntegratorTable (params.hpp); its step is
// here, chosen by a switch the compiler checks (docs/architecture.md, "A new integrator").
#include "dampbound/physics/model.hpp"

namespace dampbound {

struct State;
struct StepWorkspace;

/// Advances every free node of `state` by params.dt with params.integrator. `ws.force` holds
/// F at the state at t; `ws.gamma_eff` the damping held constant over the step. Returns the
/// number of zero-length springs met in any extra force evaluations.
int advance(const Model& model, const Params& params, State& state, StepWorkspace& ws);

}  // namespace dampbound
