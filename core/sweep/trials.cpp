// Support of the batched kernel: the order it applies the springs in, and the conversions
// between a sweep's trials and core's Params / RunResult.
#include <set>
#include <stdexcept>

#include "core/physics/integrate.hpp"
#include "core/sweep/kernel.hpp"
#include "core/sweep/trials.hpp"
#include "dampbound/run/session.hpp"

namespace dampbound {

Params trial_params(const Params& base, DampingPolicy policy, const TrialParams& t) {
  Params p = base;
  p.m = t.m;
  p.kappa = t.kappa;
  p.gamma = t.gamma;
  p.dt = t.dt;
  p.factor = t.factor;
  p.policy = policy;
  if (t.kd) p.kd = *t.kd;
  if (t.rayleigh_mass) p.rayleigh_mass = *t.rayleigh_mass;
  if (t.rayleigh_stiffness) p.rayleigh_stiffness = *t.rayleigh_stiffness;
  return p;
}

std::optional<std::string> batch_kernel_unsupported(const SceneSpec& scene) {
  return batch_kernel_unsupported(scene, scene.params);
}

std::optional<std::string> batch_kernel_unsupported(const SceneSpec& scene, const Params& params) {
  if (!scene.cuts.empty()) return "the scene cuts springs during the run";
  if (params.kd != 0 || params.rayleigh_mass != 0 || params.rayleigh_stiffness != 0)
    return "dashpot or Rayleigh damping: the batched kernel applies the nodal "
           "damping only, so each trial runs step()";
  const Integrator in = params.integrator;
  if (!integrator_traits(in).batched_kernel)
    return std::string("integrator ") + to_string(in);
  return std::nullopt;
}

// Greedy list scheduling: among the springs whose nodes have no earlier spring pending, take
// the first one that shares no node with the last kWindow applied (see spring_schedule in trials.hpp).
std::vector<int> spring_schedule(const ModelSpec& model) {
  const std::vector<Spring>& list = model.springs;
  const size_t nodes = model.rest.size();
  constexpr int kWindow = 6;
  const size_t count = list.size();
  std::vector<std::vector<size_t>> incident(nodes);
  for (size_t s = 0; s < count; ++s) {
    incident[static_cast<size_t>(list[s].i)].push_back(s);
    if (list[s].j != list[s].i) incident[static_cast<size_t>(list[s].j)].push_back(s);
  }
  std::vector<size_t> next(nodes, 0);
  auto is_ready = [&](size_t s) {
    const size_t i = static_cast<size_t>(list[s].i), j = static_cast<size_t>(list[s].j);
    return incident[i][next[i]] == s && incident[j][next[j]] == s;
  };
  std::set<size_t> ready;
  for (size_t s = 0; s < count; ++s)
    if (is_ready(s)) ready.insert(s);
  std::vector<int> out;
  out.reserve(count);
  std::vector<long> last_used(nodes, -kWindow - 1);
  while (!ready.empty()) {
    const long t = static_cast<long>(out.size());
    size_t pick = *ready.begin();
    for (size_t s : ready) {
      if (t - last_used[static_cast<size_t>(list[s].i)] > kWindow &&
          t - last_used[static_cast<size_t>(list[s].j)] > kWindow) {
        pick = s;
        break;
      }
    }
    ready.erase(pick);
    out.push_back(static_cast<int>(pick));
    for (int end : {list[pick].i, list[pick].j}) {
      const size_t e = static_cast<size_t>(end);
      last_used[e] = t;
      if (next[e] < incident[e].size() && incident[e][next[e]] == pick) ++next[e];
    }
    for (int end : {list[pick].i, list[pick].j}) {
      const size_t e = static_cast<size_t>(end);
      if (next[e] < incident[e].size() && is_ready(incident[e][next[e]]))
        ready.insert(incident[e][next[e]]);
    }
  }
  return out;
}

std::vector<TrialResult> run_batched(const SceneSpec& scene, DampingPolicy policy,
                                     const StopRules& rules,
                                     const std::vector<TrialParams>& trials, KernelIsa isa,
                                     const std::atomic<bool>* cancel) {
  std::vector<TrialResult> out(trials.size());
  BatchKernel kernel(scene, policy, rules, isa);
  std::size_t next = 0;
  kernel.run(
      [&](std::size_t& id, TrialParams& p) {
        if (next >= trials.size()) return false;
        id = next;
        p = trials[next++];
        return true;
      },
      [&](std::size_t id, const TrialResult& r) { out[id] = r; }, cancel);
  if (cancel != nullptr && cancel->load()) return {};
  return out;
}

TrialResult run_reference(const SceneSpec& scene, DampingPolicy policy, const StopRules& rules,
                          const TrialParams& trial, const std::atomic<bool>* cancel) {
  Session session(scene, trial_params(scene.params, policy, trial), rules);
  session.set_keep_trace(false);
  while (session.running()) {
    if (cancel && cancel->load(std::memory_order_relaxed)) return TrialResult{};
    session.step_once();
  }
  return session.result();  // its TrialResult part
}

}  // namespace dampbound
