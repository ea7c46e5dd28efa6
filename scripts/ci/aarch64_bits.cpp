// The check that scripts/ci/aarch64.sh cross-builds for aarch64 and runs under qemu (and
// natively, to compare): every trial of a small sample through the batched kernel's generic
// copy and through the plain step() (run_reference), on the paper plane, every policy, both
// explicit integrators; any difference in outcome, counts or the bits of the final maximum
// displacement fails. It prints one line per run with a digest of every result, so runs on
// two architectures can be compared: the same digest means the same bits.
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#include "core/sweep/trials.hpp"
#include "dampbound/physics/bounds.hpp"
#include "dampbound/run/scene.hpp"

using namespace dampbound;

namespace {

std::uint64_t bits(double x) {
  std::uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}

/// FNV-1a over 64-bit words.
void mix(std::uint64_t& h, std::uint64_t v) {
  for (int k = 0; k < 8; ++k) {
    h ^= (v >> (8 * k)) & 0xff;
    h *= 1099511628211ULL;
  }
}

}  // namespace

int main() {
  SceneSpec scene = paper_plane_scene(8);
  StopRules rules = scene.rules;
  rules.max_iterations = 150;
  std::vector<TrialParams> trials;
  for (double zeta : {0.2, 1.0})
    for (double r : {1.0, 60.0, 400.0})
      for (double factor : {1.0, 1.05}) {
        TrialParams t;
        t.m = 0.002;
        t.kappa = r * t.m;
        t.gamma = zeta * lower_bound(t.m, t.kappa);
        t.factor = factor;
        trials.push_back(t);
      }
  std::uint64_t digest = 14695981039346656037ULL;
  int compared = 0, differ = 0;
  for (Integrator integ : {Integrator::semi_implicit_euler, Integrator::forward_euler}) {
    scene.params.integrator = integ;
    for (DampingPolicy p : {DampingPolicy::fixed, DampingPolicy::clamp, DampingPolicy::upper,
                            DampingPolicy::lower, DampingPolicy::safe}) {
      const auto got = run_batched(scene, p, rules, trials, KernelIsa::generic);
      for (size_t k = 0; k < trials.size(); ++k) {
        const TrialResult ref = run_reference(scene, p, rules, trials[k]);
        const TrialResult& g = got[k];
        ++compared;
        if (g.outcome != ref.outcome || g.iterations != ref.iterations ||
            bits(g.max_displacement) != bits(ref.max_displacement) ||
            g.violations != ref.violations || g.unstabilisable != ref.unstabilisable ||
            g.clamped != ref.clamped) {
          ++differ;
          std::printf("differ: %s %s trial %zu: kernel %d iterations %.17g, step() %d %.17g\n",
                      to_string(integ), to_string(p), k, g.iterations, g.max_displacement,
                      ref.iterations, ref.max_displacement);
        }
        for (std::uint64_t v :
             {static_cast<std::uint64_t>(ref.outcome), static_cast<std::uint64_t>(ref.iterations),
              bits(ref.max_displacement), static_cast<std::uint64_t>(ref.violations),
              static_cast<std::uint64_t>(ref.unstabilisable),
              static_cast<std::uint64_t>(ref.clamped)})
          mix(digest, v);
      }
    }
  }
  std::printf("kernel (generic copy) against step(): %d trials, %d differ; digest %016" PRIx64
              "\n",
              compared, differ, digest);
  return differ == 0 ? 0 : 1;
}
