#pragma once
// Small scenes shared by the core and ui tests.
#include "dampbound/physics/model.hpp"

namespace dampbound::test {

/// Twelve nodes 0.5 cm apart between fixed ends, each free node pulled down by `load`: slack
/// at rest (no sideways stiffness) and not in equilibrium there (docs/criteria.md's chain).
inline ModelSpec loaded_chain(double load = 0.0005) {
  ModelSpec s;
  for (int i = 0; i < 12; ++i) {
    add_node(s, Vec3(0.5 * i, 0, 0));
    if (i > 0) add_spring(s, i - 1, i);
  }
  s.fixed[0] = s.fixed[11] = 1;
  for (int i = 1; i < 11; ++i) s.external_force[static_cast<size_t>(i)] = Vec3(0, -load, 0);
  return s;
}

}  // namespace dampbound::test
