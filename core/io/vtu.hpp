#pragma once
// ParaView output (docs/meshes.md "ParaView output"): one VTK XML unstructured grid (.vtu) per
// saved step and a .pvd collection of them with their times. Points are the nodes at their
// current positions, cells are the springs (VTK_LINE), then the source mesh's cells when the
// scene has a mesh file. Arrays are base64-encoded binary
// (header_type UInt64), so +inf (an upper bound with v = 0) survives exactly.
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include "dampbound/physics/step.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {

/// The node states as stored in the "state" point array.
/// 0 within, 1 clamped, 2 violating, 3 unstabilisable, 4 fixed (NodeStatus's order).
int state_code(NodeStatus s);

/// Writes one .vtu. Point data: displacement x - X (cm, 3 components), velocity (cm/s, 3),
/// lower = gamma_lo_i (eq. 5), upper = gamma_hi_i (eq. 6; +inf when v_i = 0), effective_damping
/// (mass unit / s), state (Int32, state_code). Cell data per spring: stiffness kappa_ij (mass
/// unit / s^2) and strain (l - l0) / l0 (0 for a spring of rest length 0). Positions are the
/// state's; bounds, damping and states are those `ws` holds: the ones of the step that led to
/// this state (evaluated at the state before it), or for iteration 0 the lower bounds, upper
/// = +inf, the user's gamma and within/fixed. safe = gamma_safe_i of SPEC 9 (mass unit / s;
/// +inf for fixed nodes) at the same state, with the step `dt` (s).
/// `body`: the source mesh's cells (SceneSpec::body), written after the springs in the same
/// piece as VTK_TETRA, VTK_TRIANGLE, VTK_QUAD or VTK_POLYGON cells over the same points, so
/// the per-node arrays colour them; their stiffness and strain are NaN (springs only). Cell
/// array "spring": the spring's index, -1 for a body cell (ParaView: Threshold on it, or
/// Extract Cells By Type, shows either part alone).
/// `extra`: more per-node arrays (Float64, one value a node), written after the others, e.g.
/// SPEC 11's added_mass or suggest --kappa-max's contact_stiffness_max. `params` (optional):
/// the parameters that shaped the run, written as FieldData (one value each: m, kappa, gamma,
/// dt, factor, kd, rayleigh_mass, rayleigh_stiffness) with the policy and integrator in a comment.
using PointArrays = std::vector<std::pair<std::string, std::vector<double>>>;
using PointField = PointArrays::value_type;  ///< one array: (name, one value per node)
void write_vtu(std::ostream& out, const Model& model, const State& state, const StepWorkspace& ws,
               double dt, const std::vector<BodyCell>& body, const PointArrays& extra,
               const Params* params = nullptr);
inline void write_vtu(std::ostream& out, const Model& model, const State& state,
                      const StepWorkspace& ws, double dt, const std::vector<BodyCell>& body = {},
                      const Params* params = nullptr) {
  write_vtu(out, model, state, ws, dt, body, PointArrays{}, params);
}

/// A series in one folder: DIR/step_NNNNNN.vtu (the iteration) and DIR/series.pvd.
class VtuSeries {
 public:
  /// Creates `dir` when missing. Throws InputError naming it when it cannot be written.
  /// `body`: the source mesh's cells, written in every file (write_vtu). The step files an
  /// older DIR/series.pvd lists are removed by write_collection() unless this series wrote
  /// them again: a rerun leaves one consistent series.
  explicit VtuSeries(std::string dir, std::vector<BodyCell> body = {});
  /// The parameters every file then carries (write_vtu's FieldData).
  void set_parameters(const Params& p) { params_ = p, has_params_ = true; }
  /// Writes the state as DIR/step_<iteration>.vtu and remembers its time for the .pvd.
  void add(const Model& model, const State& state, const StepWorkspace& ws, double dt);
  /// Writes DIR/series.pvd listing every file added so far (rewritten on each call).
  void write_collection() const;
  const std::string& dir() const { return dir_; }
  /// The (time in s, file name) pairs written so far.
  const std::vector<std::pair<double, std::string>>& files() const { return files_; }

 private:
  std::string dir_;
  std::vector<BodyCell> body_;
  std::vector<std::pair<double, std::string>> files_;
  std::vector<std::string> older_;  ///< the step files the folder's older series.pvd listed
  Params params_;
  bool has_params_ = false;
};

/// The step file names (step_<digits>.vtu, nothing else) a .pvd's text lists.
std::vector<std::string> pvd_step_files(const std::string& pvd_text);

}  // namespace dampbound
