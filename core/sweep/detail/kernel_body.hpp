#pragma once
// What each compiled variant of the batched kernel provides (core/sweep/detail/kernel_body.cpp, built as
// is and again under a target pragma by core/sweep/detail/kernel_avx2.cpp and
// core/sweep/detail/kernel_avx512.cpp), and the factory of each. Internal to core: the dispatch in
// core/sweep/kernel.cpp picks one at run time.
#include <atomic>
#include <cstdint>
#include <memory>

#include "core/sweep/kernel.hpp"

namespace dampbound {

struct BatchKernel::Impl {
  virtual ~Impl() = default;
  virtual std::uint64_t run(const TrialSource& source, const TrialSink& sink,
                            const std::atomic<bool>* cancel) = 0;
  virtual long long spring_evaluations_per_step() const = 0;
};

// One factory per variant; a variant missing on this architecture has no definition and is
// never called (kernel_isa_supported says no).
namespace kernel_generic {
std::unique_ptr<BatchKernel::Impl> make(const SceneSpec&, DampingPolicy, const StopRules&);
}

}  // namespace dampbound
