#pragma once
// Where a sweep steps its trials: on the CPU's threads (the batched kernel, or Session per
// trial), or on a device that runs the trial body (core/sweep/detail/trial_body.hpp) for many
// trials at once, the GPU sweep (gpu/). The runner hands a device the classes one by one as
// it hands them to the batched kernel, so the journal, --resume, --shard and the CSV are the
// same either way.
#include <atomic>
#include <cstdint>
#include <optional>
#include <string>

#include "core/sweep/kernel.hpp"

namespace dampbound {

/// `sweep --device`: cpu (the default), gpu (fails without one), auto (the GPU when there is
/// one that can run the scene, else the CPU).
enum class SweepDevice { cpu, gpu, automatic };

const char* to_string(SweepDevice d);  ///< "cpu", "gpu", "auto"
/// Parses "cpu" | "gpu" | "auto"; nullopt when unknown.
std::optional<SweepDevice> parse_sweep_device(const std::string& s);

/// A device that runs a sweep's trials (one scene, policy and stop rules, fixed when it is
/// made). Same contract as BatchKernel::run: trials from `source` until it is empty, each
/// result to `sink` as soon as its trial ends, unfinished trials dropped when `cancel` becomes
/// true; returns the trial-steps taken. Called from one thread.
class TrialDevice {
 public:
  virtual ~TrialDevice() = default;
  /// What runs the trials, for the report (a GPU's name, compute capability and memory).
  virtual std::string name() const = 0;
  virtual std::uint64_t run(const TrialSource& source, const TrialSink& sink,
                            const std::atomic<bool>* cancel) = 0;
};

}  // namespace dampbound
