#pragma once
// The nodes that limit the time step and the damping: the smallest dt_safe_i and gamma_safe_i
// of SPEC 9, each with what makes it small, in words.
#include <string>
#include <vector>

#include "core/physics/safe_bound_nodes.hpp"
#include "dampbound/physics/model.hpp"

namespace dampbound {

/// One node and the local facts that set its safe bound.
struct WorstNode {
  int node = -1;
  double dt_safe = 0;       ///< SPEC 9 at the user's gamma_i (s)
  double gamma_safe = 0;    ///< SPEC 9 at dt (mass unit / s)
  double mass = 0;          ///< m_i
  double stiffest = 0;      ///< the largest stiffness of its springs and anchor
  double shortest_edge = 0; ///< its shortest incident spring at rest (cm; inf when none)
  int degree = 0;           ///< incident springs
  std::string cause;        ///< e.g. "edge 12x shorter than the median"
};

struct WorstNodes {
  std::vector<WorstNode> by_dt;     ///< smallest dt_safe_i first
  std::vector<WorstNode> by_gamma;  ///< smallest gamma_safe_i first
  double median_mass = 0, median_kappa = 0, median_edge = 0;  ///< over free nodes / springs
};

/// The `count` free nodes with the smallest dt_safe_i and with the smallest gamma_safe_i at
/// positions x and step dt.
WorstNodes worst_nodes(const Model& model, const std::vector<Vec3>& x, double dt, int count);

/// The given free nodes described as worst_nodes() describes its own (the same medians and
/// causes): what mass scaling (SPEC 11) reports for the nodes it adds the most mass to.
std::vector<WorstNode> describe_nodes(const Model& model, const std::vector<Vec3>& x, double dt,
                                      const std::vector<int>& nodes);

}  // namespace dampbound
