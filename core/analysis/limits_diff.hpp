#pragma once
// `dampbound diff`: a scene's limits at rest side by side with another's (or with a saved
// baseline), and what changed them (docs/guide.md, "diff"). The limits are the exact dt limit
// at the scene's damping (linear_stability_exact.hpp), the exact gamma range at its dt, SPEC
// 9/10's safe step (the smallest dt_safe_i) and the worst nodes with their causes
// (worst_nodes.hpp). What changed them: nodes and springs are matched by rest position (so a
// renumbered mesh compares node for node), and the changes listed are those at the nodes that
// limit the new scene: the nodes of the index's top eigenvector at the dt limit (the mode that
// becomes unstable first; the paper's step) and the nodes whose dt_safe_i fell most.
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "core/analysis/linear_stability_exact.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {

/// A scene's limits, and the per-node and per-spring data that diff matches: what
/// `diff --save` writes as a baseline (JSON, full precision) and reads back.
struct LimitsSnapshot {
  std::string scene;  ///< name or file
  Params params;      ///< m, kappa, gamma, dt, kd, alpha, beta, integrator (policy fixed)
  std::string method; ///< the exact analysis's method (to_string(ExactMethod))
  double dt_limit = 0;             ///< exact: stable for dt < dt_limit (s); NaN: not computed
  double gamma_lo = 0, gamma_hi = 0;  ///< exact: stable for gamma in [lo, hi) at params.dt
  double dt_safe = 0;              ///< SPEC 9/10: the smallest dt_safe_i (s)
  int dt_safe_node = -1;
  struct Node {
    int node = -1;
    double dt_safe = 0;
    std::string cause;
  };
  std::vector<Node> worst;  ///< the 5 smallest dt_safe_i, with causes (worst_nodes.hpp)
  /// The limiting mode: nodes holding the most of the index's top eigenvector at 0.999 x
  /// dt_limit (sum of their three components squared), largest share first, until 90 % or 8
  /// nodes; empty where the step is not the paper's or the limit is not finite.
  std::vector<int> mode_nodes;
  std::vector<double> mode_share;
  // Per node and per spring, for matching.
  std::vector<Vec3> rest;
  std::vector<double> mass, anchor, node_dt_safe;  ///< m_i, kappa_a,i, dt_safe_i
  std::vector<std::uint8_t> fixed;
  std::vector<int> spring_i, spring_j;
  std::vector<double> spring_kappa, spring_rest_length;
};

/// The limits of the scene at params (zeta resolved; policy fixed), linearised at rest.
LimitsSnapshot limits_snapshot(const SceneSpec& scene, const Params& params,
                               const ExactOptions& options = {});

/// JSON with every number at full precision (format "dampbound-limits", version 1).
void write_limits_json(std::ostream& out, const LimitsSnapshot& s);
/// Reads what write_limits_json wrote; InputError naming `path` for anything else.
LimitsSnapshot read_limits_json(const std::string& text, const std::string& path);

/// The fewest substeps n with frame_dt / n < dt_limit (1 when the limit is infinite; 0 when it
/// is not a positive number).
int limit_substeps(double frame_dt, double dt_limit);

/// One change at or near the nodes that limit the new scene, in words.
struct LimitChange {
  std::string what;  ///< e.g. "spring 12-13 (new node numbers): kappa x4 (0.001 -> 0.004)"
  double weight = 0; ///< how much of the new limiting mode sits at its nodes (0..1)
};

struct LimitsDiff {
  int matched_nodes = 0, new_nodes = 0, removed_nodes = 0;
  bool renumbered = false;  ///< some matched node has another index
  std::vector<std::string> parameters;  ///< parameter changes, e.g. "dt 0.05 -> 0.1"
  std::vector<LimitChange> changes;     ///< at the new limiting nodes, most weight first
  /// Matched nodes whose dt_safe_i fell most (new / old < 0.99), with the new index.
  struct Fall {
    int node = -1;
    double old_dt = 0, new_dt = 0;
  };
  std::vector<Fall> falls;
  double drop = 0;  ///< 1 - new dt_limit / old dt_limit (> 0: the limit fell)
  /// Over the whole scene: matched nodes with another mass, anchor or fixed flag, and springs
  /// new, removed or with another stiffness or rest length (new nodes: new_nodes).
  int changed_nodes = 0, changed_springs = 0;
};

/// Compares two snapshots (nodes matched by rest position within 1e-9 of the scene's size).
LimitsDiff diff_limits(const LimitsSnapshot& old_limits, const LimitsSnapshot& new_limits);

}  // namespace dampbound
