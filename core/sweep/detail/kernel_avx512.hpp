#pragma once
// The batched kernel compiled for AVX512 (kernel_avx512.cpp: kernel_body.cpp under a target pragma).
#include <memory>

#include "core/sweep/detail/kernel_body.hpp"

namespace dampbound {

namespace kernel_avx512 {
std::unique_ptr<BatchKernel::Impl> make(const SceneSpec&, DampingPolicy, const StopRules&);
}

}  // namespace dampbound
