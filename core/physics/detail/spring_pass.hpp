#pragma once
// The springs' share of a step in one pass: the internal forces (SPEC 1, forces.hpp) and
// SPEC 9's Gershgorin row sums (safe_bound.hpp) at the same positions, each spring's
// direction and length found once. internal_forces() and safe_row_sums() are this pass with
// one output; step() asks for both. Every node's sums are added in spring order (after its
// anchor term), on threads too (each owns a range of nodes), so the bits are the same whether
// the two are computed together or apart, on any number of threads.
#include <vector>

#include "dampbound/physics/forces.hpp"
#include "dampbound/physics/model.hpp"

namespace dampbound::detail {

/// What the pass counts.
struct SpringCounts {
  int zero_length = 0;  ///< springs of zero (or NaN) length: no direction, no force (SPEC 1)
  int compressed = 0;   ///< springs with 0 < l < l0 (counted when row sums are asked for)
};

/// F_i into *force (resized to the node count) when force is not null, and R_i into *row_sum
/// (0 at fixed nodes) when row_sum is not null, at positions x. `pass` (optional) brings the
/// threads, the copy of the spring batch to run (spring_batch.hpp) and the row sums' buffers.
SpringCounts spring_pass(const Model& model, const std::vector<Vec3>& x,
                         std::vector<Vec3>* force, std::vector<double>* row_sum,
                         SpringPass* pass = nullptr);

}  // namespace dampbound::detail
