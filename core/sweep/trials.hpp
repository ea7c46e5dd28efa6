#pragma once
// Trials outside a sweep: the batched kernel over a list of trials on one thread, the reference
// run of one trial through Session, and the conversions between their results.
#include <atomic>
#include <vector>

#include "core/sweep/kernel.hpp"
#include "dampbound/run/session.hpp"

namespace dampbound {


/// Params of a scene with a trial's values and the sweep's policy filled in.
Params trial_params(const Params& base, DampingPolicy policy, const TrialParams& t);

/// The order in which the kernel applies the springs (indices into model.springs). Each
/// node's force must receive its springs' contributions in the list order of step()
/// (floating-point addition is not associative), so for every node its springs keep their
/// relative order; springs on different nodes are interleaved so that consecutive ones share
/// no node, which keeps one spring's force update from waiting on the previous one's through
/// memory and lets the CPU overlap their square roots and divisions.
std::vector<int> spring_schedule(const ModelSpec& model);

/// Runs `trials` with the batched kernel on one thread and returns their results in order
/// (tests, small sweeps, the tuner's map). When `cancel` becomes true it returns {} at the
/// next step.
std::vector<TrialResult> run_batched(const SceneSpec& scene, DampingPolicy policy,
                                     const StopRules& rules,
                                     const std::vector<TrialParams>& trials,
                                     KernelIsa isa = KernelIsa::best,
                                     const std::atomic<bool>* cancel = nullptr);

/// The reference: each trial through Session::step_once (the one step() of core). When
/// `cancel` becomes true it returns at the next step with outcome `running`.
TrialResult run_reference(const SceneSpec& scene, DampingPolicy policy, const StopRules& rules,
                          const TrialParams& trial, const std::atomic<bool>* cancel = nullptr);

}  // namespace dampbound
