// Ends the target pushed by core/physics/detail/target_push.hpp. No include guard: one pop per push.
#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif
