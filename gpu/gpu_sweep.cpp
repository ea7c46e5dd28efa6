// The GPU sweep's host side: hands trials to the device's slots, takes results back, refills
// each finished slot with the next trial, as the batched kernel does with its lanes.
#include "gpu/gpu_sweep.hpp"

#include <chrono>
#include <stdexcept>
#include <vector>

#include "core/sweep/flat_model.hpp"
#include "dampbound/physics/error.hpp"
#include "gpu/runtime.hpp"

namespace dampbound {

namespace {

/// Most trials side by side: enough to fill a data-centre GPU's threads several times over.
constexpr int kMaxSlots = 1 << 17;
/// A launch steps for about this long, so that Ctrl-C and the progress line come promptly
/// and a slot whose trial ended early idles little.
constexpr double kLaunchSeconds = 0.25;

class GpuSweep final : public TrialDevice {
 public:
  GpuSweep(const SceneSpec& scene, DampingPolicy policy, const StopRules& rules, std::string name)
      : flat_(scene, policy, rules), runtime_(flat_.view(), kMaxSlots), name_(std::move(name)) {}

  std::string name() const override { return name_; }

  std::uint64_t run(const TrialSource& source, const TrialSink& sink,
                    const std::atomic<bool>* cancel) override {
    const int count = runtime_.slots();
    std::vector<trial_body::TrialSlot> slots(static_cast<size_t>(count));
    std::vector<unsigned char> mode(static_cast<size_t>(count), gpu::kIdle);
    std::vector<std::size_t> ids(static_cast<size_t>(count), 0);
    int live = 0;
    auto refill = [&](size_t s) {
      TrialParams p;
      if (source(ids[s], p)) {
        slots[s].p = flat_.constants(p);
        mode[s] = gpu::kBegin;
        ++live;
      } else {
        mode[s] = gpu::kIdle;
      }
    };
    for (size_t s = 0; s < slots.size(); ++s) refill(s);
    std::uint64_t steps_taken = 0;
    int steps = 16;
    using Clock = std::chrono::steady_clock;
    while (live > 0) {
      if (cancel && cancel->load(std::memory_order_relaxed)) break;
      const Clock::time_point t0 = Clock::now();
      runtime_.advance(slots.data(), mode.data(), steps);
      const double took = std::chrono::duration<double>(Clock::now() - t0).count();
      if (took < kLaunchSeconds / 2 && steps < (1 << 20)) steps *= 2;
      for (size_t s = 0; s < slots.size(); ++s) {
        if (mode[s] == gpu::kIdle) continue;
        mode[s] = gpu::kContinue;
        const TrialResult& r = slots[s].r;
        if (r.outcome == Outcome::running) continue;
        steps_taken += static_cast<std::uint64_t>(r.iterations);
        --live;
        sink(ids[s], r);
        refill(s);
      }
    }
    return steps_taken;
  }

 private:
  FlatScene flat_;
  gpu::Runtime runtime_;
  std::string name_;
};

}  // namespace

std::unique_ptr<TrialDevice> open_gpu_sweep(const SceneSpec& scene, DampingPolicy policy,
                                            const StopRules& rules) {
  const gpu::Probe probe = gpu::probe();
  if (!probe.ok) throw std::runtime_error(probe.what);
  if (const auto why = trial_body_unsupported(scene))
    throw std::runtime_error("the GPU sweep cannot run this scene: " + *why);
  return std::make_unique<GpuSweep>(scene, policy, rules, probe.what);
}

std::unique_ptr<TrialDevice> choose_sweep_device(SweepDevice device, const SceneSpec& scene,
                                                 DampingPolicy policy, const StopRules& rules,
                                                 bool plain, std::FILE* log) {
  if (device == SweepDevice::cpu) return nullptr;
  std::string why;
  std::unique_ptr<TrialDevice> gpu;
  if (plain) {
    why = "--plain steps every trial through Session on the CPU";
  } else {
    try {
      gpu = open_gpu_sweep(scene, policy, rules);
    } catch (const std::exception& e) {
      why = e.what();
    }
  }
  if (!gpu && device == SweepDevice::gpu) throw InputError("--device gpu: " + why);
  std::fprintf(log, "sweep: device %s: %s\n", gpu ? "gpu" : "cpu",
               gpu ? gpu->name().c_str() : ("no GPU sweep here, " + why).c_str());
  return gpu;
}

}  // namespace dampbound
