#include "core/analysis/kappa_ceiling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "core/analysis/damping_limits.hpp"
#include "core/analysis/linear_stability_cholesky.hpp"
#include "core/physics/integrate.hpp"
#include "core/physics/safe_bound.hpp"
#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/physics/error.hpp"
#include "dampbound/physics/stiffness.hpp"

namespace dampbound {

StiffnessSelection whole_selection(const ModelSpec& spec) {
  StiffnessSelection s;
  s.label = "all springs and anchors";
  s.springs.resize(spec.springs.size());
  std::iota(s.springs.begin(), s.springs.end(), 0);
  for (int i = 0; i < spec.node_count(); ++i)
    if (spec.anchor_scale[static_cast<size_t>(i)] > 0) s.anchors.push_back(i);
  return s;
}

StiffnessSelection region_selection(const ModelSpec& spec, const SceneRegion& region) {
  StiffnessSelection s;
  s.label = region.label;
  std::vector<char> in(spec.rest.size(), 0);
  for (int i : region.nodes) in[static_cast<size_t>(i)] = 1;
  for (int k = 0; k < spec.spring_count(); ++k) {
    const Spring& sp = spec.springs[static_cast<size_t>(k)];
    if (in[static_cast<size_t>(sp.i)] && in[static_cast<size_t>(sp.j)]) s.springs.push_back(k);
  }
  for (int i : region.nodes)
    if (spec.anchor_scale[static_cast<size_t>(i)] > 0) s.anchors.push_back(i);
  return s;
}

ModelSpec scaled_stiffness(ModelSpec spec, const StiffnessSelection& selection, double factor) {
  for (int k : selection.springs) spec.springs[static_cast<size_t>(k)].kappa_scale *= factor;
  for (int i : selection.anchors) spec.anchor_scale[static_cast<size_t>(i)] *= factor;
  return spec;
}

StiffnessCeiling stiffness_ceiling(const SceneSpec& scene, const Params& params,
                                   const StiffnessSelection& selection, const StopRules& rules,
                                   bool verify,
                                   const std::function<bool(const std::string&)>& progress,
                                   double max_factor_flops) {
  const auto stage = [&](const std::string& next) {
    if (progress && !progress(next)) throw SuggestCancelled();
  };
  if (!integrator_traits(params.integrator).paper_step)
    throw InputError(std::string("--kappa-max: the exact index is the paper's step's "
                                 "(semi-implicit-euler), not ") + to_string(params.integrator));
  Params p = params;
  p.zeta.reset();  // gamma_i held at the scene's values while the stiffness moves
  StiffnessCeiling c;
  c.label = selection.label;
  c.springs = static_cast<int>(selection.springs.size());
  c.anchors = static_cast<int>(selection.anchors.size());
  stage("the index at factor 1 (" + std::to_string(scene.model.node_count()) + " nodes)");
  const Model model = compile_model(scene.model, p);
  const std::vector<Vec3>& x = model.spec().rest;
  if (!psd_floor(model, x))
    throw std::runtime_error("--kappa-max: K is not positive semi-definite at rest (a spring is "
                             "compressed), so no stiffness is stable (SPEC 9)");
  // K is linear in the scales: A_S = A(selection doubled) - A(model), same masses.
  const Model doubled = compile_model(scaled_stiffness(scene.model, selection, 2), p);
  const SparseMatrix A1 = mass_weighted(model, tangent_stiffness(model, x));
  const SparseMatrix AS = mass_weighted(doubled, tangent_stiffness(doubled, x)) - A1;
  const SparseMatrix C1 = weighted_damping(model, x, model.gamma);
  const double dt = p.dt, beta = model.rayleigh_stiffness;
  c.index =
      certified_largest_eigenvalue((dt * dt) * A1 + (2 * dt) * C1, nullptr, 1, max_factor_flops).hi;
  if (AS.norm() == 0) {
    c.factor = std::numeric_limits<double>::infinity();
    return c;
  }
  // dt^2 (A1 - AS) + 2 dt (C1 - beta AS + s (dt/2 + beta) AS) is the index matrix at factor s.
  const SparseMatrix A0 = A1 - AS, C0 = C1 - beta * AS, U = (dt / 2 + beta) * AS;
  stage("bisection on the factor (a certified largest eigenvalue per probe)");
  c.factor = largest_stable_coefficient(A0, C0, U, dt, max_factor_flops);
  if (!verify || !(c.factor > 0) || std::isinf(c.factor)) return c;
  // The ceiling is a statement about the linearised step: the runs take the scene's
  // perturbation (and the band it is judged by) scaled to 1e-3 of the shortest spring, where
  // the forces are linear to that order; the scene's own amplitude may leave that regime at
  // these stiffnesses (a 5 cm pull on the paper's 0.57 cm plane folds it).
  double shortest = std::numeric_limits<double>::infinity();
  for (const Spring& sp : scene.model.springs)
    if (sp.rest_length > 0) shortest = std::min(shortest, sp.rest_length);
  const double scale = std::isfinite(shortest) && rules.reference > 0
                           ? std::min(1.0, 1e-3 * shortest / rules.reference)
                           : 1.0;
  StopRules small = rules;
  small.reference *= scale;
  const auto run_at = [&](double f, const char* label) {
    SceneSpec s = scene;
    s.model = scaled_stiffness(scene.model, selection, f);
    for (Perturbation& q : s.perturbations) q.displacement *= scale, q.velocity *= scale;
    return verify_run(s, p, small, label);
  };
  c.run_scale = scale;
  stage("verifying run 1 of 2: 0.98 x the factor");
  c.below = run_at(0.98 * c.factor, "0.98 x ceiling");
  stage("verifying run 2 of 2: 1.02 x the factor");
  c.above = run_at(1.02 * c.factor, "1.02 x ceiling");
  c.ran = true;
  return c;
}

ContactCeilings contact_ceilings(const Model& model, const std::vector<Vec3>& x, double dt,
                                 double kd, int worst_count) {
  ContactCeilings out;
  const size_t n = model.spec().rest.size();
  out.k_max.assign(n, std::numeric_limits<double>::quiet_NaN());
  const DampedSafeRows rows(model, x);
  const double beta = model.rayleigh_stiffness;
  std::vector<int> free;
  for (size_t i = 0; i < n; ++i) {
    if (model.spec().fixed[i]) continue;
    const double g = rows.gamma_safe(static_cast<int>(i), dt);
    const double k = 2 * (g - model.gamma[i] - kd) / (dt + 2 * beta);
    out.k_max[i] = k > 0 ? k : 0.0;
    out.zero += k > 0 ? 0 : 1;
    free.push_back(static_cast<int>(i));
  }
  if (free.empty()) return out;
  const auto less = [&](int a, int b) {
    const double ka = out.k_max[static_cast<size_t>(a)], kb = out.k_max[static_cast<size_t>(b)];
    return ka < kb || (ka == kb && a < b);
  };
  std::vector<int> order = free;
  const size_t mid = order.size() / 2;
  std::nth_element(order.begin(), order.begin() + static_cast<long>(mid), order.end(), less);
  out.median = out.k_max[static_cast<size_t>(order[mid])];
  if (order.size() % 2 == 0) {  // the mean of the two middle values
    const double below = out.k_max[static_cast<size_t>(
        *std::max_element(order.begin(), order.begin() + static_cast<long>(mid), less))];
    out.median = 0.5 * (out.median + below);
  }
  const size_t w = std::min(order.size(), static_cast<size_t>(std::max(worst_count, 1)));
  std::partial_sort(order.begin(), order.begin() + static_cast<long>(w), order.end(), less);
  out.worst.assign(order.begin(), order.begin() + static_cast<long>(w));
  out.min = out.k_max[static_cast<size_t>(out.worst.front())];
  return out;
}

}  // namespace dampbound
