#pragma once
// DAMPBOUND_HD marks a function that device code calls too: `__host__ __device__` where nvcc
// compiles the file (the GPU sweep, gpu/), nothing in plain C++. Such a function uses only
// what both sides have (arithmetic, <cmath>'s sqrt and fabs, no allocation, no exceptions), so
// its host and device copies round alike: IEEE square roots and divisions, no contraction into
// fused multiply-adds (-ffp-contract=off on the host, -fmad=false for nvcc).
#if defined(__CUDACC__)
#define DAMPBOUND_HD __host__ __device__
#else
#define DAMPBOUND_HD
#endif
