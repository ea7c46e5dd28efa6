#include "dampbound/physics/step_isa.hpp"

#include <cstdlib>

#include "core/physics/detail/cpu_features.hpp"

namespace dampbound {

const char* to_string(StepIsa isa) {
  switch (isa) {
    case StepIsa::best:
      return "best";
    case StepIsa::generic:
      return "generic";
    case StepIsa::avx2:
      return "avx2";
  }
  return "?";
}

std::optional<StepIsa> parse_step_isa(const std::string& s) {
  for (StepIsa isa : {StepIsa::best, StepIsa::generic, StepIsa::avx2})
    if (s == to_string(isa)) return isa;
  return std::nullopt;
}

bool step_isa_supported(StepIsa isa) {
  switch (isa) {
    case StepIsa::best:
    case StepIsa::generic:
      return true;
    case StepIsa::avx2:
      return detail::cpu_has_avx2_set();
  }
  return false;
}

namespace {

StepIsa resolve_best() {
  if (const char* env = std::getenv("DAMPBOUND_STEP_ISA")) {
    const auto isa = parse_step_isa(env);
    if (isa && *isa != StepIsa::best && step_isa_supported(*isa)) return *isa;
  }
#if defined(__AVX2__)
  // Built for the host (DAMPBOUND_NATIVE) on an AVX2 machine or wider: the plain copy already
  // has the host's target and tuning.
  return StepIsa::generic;
#else
  return step_isa_supported(StepIsa::avx2) ? StepIsa::avx2 : StepIsa::generic;
#endif
}

}  // namespace

StepIsa best_step_isa() {
  static const StepIsa best = resolve_best();
  return best;
}

}  // namespace dampbound
