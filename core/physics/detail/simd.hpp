#pragma once
// Lane vectors: one double per lane, kLanes side by side. The batched sweep kernel
// (core/sweep/detail/kernel_body.cpp) puts one trial in each lane, step()'s spring loop
// (core/physics/detail/spring_batch.cpp) one spring. GCC/Clang vector extensions give + - * / and
// comparisons lane by lane with IEEE rounding, exactly like scalar code; sqrt goes through the
// matching SIMD instruction (also correctly rounded). A vector is one register wide where
// there is AVX (8 lanes in a zmm register with AVX-512, 4 in a ymm register with AVX2: a
// wider vector would be split into halves that selects and by-value passing send through
// memory); without AVX it is 8 lanes split into xmm operations. Lanes are independent, so the
// lane count changes the speed, never a lane's bits.
//
// The instruction set comes from the compiler flags (__AVX512F__, __AVX__) or, in the per-ISA
// copies built under a target pragma, from DAMPBOUND_SIMD_AVX512 / DAMPBOUND_SIMD_AVX2 (a
// target pragma does not define the macros under clang). Everything here has internal
// linkage, so the copies compiled for different targets never meet at link time.
#include <cmath>
#include <cstdint>
#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

// Without AVX-512 (DAMPBOUND_NATIVE=OFF) GCC warns that passing these 64-byte vectors
// by value has another ABI than with it. They never cross a translation unit (only the
// kernel's and the spring batch's bodies include this header), so the warning does not apply.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace dampbound::simd {
namespace {

#if !(defined(__AVX512F__) || defined(DAMPBOUND_SIMD_AVX512)) && \
    (defined(__AVX__) || defined(DAMPBOUND_SIMD_AVX2))
#define DAMPBOUND_SIMD_YMM 1
/// Trials per vector: 4 doubles = 32 bytes = one AVX2 register.
constexpr int kLanes = 4;
#elif !(defined(__AVX512F__) || defined(DAMPBOUND_SIMD_AVX512)) && defined(DAMPBOUND_SIMD_REGISTER)
/// Lanes per vector: 2 doubles = 16 bytes = one SSE2 (or NEON) register, for a user that asks
/// for one register's width everywhere (DAMPBOUND_SIMD_REGISTER: the spring batch, whose
/// lanes are gathered one by one).
constexpr int kLanes = 2;
#else
/// Lanes per vector: 8 doubles = 64 bytes = one AVX-512 register.
constexpr int kLanes = 8;
#endif
constexpr int kBytes = kLanes * static_cast<int>(sizeof(double));

// The alignment is explicit: GCC otherwise derives a vector type's alignment from the target
// in force where the type is used, so a std::vector<NodeBlock> instantiated after the target
// pragma of core/sweep/detail/kernel_avx512.cpp ends would allocate 16-byte aligned blocks
// that the kernel's AVX-512 code reads with aligned loads.
typedef double vd __attribute__((vector_size(kBytes), aligned(kBytes)));
typedef std::int64_t vl __attribute__((vector_size(kBytes), aligned(kBytes)));
static_assert(alignof(vd) == kBytes && alignof(vl) == kBytes, "one register per vector");

/// Every lane = x (keeps the sign of a zero, unlike `vd{} + x`).
inline vd splat(double x) {
  vd r;
  for (int l = 0; l < kLanes; ++l) r[l] = x;
  return r;
}

inline vl splat_int(std::int64_t x) {
  vl r;
  for (int l = 0; l < kLanes; ++l) r[l] = x;
  return r;
}

/// Correctly rounded square root of every lane (IEEE 754, same as std::sqrt).
inline vd sqrt(vd x) {
#if defined(__AVX512F__) || defined(DAMPBOUND_SIMD_AVX512)
  // The masked form with every lane selected: GCC 12's _mm512_sqrt_pd reads an undefined
  // register and trips -Wmaybe-uninitialized.
  const __m512d v = reinterpret_cast<__m512d>(x);
  return reinterpret_cast<vd>(_mm512_mask_sqrt_pd(v, static_cast<__mmask8>(0xFF), v));
#elif defined(DAMPBOUND_SIMD_YMM)
  return reinterpret_cast<vd>(_mm256_sqrt_pd(reinterpret_cast<__m256d>(x)));
#else
  vd r;
  for (int l = 0; l < kLanes; ++l) r[l] = std::sqrt(x[l]);
  return r;
#endif
}

/// simd::sqrt as a function object (spring_geometry's `root` for lane vectors).
struct Sqrt {
  vd operator()(vd x) const { return sqrt(x); }
};

/// |x| lane by lane (clears the sign bit, as std::abs does).
inline vd abs(vd x) { return (vd)((vl)x & splat_int(INT64_MAX)); }

/// Lane-wise `mask ? a : b` (mask lanes are all ones or zero, as comparisons give).
inline vd select(vl mask, vd a, vd b) {
  return mask ? a : b;
}

}  // namespace
}  // namespace dampbound::simd
