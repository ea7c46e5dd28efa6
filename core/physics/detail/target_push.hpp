// What the per-instruction-set copies compile under (core/physics/detail/spring_batch_avx2.cpp,
// core/sweep/detail/kernel_avx2.cpp, kernel_avx512.cpp): the target of DAMPBOUND_SIMD_AVX2
// (x86-64-v3: AVX2, FMA, BMI1/2) or DAMPBOUND_SIMD_AVX512 (x86-64-v4: AVX-512 F, CD, DQ, BW,
// VL besides), pushed for every function defined until core/physics/detail/target_pop.hpp. A copy
// includes its headers first, so that templates and inline functions it shares with the rest
// of the library keep the baseline target; only its own code gets this one. The feature lists
// are detail::cpu_has_avx2_set()'s and cpu_has_avx512_set()'s (core/physics/detail/cpu_features.hpp).
// No include guard: one push per copy.
#if defined(DAMPBOUND_SIMD_AVX512)
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx512f,avx512cd,avx512dq,avx512bw,avx512vl,avx2,avx,fma,bmi,bmi2,popcnt"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx512f,avx512cd,avx512dq,avx512bw,avx512vl,avx2,avx,fma,bmi,bmi2,popcnt")
#endif
#elif defined(DAMPBOUND_SIMD_AVX2)
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2,avx,fma,bmi,bmi2,popcnt"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2,avx,fma,bmi,bmi2,popcnt")
#endif
#else
#error "core/physics/detail/target_push.hpp: define DAMPBOUND_SIMD_AVX2 or DAMPBOUND_SIMD_AVX512 first"
#endif
