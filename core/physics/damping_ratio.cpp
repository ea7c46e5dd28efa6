#include "core/physics/damping_ratio.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "dampbound/physics/bounds.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound {

std::vector<double> damping_ratio(const Model& model) {
  std::vector<double> zeta(model.gamma.size());
  for (size_t i = 0; i < zeta.size(); ++i)
    zeta[i] = damping_ratio(model.gamma[i], model.lower_bound[i]);
  return zeta;
}

DampingRatioRange damping_ratio_range(const Model& model) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  DampingRatioRange r{nan, nan};
  const std::vector<double> zeta = damping_ratio(model);
  for (size_t i = 0; i < zeta.size(); ++i) {
    if (model.spec().fixed[i] || std::isnan(zeta[i])) continue;
    r.min = std::isnan(r.min) ? zeta[i] : std::min(r.min, zeta[i]);
    r.max = std::isnan(r.max) ? zeta[i] : std::max(r.max, zeta[i]);
  }
  return r;
}

double gamma_of_zeta(double zeta, const Params& params) {
  return zeta * lower_bound(params.m, params.kappa);
}

void resolve_zeta(ModelSpec& spec, Params& params) {
  if (!params.zeta) return;
  // The lower bounds at m = kappa = 1 are 2 sqrt(mass_scale_i * kappa_i / kappa): compile_model
  // computes kappa_i (SPEC 3), so no second copy of that rule exists.
  Params unit;
  unit.m = unit.kappa = 1;
  unit.gamma = 0;
  const Model m = compile_model(spec, unit);
  for (size_t i = 0; i < spec.gamma_scale.size(); ++i)
    spec.gamma_scale[i] *= m.lower_bound[i] / 2;
  resolve_zeta(params);
}

void resolve_zeta(Params& params) {
  if (!params.zeta) return;
  params.gamma = gamma_of_zeta(*params.zeta, params);
  params.zeta.reset();
}

}  // namespace dampbound
