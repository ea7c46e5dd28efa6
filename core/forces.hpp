#pragma once
// The internal force F_i of paper eq. 6 (SPEC 1): spring and anchor forces only, no damping,
// no external force.
#include <vector>

#include "core/model.hpp"

namespace dampbound {

/// F_i = sum_j kappa_ij (l_ij - l0_ij) d_ij  -  kappa_a,i (x_i - X_i),  d_ij = (x_j - x_i)/l_ij
/// (paper eq. 1, SPEC 1). `force` is resized to the node count. A spring of zero current
/// length has no direction and contributes nothing; the return value counts such springs.
int internal_forces(const Model& model, const std::vector<Vec3>& x, std::vector<Vec3>& force);

}  // namespace dampbound
