#pragma once
// Each spring's share of step()'s spring loop, a batch of springs at a time in SIMD lanes (one
// spring per lane): its direction, its force (SPEC 1) and its tangent block with SPEC 9's row
// sums (SPEC 7, spring_block.hpp). core/physics/detail/spring_pass.cpp then adds them to the nodes in
// spring order, one by one, as before. Every lane does the scalar formulas' operations in their
// order, so each value has the bits the scalar code gives.
//
// Compiled twice: as is (spring_batch.cpp, the portable copy) and for AVX2 under a target
// pragma (spring_batch_avx2.cpp); StepIsa (include/dampbound/physics/step_isa.hpp) picks one at run time.
#include <cstddef>

#include "dampbound/physics/model.hpp"
#include "dampbound/physics/step_isa.hpp"

namespace dampbound::detail {

/// Springs per batch: a multiple of every lane count (4 with AVX2, 8 otherwise), small
/// enough that a batch's results stay in L1 while they are added to the nodes.
inline constexpr std::size_t kSpringBatch = 64;

/// What a batch reads: the model's springs and the positions, as plain arrays (the copies
/// compiled for other targets touch no Eigen or standard-library code).
struct SpringBatchInput {
  const Spring* springs;      ///< model.springs
  const double* kappa;        ///< model.spring_kappa
  const double* weight;       ///< model.spring_weight: w = 1/sqrt(m_i m_j)
  const double* x;            ///< positions, x, y, z of node 0, then node 1, ...
};

/// One batch's results, spring q of the batch in column q. Where `direction` is 0 the spring
/// has zero (or NaN) length and nothing else in its column means anything.
struct SpringBatch {
  alignas(64) double force[3][kSpringBatch];  ///< kappa (l - l0) / l (x_j - x_i), on node i
  alignas(64) double block[6][kSpringBatch];  ///< B's upper triangle {xx, xy, xz, yy, yz, zz}
  alignas(64) double off[3][kSpringBatch];    ///< row r of |B| summed, times w
  unsigned char direction[kSpringBatch];      ///< l > 0
  unsigned char compressed[kSpringBatch];     ///< l < l0 (with `blocks` only)
};

/// Fills `out` for the springs [first, first + count), count <= kSpringBatch: `direction`
/// always, `force` when `forces`, `block`, `off` and `compressed` when `blocks`.
using SpringBatchFunction = void (*)(const SpringBatchInput& in, std::size_t first,
                                     std::size_t count, bool forces, bool blocks,
                                     SpringBatch& out);

namespace spring_batch_generic {
void compute(const SpringBatchInput& in, std::size_t first, std::size_t count, bool forces,
             bool blocks, SpringBatch& out);
}
#if defined(__x86_64__)
namespace spring_batch_avx2 {
void compute(const SpringBatchInput& in, std::size_t first, std::size_t count, bool forces,
             bool blocks, SpringBatch& out);
}
#endif

/// The copy that runs `isa` (`best` resolved by best_step_isa()); the portable one where this
/// CPU lacks `isa`.
SpringBatchFunction spring_batch_for(StepIsa isa);

/// The input for `model` at positions x (x.size() nodes).
SpringBatchInput spring_batch_input(const Model& model, const std::vector<Vec3>& x);

}  // namespace dampbound::detail
