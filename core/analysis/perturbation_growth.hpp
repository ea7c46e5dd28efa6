#pragma once
// The check by simulation of the exact analysis (linear_stability_exact.hpp): a small random
// perturbation stepped with the real step() of core/, its growth measured. What the tests
// set against every verdict and limit.
#include <vector>

#include "dampbound/physics/model.hpp"
#include "dampbound/physics/params.hpp"

namespace dampbound {

/// The check by simulation: runs the real step() (params.integrator, policy fixed) for
/// `steps` steps from the rest state with every free node moved by a deterministic
/// pseudo-random vector of size up to `amplitude` (cm; small, so the linearisation holds,
/// and in every direction, so every mode is excited), and returns
/// max_i |x_i - X_i| after / before. Decays (< 1) inside the exact limits, grows outside.
double perturbation_growth(const Model& model, const Params& params, int steps,
                           double amplitude = 1e-6, unsigned seed = 12345);

/// The same about an equilibrium `about` (positions where F_i + f_i = 0 at every free node,
/// e.g. a mesh held deformed by its external forces): starts there, moved as above, with
/// v = 0, and returns max_i |x_i - about_i| after / before. What exact_stability(model,
/// about, params) predicts.
double perturbation_growth(const Model& model, const std::vector<Vec3>& about,
                           const Params& params, int steps, double amplitude = 1e-6,
                           unsigned seed = 12345);

}  // namespace dampbound
