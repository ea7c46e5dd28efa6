// The spring batch (spring_batch.cpp) compiled once more for AVX2 (with FMA, BMI1/2: x86-64-v3's
// set, detail::cpu_has_avx2_set()), under a target pragma instead of compiler flags, so that
// the rest of the library stays portable. FMA is allowed but never used: the build has
// -ffp-contract=off, so this copy rounds as the portable one does. Headers are included before
// the pragma: inline functions shared with other files keep the baseline target
// (tests/build/kernel_variants.sh checks the object).
#if defined(__x86_64__)
#include <immintrin.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <utility>

#include "core/physics/detail/spring_batch.hpp"  // spring_block.hpp and simd.hpp come after the pragma

#define DAMPBOUND_SPRING_BATCH_VARIANT spring_batch_avx2
#define DAMPBOUND_SIMD_AVX2 1
#include "core/physics/detail/target_push.hpp"

#include "core/physics/detail/spring_batch.cpp"

#include "core/physics/detail/target_pop.hpp"
#endif  // __x86_64__
