// Which compiled variant of the batched kernel runs (core/sweep/detail/kernel_body.hpp): the widest
// instruction set this CPU has, decided at run time, so one build runs on any x86-64 machine.
#include <cstdlib>
#include <stdexcept>

#include "core/physics/detail/cpu_features.hpp"
#include "core/sweep/detail/kernel_avx2.hpp"
#include "core/sweep/detail/kernel_avx512.hpp"
#include "core/sweep/detail/kernel_body.hpp"
#include "core/sweep/kernel.hpp"

namespace dampbound {

const char* to_string(KernelIsa isa) {
  switch (isa) {
    case KernelIsa::best:
      return "best";
    case KernelIsa::generic:
      return "generic";
    case KernelIsa::avx2:
      return "avx2";
    case KernelIsa::avx512:
      return "avx512";
  }
  return "?";
}

std::optional<KernelIsa> parse_kernel_isa(const std::string& s) {
  for (KernelIsa isa : {KernelIsa::best, KernelIsa::generic, KernelIsa::avx2, KernelIsa::avx512})
    if (s == to_string(isa)) return isa;
  return std::nullopt;
}

bool kernel_isa_supported(KernelIsa isa) {
  // The features of the target pragmas in core/sweep/detail/kernel_avx2.cpp and _avx512.cpp.
  switch (isa) {
    case KernelIsa::best:
    case KernelIsa::generic:
      return true;
    case KernelIsa::avx2:
      return detail::cpu_has_avx2_set();
    case KernelIsa::avx512:
      return detail::cpu_has_avx512_set();
  }
  return false;
}

KernelIsa best_kernel_isa() {
  if (const char* env = std::getenv("DAMPBOUND_KERNEL_ISA")) {
    const auto isa = parse_kernel_isa(env);
    if (isa && *isa != KernelIsa::best && kernel_isa_supported(*isa)) return *isa;
  }
#if defined(__AVX512F__)
  // Built for the host (DAMPBOUND_NATIVE) on an AVX-512 machine: the plain copy already has
  // the widest target, and the host's tuning besides.
  return KernelIsa::generic;
#else
  for (KernelIsa isa : {KernelIsa::avx512, KernelIsa::avx2})
    if (kernel_isa_supported(isa)) return isa;
  return KernelIsa::generic;
#endif
}

BatchKernel::BatchKernel(const SceneSpec& scene, DampingPolicy policy, const StopRules& rules,
                         KernelIsa isa) {
  isa_ = isa == KernelIsa::best ? best_kernel_isa() : isa;
  if (!kernel_isa_supported(isa_))
    throw std::invalid_argument(std::string("batched kernel: this CPU cannot run the ") +
                                to_string(isa_) + " variant");
  switch (isa_) {
#if defined(__x86_64__)
    case KernelIsa::avx512:
      impl_ = kernel_avx512::make(scene, policy, rules);
      break;
    case KernelIsa::avx2:
      impl_ = kernel_avx2::make(scene, policy, rules);
      break;
#endif
    default:
      impl_ = kernel_generic::make(scene, policy, rules);
      break;
  }
}

BatchKernel::~BatchKernel() = default;

std::uint64_t BatchKernel::run(const TrialSource& source, const TrialSink& sink,
                               const std::atomic<bool>* cancel) {
  return impl_->run(source, sink, cancel);
}

long long BatchKernel::spring_evaluations_per_step() const {
  return impl_->spring_evaluations_per_step();
}

}  // namespace dampbound
