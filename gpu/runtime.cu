// The GPU sweep's device side: the trial body (core/sweep/detail/trial_body.hpp) run by one
// device thread per trial. Compiled with -fmad=false (no fused multiply-adds); double
// division and square root are IEEE correctly rounded on the device, so a thread's trial
// rounds exactly as the host copy of the body, the batched kernel and step() do.
#include <cuda_runtime.h>

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/runtime.hpp"

namespace dampbound::gpu {

namespace {

using trial_body::FlatModel;
using trial_body::TrialSlot;
using trial_body::TrialView;

void check(cudaError_t e, const char* what) {
  if (e != cudaSuccess)
    throw std::runtime_error(std::string("CUDA: ") + what + ": " + cudaGetErrorString(e));
}

/// Steps every slot that is not idle: a new trial from the initial state (kBegin), then up to
/// `max_steps` steps. Slot t's state arrays start at element t and stride `slots`, so
/// neighbouring threads touch neighbouring doubles.
__global__ void advance_trials(FlatModel model, TrialSlot* slots, const unsigned char* mode,
                               double* state, int count, int max_steps) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= count || mode[t] == kIdle) return;
  const std::size_t stride = static_cast<std::size_t>(count);
  const std::size_t n3 = 3 * static_cast<std::size_t>(model.nodes) * stride;
  const TrialView view{state + t,
                       state + n3 + t,
                       state + 2 * n3 + t,
                       state + 3 * n3 + t,
                       model.policy == DampingPolicy::safe ? state + 4 * n3 + t : nullptr,
                       stride};
  TrialSlot slot = slots[t];
  if (mode[t] == kBegin) trial_body::trial_begin(model, slot, view);
  if (slot.r.outcome == Outcome::running) trial_body::trial_advance(model, slot, view, max_steps);
  slots[t] = slot;
}

constexpr int kThreadsPerBlock = 128;

}  // namespace

Probe probe() {
  int count = 0;
  const cudaError_t e = cudaGetDeviceCount(&count);
  if (e == cudaErrorInsufficientDriver)
    return {false, "no NVIDIA driver, or one older than this build's CUDA " +
                       std::to_string(CUDART_VERSION / 1000) + " runtime"};
  if (e == cudaErrorNoDevice || (e == cudaSuccess && count == 0)) return {false, "no CUDA device"};
  if (e != cudaSuccess)
    return {false, std::string("no usable CUDA device (") + cudaGetErrorString(e) + ")"};
  cudaDeviceProp p{};
  if (cudaGetDeviceProperties(&p, 0) != cudaSuccess) return {false, "CUDA device 0 unreadable"};
  // A kernel image for this device: the build holds sm_90 code and compute_80 PTX.
  cudaFuncAttributes attr{};
  const cudaError_t image = cudaFuncGetAttributes(&attr, advance_trials);
  if (image != cudaSuccess)
    return {false, std::string(p.name) + " cannot run this build's kernel (" +
                       cudaGetErrorString(image) + ")"};
  char what[256];
  std::snprintf(what, sizeof what, "%s, compute capability %d.%d, %.0f GiB", p.name, p.major,
                p.minor, static_cast<double>(p.totalGlobalMem) / (1u << 30));
  return {true, what};
}

struct Runtime::Impl {
  FlatModel model;  // pointers into device memory
  std::vector<void*> owned;
  TrialSlot* slots = nullptr;
  unsigned char* mode = nullptr;
  double* state = nullptr;
  int count = 0;

  template <class T>
  const T* copy(const T* host, std::size_t n) {
    void* p = nullptr;
    check(cudaMalloc(&p, n * sizeof(T) + 1), "cudaMalloc");
    owned.push_back(p);
    if (n > 0) check(cudaMemcpy(p, host, n * sizeof(T), cudaMemcpyHostToDevice), "cudaMemcpy");
    return static_cast<const T*>(p);
  }

