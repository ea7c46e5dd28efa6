// The GPU sweep's device side in a build without CUDA (no nvcc at configure time, or
// -DDAMPBOUND_CUDA=OFF): nothing runs, and probe() says why.
#include <stdexcept>

#include "gpu/runtime.hpp"

namespace dampbound::gpu {

Probe probe() {
  return {false, "this dampbound was built without CUDA (no nvcc at configure time)"};
}

struct Runtime::Impl {};

Runtime::Runtime(const trial_body::FlatModel&, int) {
  throw std::runtime_error("this dampbound was built without CUDA");
}

Runtime::~Runtime() = default;

int Runtime::slots() const {
  return 0;
}

void Runtime::advance(trial_body::TrialSlot*, const unsigned char*, int) {}

}  // namespace dampbound::gpu
