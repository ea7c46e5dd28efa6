#pragma once
// `sweep --device`: the GPU sweep as a TrialDevice (core/sweep/device.hpp) over the device
// side (gpu/runtime.hpp), and the choice between it and the CPU.
#include <cstdio>
#include <memory>
#include <string>

#include "core/sweep/device.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {

/// Opens the GPU sweep for `scene` (the scene's integrator, the sweep's policy and rules).
/// Throws std::runtime_error when no GPU can run it (the reason in one line).
std::unique_ptr<TrialDevice> open_gpu_sweep(const SceneSpec& scene, DampingPolicy policy,
                                            const StopRules& rules);

/// The device `sweep --device` asks for: nullptr for the CPU. `gpu` throws InputError (one
/// line, naming --device) when there is no usable GPU or it cannot run the scene (`plain`:
/// --plain was given, which steps every trial through Session on the CPU); `auto` takes the
/// GPU when it can, else the CPU. A GPU, and auto's choice either way, is said on `log`.
std::unique_ptr<TrialDevice> choose_sweep_device(SweepDevice device, const SceneSpec& scene,
                                                 DampingPolicy policy, const StopRules& rules,
                                                 bool plain, std::FILE* log);

}  // namespace dampbound
