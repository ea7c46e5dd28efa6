#pragma once
// Writing scenes back as TOML (the format of core/io/scene_file.cpp, docs/scene-format.md), and
// turning measured runs into [[expect]] entries: how the tuner's "Save as scene" makes a check
// that `dampbound check FILE` replays headless.
#include <iosfwd>
#include <string>
#include <vector>

#include "dampbound/run/protocol.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {

/// How loose the [[expect]] entries written for a measured run are.
struct ExpectTolerance {
  /// Each asserted iteration (the outcome's, the first entry, the exit, the settled one) must
  /// lie within +- max(iterations, ceil(iteration_fraction x the measured one)) of it: a
  /// decaying oscillation's crossing of the threshold moves by a few iterations under another
  /// compiler's rounding (FMA contraction moved one from 110 to 114).
  int iterations = 2;
  double iteration_fraction = 0.05;
  /// max_displacement_below = this x the measured final max displacement (cm), for runs that
  /// did not diverge; <= 1 (the default) leaves it out. The outcome already bounds the final
  /// displacement by the thresholds; a settled run's last displacement is rounding noise
  /// (1e-14 cm), which any other rounding changes by more than a factor.
  double displacement_factor = 1;
  /// Also assert violating and unstabilisable node-steps <= the measured counts.
  bool counts = false;
};

/// The default tolerances.
inline ExpectTolerance default_expect_tolerance() {
  return {};
}

/// The [[expect]] entry for `result`, measured under `rule` on the run labelled `run` ("" =
/// the scene's own [params]): the rule, the outcome, the outcome's iteration when it is not
/// the limit (restored, diverged), and under the settled rule (SPEC 8) the first entry, whether
/// and when the run left the band, and the settled iteration, each within the tolerance; then
/// what the tolerance adds.
Expectation expectation_for(const RunResult& result, const std::string& run,
                            const ExpectTolerance& tolerance,
                            StopRule rule = StopRule::first_entry);

/// Writes `scene` as TOML that load_scene() reads back to the same model, parameters,
/// perturbations, protocol, cuts, runs and expectations. The geometry is a [grid] when the
/// model is the plain grid; else the source file's geometry tables (grid, node, spring,
/// region, mesh) when they still compile to this model, with a mesh path made relative to
/// `dest_path`; else every node and spring written out. `header` lines become comments.
void write_scene_toml(std::ostream& out, const SceneSpec& scene, const std::string& dest_path,
                      const std::vector<std::string>& header = {});

/// write_scene_toml into a string.
std::string scene_toml(const SceneSpec& scene, const std::string& dest_path,
                       const std::vector<std::string>& header = {});

/// True when two models have the same nodes (rest, scales, forces, fixed) and springs
/// (ends, rest length, stiffness scale), compared exactly.
bool same_topology(const ModelSpec& a, const ModelSpec& b);

}  // namespace dampbound
