// Included FIRST by the .cpp files that inline Eigen's dense/sparse solvers and Spectra.
// GCC 12 with -march=native (AVX-512) reports false -Wmaybe-uninitialized inside its own
// intrinsics headers, and a false -Wuse-after-free inside Spectra's Hessenberg solver, when
// these templates are inlined; the pragmas must precede every include and last for the whole
// translation unit, so this header deliberately has no push/pop (and no #pragma once effect
// beyond the file that includes it).
#pragma once
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#if __GNUC__ >= 12
#pragma GCC diagnostic ignored "-Wuse-after-free"
#endif
#endif
