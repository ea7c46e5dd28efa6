#pragma once
// What the hunter checks on one scene and on one sweep. Each check is one guarantee that
// dampbound prints (a verdict, a limit, a safe bound, a substep count, a sweep row), set
// against the dense reference or against runs; a failed one is a contradiction.
#include <cstdint>
#include <string>
#include <vector>

#include "hunter_cases.hpp"

namespace dampbound::hunt {

struct Tally {
  long scenes = 0, sweeps = 0, checks = 0, contradictions = 0;
  bool verbose = false;
  std::vector<std::string> found;
  void expect(bool ok, const std::string& where, const std::string& what) {
    ++checks;
    if (ok) return;
    ++contradictions;
    found.push_back(where + ": " + what);
  }
};

/// Every guarantee about one scene: the exact verdict, dt limit and gamma interval at 0.98x
/// and 1.02x (dense radius, and runs of step() with a small perturbation of every node), the
/// safe bound never above the exact limits and stable at its own values, suggest's damping
/// range, safe gamma and dt, and the substep counts.
void hunt_scene(const Case& c, Tally& tally);

/// A small sweep of the paper's plane (random policy, damping axes and rule): its rows under
/// the batched kernel with similarity classes against every trial run alone through a
/// Session with the classes off.
void hunt_sweep(std::uint64_t seed, Tally& tally);

}  // namespace dampbound::hunt
