#pragma once
// Scene descriptions (plain data) and their TOML file format (docs/scene-format.md).
// A scene is a topology with per-element scales, default parameters, a perturbation, stop
// rules, the watched node, and optionally cuts, named runs and expectations.
#include "dampbound/physics/export.hpp"
#include <optional>
#include <string>
#include <vector>

#include "dampbound/physics/model.hpp"
#include "dampbound/run/protocol.hpp"

namespace dampbound DAMPBOUND_API {

/// Moves a node away from rest and/or gives it a velocity at t = 0.
struct Perturbation {
  int node = 0;
  Vec3 displacement = Vec3::Zero();  ///< cm
  Vec3 velocity = Vec3::Zero();      ///< cm / s
};

/// A cut at a given iteration: removes every spring whose current position, projected on the
/// xz-plane, crosses the segment from (x0, z0) to (x1, z1) (paper sec. 5, topology change).
struct CutEvent {
  int iteration = 0;  ///< applied after this many steps (0 = before the first step)
  double from[2] = {0, 0};
  double to[2] = {0, 0};
};

/// A named variant of the scene's parameters: what figure overlays and check runs.
struct RunSpec {
  std::string label;
  Params params;
  StopRules rules;
};

/// What `check` asserts about a run's result; unset fields are not checked.
struct Expectation {
  std::string run;  ///< label of a RunSpec; empty = the scene's own parameters
  int line = 0;     ///< line in the scene file, for messages
  /// The verdict rule the run is judged by (SPEC 8); the default rule (settled) when the table
  /// does not say.
  StopRule rule = StopRules{}.rule;
  std::optional<Outcome> outcome;
  std::optional<int> iterations_min, iterations_max;  ///< the outcome's iteration
  std::optional<int> first_entry_min, first_entry_max;  ///< first iteration below the band
  std::optional<bool> left;                           ///< left the band after entering it
  std::optional<int> left_at_min, left_at_max;        ///< the first exit (settled rule)
  std::optional<int> settled_at_min, settled_at_max;  ///< the settled iteration (settled rule)
  std::optional<double> max_displacement_below;  ///< final max displacement < this (cm)
  std::optional<long long> unstabilisable_max;   ///< unstabilisable node-steps <= this
  std::optional<long long> violations_max;       ///< violating node-steps <= this
  std::optional<long long> violations_min;       ///< violating node-steps >= this
  /// SPEC 11: with mass_scale_dt the expectation judges mass scaling for that target step
  /// (the run's parameters, safety 0.9): the keys above judge the run at dt* with the scaled
  /// masses (settled rule), these the answer.
  std::optional<double> mass_scale_dt;
  std::optional<double> added_mass_min, added_mass_max;  ///< tightened, % of the free mass
  std::optional<int> scaled_nodes_min, scaled_nodes_max; ///< nodes given mass
  /// Limits at rest by the exact analysis (no run): dt_limit >= dt_limit_min (s), and the
  /// fewest substeps n with frame_dt / n < dt_limit at most substeps_max.
  std::optional<double> dt_limit_min;
  std::optional<int> substeps_max;
  std::optional<double> frame_dt;  ///< unset: the run's dt
};

/// A generated grid in the xz-plane (SPEC 5): node (a, b) at (a h, 0, b h), index a*nz + b.
struct GridSpec {
  int nx = 0, nz = 0;
  double spacing = 0;
  bool diagonals = true;
  bool anchors = true;
};

/// A cell of the mesh file a scene was built from, kept for output (ParaView draws the body,
/// coloured by the per-node fields): dimension 3 a tetrahedron (positive signed volume),
/// dimension 2 a face of 3 or more corners; corners are node indices.
struct BodyCell {
  int dimension = 2;
  std::vector<int> corners;
};

/// The nodes a [[region]] box or a [[mesh_region]] of the scene file names, kept for the
/// questions asked per region (suggest --kappa-max scales the springs with both ends in it and
/// its nodes' anchors, as the file's kappa_scale and anchor_scale do).
struct SceneRegion {
  std::string label;       ///< "region 1 (line 12)", or the mesh region's name or "tag 3"
  std::vector<int> nodes;  ///< ascending
};

/// A scene: its mesh and everything a run of it needs. A new field must also be copied by
/// scene_as_run() (core/run/session.cpp), which copies every field but the mesh by name.
struct SceneSpec {
  std::string name;
  std::string description;
  std::string path;               ///< file it was loaded from ("" when built in code)
  ModelSpec model;                ///< topology and scales; compile_model() adds parameters
  std::optional<GridSpec> grid;   ///< set when the geometry is a generated grid
  Params params = default_params();
  StopRules rules = default_stop_rules();
  std::vector<Perturbation> perturbations;
  int watched = 0;
  std::vector<CutEvent> cuts;
  std::vector<RunSpec> runs;
  std::vector<Expectation> expectations;
  std::vector<BodyCell> body;     ///< the mesh file's body cells (empty without a [mesh])
  std::vector<SceneRegion> regions;  ///< in file order, [[region]] after [[mesh_region]]
};

/// Builds the grid's nodes, springs (a,b)-(a+1,b), (a,b)-(a,b+1), one diagonal
/// (a,b)-(a+1,b+1) per cell, rest length = initial length, and anchors (SPEC 5). Throws
/// InputError, as a scene file's [grid] does, unless 1 <= nx, nz, nx * nz <= 4 000 000 and
/// the spacing is finite and > 0.
ModelSpec make_grid(const GridSpec& grid);

/// What makes a scene unusable by a Session (no node; a watched or perturbed node, a spring
/// end out of range; a rest position, scale or perturbation that is not finite), naming it;
/// nullopt when usable. The scene files refuse the same; this serves scenes built in code.
std::optional<std::string> validate(const SceneSpec& scene);

/// SPEC 5's scene built in code: an n x n grid (n = 36 is the paper's mesh; the file
/// scenes/paper-plane.toml describes the same scene, which a test checks), node (n/2, n/2)
/// moved 5 cm along y and watched, the default parameters and protocol. The GUI falls back
/// on it when scenes/ is missing; tests build small versions of it. n in 1..2000 (InputError
/// otherwise).
SceneSpec paper_plane_scene(int n = 36);

/// The rest state with the scene's perturbations applied.
State initial_state(const SceneSpec& scene);

/// Turns zeta into gamma for a scene (damping_ratio.hpp's resolve_zeta): its [params] and
/// every [[run]] (they give zeta all or none; InputError naming the file otherwise).
void resolve_zeta(SceneSpec& scene);

/// Indices of springs whose xz-projection at positions x crosses the cut's segment.
std::vector<int> springs_crossing(const ModelSpec& model, const std::vector<Vec3>& x,
                                  const double from[2], const double to[2]);

}  // namespace dampbound
