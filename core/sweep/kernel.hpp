#pragma once
// The batched sweep kernel: many trials of one scene stepped together, one trial per SIMD
// lane (structure of arrays), each with its own m, kappa, gamma, dt and factor. It mirrors
// step() (core/physics/step.cpp) operation by operation in the same order, so on the same trial it
// gives the same trajectory bit for bit (the build has -ffp-contract=off), and the same
// outcome, iteration and counts as Session::run_to_end, under either stop rule (SPEC 5, 8):
// both judge through judge_band(). A lane whose trial is over is refilled with the next
// trial at once.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dampbound/run/protocol.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {

/// What varies from trial to trial in a sweep (units as in Params).
struct TrialParams {
  double m = 0.001;
  double kappa = 0.001;
  double gamma = 0;
  double dt = 0.05;
  double factor = 1;
  /// SPEC 10 damping of a sweep that has these axes (unset: the scene's value).
  std::optional<double> kd, rayleigh_mass, rayleigh_stiffness;
};

/// Hands out the next trial: fills `id` and `params`, or returns false when none is left.
/// Called from the kernel's own thread only.
using TrialSource = std::function<bool(std::size_t& id, TrialParams& params)>;
/// Receives a finished trial.
using TrialSink = std::function<void(std::size_t id, const TrialResult& result)>;

/// The instruction sets the batched kernel is compiled for, all in every build (each a copy of
/// core/sweep/detail/kernel_body.cpp compiled with that target, detail/kernel_avx*.cpp);
/// `best` picks the widest this CPU runs, at run time. Every variant rounds exactly as step() does.
enum class KernelIsa { best, generic, avx2, avx512 };

const char* to_string(KernelIsa isa);
/// Parses "best" | "generic" | "avx2" | "avx512"; nullopt when unknown.
std::optional<KernelIsa> parse_kernel_isa(const std::string& s);
/// Whether this CPU (and OS) can run `isa` (always true for best and generic).
bool kernel_isa_supported(KernelIsa isa);
/// What `best` resolves to on this machine: DAMPBOUND_KERNEL_ISA from the environment when it
/// names a supported variant (for benchmarks and tests), else the widest supported one (the
/// plain copy in a DAMPBOUND_NATIVE build for an AVX-512 host: it is compiled for the host).
KernelIsa best_kernel_isa();

/// Why the batched kernel cannot run a scene (nullopt when it can): cuts (topology changes
/// mid-run) and integrators other than the paper's semi-implicit Euler and forward Euler.
std::optional<std::string> batch_kernel_unsupported(const SceneSpec& scene);
/// The same for the scene run with `params` instead of its own.
std::optional<std::string> batch_kernel_unsupported(const SceneSpec& scene, const Params& params);

class BatchKernel {
 public:
  /// The most trials a kernel runs side by side (one per SIMD lane): 8 for the AVX-512 and
  /// generic copies, 4 for the AVX2 copy.
  static constexpr int kLanes = 8;

  /// Topology, scales, external forces, fixed nodes and initial state from `scene`; the
  /// integrator from scene.params. Throws std::invalid_argument when
  /// batch_kernel_unsupported(scene) gives a reason, or when `isa` is not supported here.
  BatchKernel(const SceneSpec& scene, DampingPolicy policy, const StopRules& rules,
              KernelIsa isa = KernelIsa::best);
  ~BatchKernel();
  BatchKernel(const BatchKernel&) = delete;
  BatchKernel& operator=(const BatchKernel&) = delete;

  /// Steps trials from `source` until it is empty and every lane has finished; each result
  /// goes to `sink` as soon as its trial ends. Returns the lane-steps taken by real trials.
  /// When `cancel` becomes true the run returns at the next step; unfinished trials are
  /// dropped without reaching the sink.
  std::uint64_t run(const TrialSource& source, const TrialSink& sink,
                    const std::atomic<bool>* cancel = nullptr);

  /// Springs plus anchors evaluated per trial step (the benchmark's unit of work).
  long long spring_evaluations_per_step() const;

  /// The variant this kernel runs (never `best`).
  KernelIsa isa() const { return isa_; }

  /// One variant's kernel (core/sweep/detail/kernel_body.hpp).
  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
  KernelIsa isa_ = KernelIsa::generic;
};

}  // namespace dampbound
