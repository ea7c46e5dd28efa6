// The body of the spring batch (spring_batch.hpp): the portable copy as compiled here, and the
// AVX2 copy where spring_batch_avx2.cpp includes this file under a target pragma. Everything
// here has internal linkage except compute(), named after the copy.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <utility>

#define DAMPBOUND_SIMD_REGISTER 1  // one register's width: 2 lanes without AVX
#include "core/physics/detail/simd.hpp"
#include "core/physics/detail/spring_batch.hpp"
#include "core/physics/detail/spring_block.hpp"

#ifndef DAMPBOUND_SPRING_BATCH_VARIANT
#define DAMPBOUND_SPRING_BATCH_VARIANT spring_batch_generic
#endif

namespace dampbound::detail {
namespace {

using simd::kLanes;
using simd::vd;
using simd::vl;

static_assert(kSpringBatch % kLanes == 0, "a batch is whole vectors");

/// |b| along row r of a symmetric block, left to right (spring_block.hpp).
inline vd row_abs(const vd* b, int r) {
  return block_row_abs(b, r, [](vd v) { return simd::abs(v); });
}

using Lanes = std::make_integer_sequence<int, kLanes>;

/// The vector {value(0), value(1), ...}: built in registers, not stored lane by lane and
/// read back (which defeats store forwarding).
template <class Value, int... L>
inline vd gather(std::integer_sequence<int, L...>, const Value& value) {
  return vd{value(L)...};
}

inline void store(double* to, vd v) { std::memcpy(to, &v, sizeof(vd)); }

inline void store_mask(unsigned char* to, vl mask) {
  for (int l = 0; l < kLanes; ++l) to[l] = mask[l] != 0;
}

template <bool Forces, bool Blocks>
void batch(const SpringBatchInput& in, std::size_t first, std::size_t count, SpringBatch& out) {
  for (std::size_t base = 0; base < count; base += kLanes) {
    // Lanes past the batch's last spring repeat it; their columns are never read.
    const double* pi[kLanes];
    const double* pj[kLanes];
    std::size_t k[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      k[l] = first + std::min(base + static_cast<std::size_t>(l), count - 1);
      pi[l] = in.x + 3 * static_cast<std::size_t>(in.springs[k[l]].i);
      pj[l] = in.x + 3 * static_cast<std::size_t>(in.springs[k[l]].j);
    }
    const Lanes lanes{};
    const vd rest = gather(lanes, [&](int l) { return in.springs[k[l]].rest_length; });
    const vd kappa = gather(lanes, [&](int l) { return in.kappa[k[l]]; });
    const vd weight = Blocks ? gather(lanes, [&](int l) { return in.weight[k[l]]; }) : vd{};
    vd xi[3], xj[3];
    for (int c = 0; c < 3; ++c) {
      xi[c] = gather(lanes, [&](int l) { return pi[l][c]; });
      xj[c] = gather(lanes, [&](int l) { return pj[l][c]; });
    }
    vd e[3];
    const vd length = spring_vector(xi, xj, e, simd::Sqrt{});
    store_mask(&out.direction[base], length > 0);
    if constexpr (Forces) {  // SPEC 1: kappa (l - l0) / l * (x_j - x_i)
      const vd scale = kappa * (length - rest) / length;
      for (int c = 0; c < 3; ++c) store(&out.force[c][base], scale * e[c]);
    }
    if constexpr (Blocks) {  // SPEC 7's block and SPEC 9's row sums (spring_pass.cpp)
      vd d[3], ratio, tension;
      spring_direction(e, length, rest, d, ratio, tension);
      vd b[6];
      spring_tangent_block(kappa, tension, ratio, d, b);
      for (int q = 0; q < 6; ++q) store(&out.block[q][base], b[q]);
      for (int r = 0; r < 3; ++r) store(&out.off[r][base], row_abs(b, r) * weight);
      store_mask(&out.compressed[base], tension < 0);
    }
  }
}

}  // namespace

namespace DAMPBOUND_SPRING_BATCH_VARIANT {

void compute(const SpringBatchInput& in, std::size_t first, std::size_t count, bool forces,
             bool blocks, SpringBatch& out) {
  if (count == 0) return;
  if (forces && blocks)
    batch<true, true>(in, first, count, out);
  else if (forces)
    batch<true, false>(in, first, count, out);
  else if (blocks)
    batch<false, true>(in, first, count, out);
  else
    batch<false, false>(in, first, count, out);
}

}  // namespace DAMPBOUND_SPRING_BATCH_VARIANT
}  // namespace dampbound::detail
