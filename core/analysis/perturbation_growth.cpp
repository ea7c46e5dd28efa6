#include "core/analysis/perturbation_growth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/physics/detail/numbers.hpp"
#include "dampbound/physics/step.hpp"

namespace dampbound {


double perturbation_growth(const Model& model, const Params& params, int steps,
                           double amplitude, unsigned seed) {
  return perturbation_growth(model, model.spec().rest, params, steps, amplitude, seed);
}

double perturbation_growth(const Model& model, const std::vector<Vec3>& about,
                           const Params& params_in, int steps, double amplitude, unsigned seed) {
  if (about.size() != model.spec().rest.size())
    throw std::invalid_argument("perturbation_growth: one position per node is needed");
  Params params = params_in;
  params.policy = DampingPolicy::fixed;
  State state = rest_state(model);
  state.x = about;
  auto uniform = [&seed] {  // a linear congruential generator: the same numbers everywhere
    seed = seed * 1103515245u + 12345u;
    return static_cast<double>((seed >> 8) & 0xffffu) / 65535.0 - 0.5;
  };
  auto away = [&] {  // max_i |x_i - about_i|; inf once a run has overflowed (inf, NaN)
    double d = 0;
    for (size_t i = 0; i < state.x.size(); ++i) {
      const double a = (state.x[i] - about[i]).norm();
      if (!std::isfinite(a)) return kInf;
      d = std::max(d, a);
    }
    return d;
  };
  for (size_t i = 0; i < state.x.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    const Vec3 d(uniform(), uniform(), uniform());
    state.x[i] += (2 * amplitude) * d;
  }
  const double before = away();
  StepWorkspace ws;
  for (int k = 0; k < steps; ++k) step(model, params, state, ws);
  return before > 0 ? away() / before : 0;
}

}  // namespace dampbound
