#pragma once
// The mass-spring model of paper eq. 1 (SPEC 1): nodes, springs, zero-rest-length anchors.
// Topology and per-element scales are fixed by the scene; set_params() turns the user's
// uniform m, kappa, gamma into the per-node and per-spring values the step uses.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "core/params.hpp"

namespace dampbound {

using Vec3 = Eigen::Vector3d;

/// A spring (i, j) with rest length l0 (cm); its stiffness is kappa * kappa_scale.
struct Spring {
  int i = 0;
  int j = 0;
  double rest_length = 0;  ///< l0_ij >= 0 (cm)
  double kappa_scale = 1;  ///< > 0
  double kappa = 0;        ///< kappa_ij, filled by set_params (mass unit / s^2)
};

/// Topology, rest state and derived per-node values. Plain data: no GL, no I/O.
struct Model {
  // --- fixed by the scene ---
  std::vector<Vec3> rest;            ///< X_i, rest positions (cm)
  std::vector<double> mass_scale;    ///< m_i = m * mass_scale_i
  std::vector<double> gamma_scale;   ///< user gamma_i = gamma * gamma_scale_i
  std::vector<double> anchor_scale;  ///< anchor kappa_a,i = kappa * anchor_scale_i; 0 = no anchor
  std::vector<Vec3> external_force;  ///< f_i (mass unit cm / s^2)
  std::vector<std::uint8_t> fixed;   ///< 1 = the node never moves
  std::vector<Spring> springs;

  // --- derived by set_params ---
  std::vector<double> mass;          ///< m_i
  std::vector<double> gamma;         ///< the user's gamma_i (before the policy)
  std::vector<double> anchor_kappa;  ///< kappa_a,i
  std::vector<double> node_kappa;    ///< kappa_i of eq. 5: max stiffness incident to i (SPEC 3)
  std::vector<double> lower_bound;   ///< gamma_lo_i = 2 sqrt(m_i kappa_i) (eq. 5)

  int node_count() const { return static_cast<int>(rest.size()); }
  int spring_count() const { return static_cast<int>(springs.size()); }
  int anchor_count() const;
};

/// Positions and velocities at time t; iteration counts completed steps.
struct State {
  std::vector<Vec3> x;  ///< positions (cm)
  std::vector<Vec3> v;  ///< velocities (cm / s)
  double time = 0;      ///< s
  int iteration = 0;
};

/// Appends a free node at `position` with unit scales and no anchor; returns its index.
int add_node(Model& model, const Vec3& position);

/// Appends a spring whose rest length is the current distance of its nodes' rest positions.
void add_spring(Model& model, int i, int j, double kappa_scale = 1);

/// Fills mass, gamma, spring and anchor stiffness, node_kappa and lower_bound from `params`.
/// Call after any change of m, kappa or gamma, or of the topology.
void set_params(Model& model, const Params& params);

/// Removes the springs with the given indices (any order, duplicates allowed) and refreshes
/// node_kappa and lower_bound: the topology change of a cut (paper sec. 5).
void remove_springs(Model& model, std::vector<int> indices, const Params& params);

/// The state at rest: x = X, v = 0, t = 0.
State rest_state(const Model& model);

/// |x_i - X_i| (cm).
inline double displacement(const Model& model, const State& state, int i) {
  return (state.x[static_cast<size_t>(i)] - model.rest[static_cast<size_t>(i)]).norm();
}

}  // namespace dampbound