  void* allocate(std::size_t bytes) {
    void* p = nullptr;
    check(cudaMalloc(&p, bytes), "cudaMalloc");
    owned.push_back(p);
    return p;
  }

  ~Impl() {
    for (void* p : owned) cudaFree(p);
  }
};

Runtime::Runtime(const FlatModel& host, int max_slots) : impl_(new Impl) {
  Impl& d = *impl_;
  const std::size_t n = static_cast<std::size_t>(host.nodes);
  const std::size_t s = static_cast<std::size_t>(host.springs);
  const std::size_t incident = static_cast<std::size_t>(host.incident_offset[n]);
  d.model = host;
  d.model.spring_i = d.copy(host.spring_i, s);
  d.model.spring_j = d.copy(host.spring_j, s);
  d.model.rest_length = d.copy(host.rest_length, s);
  d.model.kappa_scale = d.copy(host.kappa_scale, s);
  d.model.kd_scale = d.copy(host.kd_scale, s);
  d.model.incident_offset = d.copy(host.incident_offset, n + 1);
  d.model.incident = d.copy(host.incident, incident);
  d.model.rest = d.copy(host.rest, 3 * n);
  d.model.x0 = d.copy(host.x0, 3 * n);
  d.model.v0 = d.copy(host.v0, 3 * n);
  d.model.ext = d.copy(host.ext, 3 * n);
  d.model.anchor_scale = d.copy(host.anchor_scale, n);
  d.model.anchor_kd_scale = d.copy(host.anchor_kd_scale, n);
  d.model.mass_scale = d.copy(host.mass_scale, n);
  d.model.gamma_scale = d.copy(host.gamma_scale, n);
  d.model.kappa_max_scale = d.copy(host.kappa_max_scale, n);
  d.model.fixed = d.copy(host.fixed, n);
  // x, v, F, D' (3 per node each), and the safe policy's 9 per node.
  const std::size_t doubles =
      12 * n + (host.policy == DampingPolicy::safe ? trial_body::kSafePerNode * n : 0);
  const std::size_t per_slot = doubles * sizeof(double) + sizeof(TrialSlot) + 1;
  std::size_t free_bytes = 0, total_bytes = 0;
  check(cudaMemGetInfo(&free_bytes, &total_bytes), "cudaMemGetInfo");
  std::size_t fit = free_bytes / 2 / per_slot;  // half the free memory at most
  if (fit < 1) throw std::runtime_error("CUDA: the device has no memory for one trial's state");
  d.count = static_cast<int>(fit < static_cast<std::size_t>(max_slots) ? fit : max_slots);
  const std::size_t count = static_cast<std::size_t>(d.count);
  d.slots = static_cast<TrialSlot*>(d.allocate(count * sizeof(TrialSlot)));
  d.mode = static_cast<unsigned char*>(d.allocate(count));
  d.state = static_cast<double*>(d.allocate(count * doubles * sizeof(double)));
}

Runtime::~Runtime() = default;

int Runtime::slots() const {
  return impl_->count;
}

void Runtime::advance(TrialSlot* slots, const unsigned char* mode, int max_steps) {
  Impl& d = *impl_;
  const std::size_t count = static_cast<std::size_t>(d.count);
  check(cudaMemcpy(d.slots, slots, count * sizeof(TrialSlot), cudaMemcpyHostToDevice),
        "cudaMemcpy slots");
  check(cudaMemcpy(d.mode, mode, count, cudaMemcpyHostToDevice), "cudaMemcpy modes");
  const int blocks = (d.count + kThreadsPerBlock - 1) / kThreadsPerBlock;
  advance_trials<<<blocks, kThreadsPerBlock>>>(d.model, d.slots, d.mode, d.state, d.count,
                                               max_steps);
  check(cudaGetLastError(), "kernel launch");
  check(cudaMemcpy(slots, d.slots, count * sizeof(TrialSlot), cudaMemcpyDeviceToHost),
        "cudaMemcpy results");
}

}  // namespace dampbound::gpu
