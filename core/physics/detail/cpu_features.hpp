#pragma once
// What the per-instruction-set copies of the library's loops need of the CPU, asked at run time
// (__builtin_cpu_supports also checks that the OS saves the wider registers: XCR0). One list per
// target pragma: core/physics/detail/spring_batch_avx2.cpp and core/sweep/detail/kernel_avx2.cpp use
// x86-64-v3's, core/sweep/detail/kernel_avx512.cpp x86-64-v4's.

namespace dampbound::detail {

/// AVX2, AVX, FMA, BMI1/2 and POPCNT: the features of the AVX2 copies' target pragma.
inline bool cpu_has_avx2_set() {
#if defined(__x86_64__)
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("avx") &&
         __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi") &&
         __builtin_cpu_supports("bmi2") && __builtin_cpu_supports("popcnt");
#else
  return false;
#endif
}

/// The AVX2 set plus AVX-512 F, CD, DQ, BW and VL.
inline bool cpu_has_avx512_set() {
#if defined(__x86_64__)
  return cpu_has_avx2_set() && __builtin_cpu_supports("avx512f") &&
         __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512dq") &&
         __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl");
#else
  return false;
#endif
}

}  // namespace dampbound::detail
