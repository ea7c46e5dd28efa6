#pragma once
// The GPU sweep's device side: gpu/runtime.cu (nvcc, where the build has CUDA) or
// gpu/runtime_none.cpp (without). Only the trial body's plain data crosses this line, so nvcc
// compiles one file and no core header beyond the trial body's (no Eigen, no toml++).
#include <cstddef>
#include <memory>
#include <string>

#include "core/sweep/detail/trial_body.hpp"

namespace dampbound::gpu {

/// The first CUDA device that can run the sweep (ok, `what` its name and memory), or why
/// there is none (`what` the reason: no CUDA in this build, no driver, no device, ...).
struct Probe {
  bool ok = false;
  std::string what;
};
Probe probe();

/// What a slot does in the next advance().
enum SlotMode : unsigned char {
  kContinue = 0,  ///< step on from where it stopped (if still running)
  kBegin = 1,     ///< a new trial: from the scene's initial state
  kIdle = 2,      ///< no trial
};

/// One scene on the device (its arrays, copied once) and the state of `slots()` trials run
/// side by side, one per device thread. Throws std::runtime_error on any CUDA error.
class Runtime {
 public:
  /// `model` points into host memory; `max_slots` caps the trials side by side (fewer when
  /// the device's free memory holds fewer states).
  Runtime(const trial_body::FlatModel& model, int max_slots);
  ~Runtime();
  Runtime(const Runtime&) = delete;
  Runtime& operator=(const Runtime&) = delete;

  int slots() const;
  /// Copies `slots` (constants, results, band histories) and `mode` (slots() each) to the
  /// device, steps every slot not idle up to `max_steps` steps or its verdict, copies the
  /// slots back.
  void advance(trial_body::TrialSlot* slots, const unsigned char* mode, int max_steps);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dampbound::gpu
