#pragma once
// SPEC 9's bound node by node, for files and lists (VTU point arrays, bounds --worst).
#include <vector>

#include "dampbound/physics/model.hpp"

namespace dampbound {

/// Per node at positions x: dt_safe_i at the user's gamma_i and gamma_safe_i at step dt
/// (SPEC 9); 0 at fixed nodes.
void safe_bounds_per_node(const Model& model, const std::vector<Vec3>& x, double dt,
                          std::vector<double>& dt_safe, std::vector<double>& gamma_safe);

}  // namespace dampbound
