// The batched kernel (core/sweep/detail/kernel_body.cpp) compiled once more for AVX-512 (F, CD, DQ, BW, VL: x86-64-v4's set),
// under a target pragma instead of compiler flags, so that the rest of the library stays
// portable; core/sweep/kernel.cpp runs it only on a CPU that has these features.
// FMA is allowed but never used: the build has -ffp-contract=off, so this copy rounds as
// step() does. Headers are included before the pragma: templates and inline functions shared
// with other files keep the baseline target, and only the kernel's own code gets this one.
#if defined(__x86_64__)
#include <immintrin.h>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "core/sweep/detail/kernel_avx512.hpp"
#include "core/sweep/detail/kernel_body.hpp"
#include "core/sweep/kernel.hpp"
#include "dampbound/run/session.hpp"

#define DAMPBOUND_KERNEL_VARIANT kernel_avx512
#define DAMPBOUND_SIMD_AVX512 1
#include "core/physics/detail/target_push.hpp"

#include "core/sweep/detail/kernel_body.cpp"
#include "core/sweep/trials.hpp"

#include "core/physics/detail/target_pop.hpp"
#endif  // __x86_64__
