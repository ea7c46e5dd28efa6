#pragma once
// The mass-spring model of paper eq. 1 (SPEC 1) in two stages, as MuJoCo's mjSpec and mjModel:
// a ModelSpec is plain topology data (rest positions, per-element scales, springs) read from a
// file or built in code; compile_model() joins it with the user's uniform m, kappa, gamma into
// a Model, complete and never changed afterwards. Every function downstream takes a
// const Model&; a parameter change or a cut compiles a new one.
#include "dampbound/physics/export.hpp"
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "dampbound/physics/params.hpp"

namespace dampbound DAMPBOUND_API {

using Vec3 = Eigen::Vector3d;

/// A spring (i, j) with rest length l0 (cm); its stiffness is kappa * kappa_scale.
struct Spring {
  int i = 0;
  int j = 0;
  double rest_length = 0;  ///< l0_ij >= 0 (cm)
  double kappa_scale = 1;  ///< > 0
  double kd_scale = 1;     ///< >= 0: its dashpot is kd * kd_scale (SPEC 10)
};

/// Topology, rest state and per-element scales: what a scene or mesh file describes. Plain
/// data, edited freely (add_node, add_spring, without_springs); no parameter is in it.
struct ModelSpec {
  std::vector<Vec3> rest;            ///< X_i, rest positions (cm)
  std::vector<double> mass_scale;    ///< m_i = m * mass_scale_i
  std::vector<double> gamma_scale;   ///< user gamma_i = gamma * gamma_scale_i
  std::vector<double> anchor_scale;  ///< anchor kappa_a,i = kappa * anchor_scale_i; 0 = no anchor
  std::vector<Vec3> external_force;  ///< f_i (mass unit cm / s^2)
  std::vector<std::uint8_t> fixed;   ///< 1 = the node never moves
  /// Anchor dashpot kd_a,i = kd * anchor_kd_scale_i at anchored nodes (SPEC 10); empty = all 1.
  std::vector<double> anchor_kd_scale;
  std::vector<Spring> springs;

  int node_count() const { return static_cast<int>(rest.size()); }
  int spring_count() const { return static_cast<int>(springs.size()); }
  int anchor_count() const;
};

class Model;
/// The one way to make a Model: every per-node and per-spring value of SPEC 1 and 3 from the
/// spec's scales and the uniform params.m, params.kappa, params.gamma.
Model compile_model(ModelSpec spec, const Params& params);

/// The model's per-node and per-spring values for other params, in place: the same values as
/// compile_model(model, params), without copying the spec or rebuilding the incidence lists:
/// what the tuner does on a slider's change (its cost: docs/performance.md).
void reparameterise(Model& model, const Params& params);

/// A compiled model: its spec plus the per-node and per-spring values the step reads. Only
/// compile_model() makes one, so no Model is ever without them; pass it as const Model&.
/// The spec is held, not inherited, and read-only: the incidence lists and per-spring values
/// are derived from its springs, so a change of topology goes through compile_model() (or
/// without_springs() and compile_model()). compile_model(model.spec(), params) recompiles it
/// with other parameters; so does reparameterise(), in place.
class Model {
 public:
  /// The topology, rest state and scales it was compiled from.
  const ModelSpec& spec() const { return spec_; }
  /// A Model reads as its spec wherever one is asked for (rest_state(model), ...).
  operator const ModelSpec&() const { return spec_; }

  std::vector<double> mass;          ///< m_i (mass unit)
  std::vector<double> gamma;         ///< the user's gamma_i before the policy (mass unit / s)
  std::vector<double> anchor_kappa;  ///< kappa_a,i (mass unit / s^2)
  std::vector<double> spring_kappa;  ///< kappa_ij of spring k (mass unit / s^2)
  /// 1 / sqrt(m_i m_j) of spring k: the weight of its block in A = M^-1/2 K M^-1/2 (SPEC 9's
  /// row sums read it every step; the masses change only with the params).
  std::vector<double> spring_weight;
  std::vector<double> node_kappa;    ///< kappa_i of eq. 5: max stiffness incident to i (SPEC 3)
  std::vector<double> lower_bound;   ///< gamma_lo_i = 2 sqrt(m_i kappa_i) (eq. 5; mass unit / s)
  // SPEC 10's damping besides the nodal gamma_i (all zero unless params ask for it).
  std::vector<double> spring_kd;     ///< kd_ij of spring k (mass unit / s)
  std::vector<double> anchor_kd;     ///< kd_a,i of node i's anchor; 0 without an anchor
  double rayleigh_mass = 0;          ///< alpha (1/s)
  double rayleigh_stiffness = 0;     ///< beta (s)
  /// Some dashpot or Rayleigh coefficient is non-zero: step() evaluates the damping pass.
  bool spring_damping = false;
  /// The springs at node i, in increasing index: incident[incident_offset[i] ..
  /// incident_offset[i + 1]), k where i is spring k's first node, ~k where it is its second.
  /// What lets a per-node loop add its springs in the serial order (tangent_stiffness()).
  std::vector<int> incident_offset;
  std::vector<int> incident;

 private:
  Model() = default;
  ModelSpec spec_;
  friend Model compile_model(ModelSpec spec, const Params& params);
};

/// Positions and velocities at time t; iteration counts completed steps.
struct State {
  std::vector<Vec3> x;  ///< positions (cm)
  std::vector<Vec3> v;  ///< velocities (cm / s)
  double time = 0;      ///< s
  int iteration = 0;
};

/// Appends a free node at `position` with unit scales and no anchor; returns its index.
int add_node(ModelSpec& spec, const Vec3& position);

/// Appends a spring whose rest length is the current distance of its nodes' rest positions.
void add_spring(ModelSpec& spec, int i, int j, double kappa_scale = 1);

/// The spec without the springs of the given indices (any order, duplicates and out-of-range
/// indices allowed): the topology change of a cut (paper sec. 5).
ModelSpec without_springs(ModelSpec spec, const std::vector<int>& indices);

/// Whether the model's numbers at step dt stay where double precision holds every
/// intermediate of the step and the analysis: each mass, stiffness and damping coefficient in
/// [1e-150, 1e150] (or 0 where 0 is allowed), and each rate they make (kappa/m, gamma/m,
/// kd/m, alpha, beta kappa/m) and its product with dt and dt^2 at most 1e150, so that squares
/// and the sums of a row cannot overflow (1/sqrt(m_i m_j) does at m = 1e-200; (gamma/m)^2 at
/// zeta = 1e300). Nullopt when they do; otherwise one line naming the node or spring, the
/// value, what overflows and the input to change. Only ratios matter (SPEC: units), so a
/// change of units always brings a model inside.
std::optional<std::string> magnitude_problem(const Model& model, double dt);

/// The state at rest: x = X, v = 0, t = 0.
State rest_state(const ModelSpec& spec);

/// |x_i - X_i| (cm).
inline double displacement(const ModelSpec& spec, const State& state, int i) {
  return (state.x[static_cast<size_t>(i)] - spec.rest[static_cast<size_t>(i)]).norm();
}

}  // namespace dampbound
