#include "core/analysis/mass_scaling_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/analysis/linear_stability_cholesky.hpp"
#include "core/analysis/substeps.hpp"
#include "core/analysis/worst_nodes.hpp"
#include "core/physics/damping_ratio.hpp"
#include "core/physics/detail/numbers.hpp"

namespace dampbound {
namespace {


/// sqrt(lambda_min(M^-1 K)) at rest (1/s), NaN where lambda_min <= 0 (a zero mode).
double lowest_frequency(const Model& model, double max_factor_flops) {
  const SparseMatrix A = mass_weighted(model, tangent_stiffness(model, model.spec().rest));
  if (A.rows() == 0) return kNaN;
  const double lo =
      certified_smallest_eigenvalue(A, psd_floor(model, model.spec().rest), 1, max_factor_flops)
          .lo;
  return lo > 0 ? std::sqrt(lo) : kNaN;
}

/// The scale that gives at least `mass` once multiplied by m (compile_model's m_i = m scale_i).
double scale_for(double mass, double m) {
  double scale = mass / m;
  while (m * scale < mass) scale = std::nextafter(scale, std::numeric_limits<double>::infinity());
  return scale;
}

}  // namespace

MassScalingProblem mass_scaling_problem(const Model& model) {
  MassScalingProblem p;
  const std::vector<Vec3>& x = model.spec().rest;
  p.K = tangent_stiffness(model, x);
  // C' = C - alpha M: spring_damping_matrix holds alpha M on its diagonal; it is taken out
  // again term by term (alpha m_i), the nodal gamma_i put in.
  p.C = spring_damping_matrix(model, x);
  std::vector<Eigen::Triplet<double>> diag;
  int b = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    p.mass.push_back(model.mass[i]);
    const double d = model.gamma[i] - model.rayleigh_mass * model.mass[i];
    for (int r = 0; r < 3; ++r)
      if (d != 0) diag.emplace_back(3 * b + r, 3 * b + r, d);
    ++b;
  }
  SparseMatrix D(p.C.rows(), p.C.cols());
  D.setFromTriplets(diag.begin(), diag.end());
  p.C += D;
  p.alpha = model.rayleigh_mass;
  return p;
}

SceneMassScaling scene_mass_scaling(const SceneSpec& scene_in, const Params& params_in,
                                    const StopRules& rules, double dt_target,
                                    const SceneMassScalingOptions& options) {
  SceneSpec scene = scene_in;
  Params params = params_in;
  resolve_zeta(scene.model, params);  // gamma_i fixed before the masses change
  params.policy = DampingPolicy::fixed;
  params.dt = dt_target;
  // The run covers the scene's simulated time at its own dt, as the substeps' runs do.
  StopRules run_rules = rules;
  run_rules.max_iterations =
      verify_iterations(rules.max_iterations, rules.max_iterations * params_in.dt, dt_target);
  SceneMassScaling s;
  s.params = params;
  const Model model = compile_model(scene.model, params);
  s.result = mass_scaling(mass_scaling_problem(model), dt_target, options);
  s.mass_before = model.mass;
  s.mass_after = model.mass;
  s.mass_scale = scene.model.mass_scale;
  s.scene = scene;
  s.scene.params = params;
  s.scene.rules = run_rules;
  s.scene.runs.clear();
  s.scene.expectations.clear();
  const auto stage = [&](const char* next) {
    if (options.progress && !options.progress(next)) throw SuggestCancelled();
  };
  if (s.result.kind == MassScalingCase::nothing_to_add && options.verify) {
    stage("the run at dt* with the masses as given");
    s.run = verify_run(s.scene, params, run_rules, "run at dt* with the masses as given");
    s.ran = true;
  }
  if (s.result.kind != MassScalingCase::scaled) return s;

  int b = 0;
  for (size_t i = 0; i < model.mass.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    const double m = s.result.mass[static_cast<size_t>(b++)];
    if (m == model.mass[i]) continue;  // not scaled
    s.mass_scale[i] = scale_for(m, params.m);
    s.mass_after[i] = params.m * s.mass_scale[i];
  }
  // The report: the nodes with the most added mass, and why they limit the step.
  std::vector<int> order;
  for (size_t i = 0; i < model.mass.size(); ++i)
    if (s.mass_after[i] > s.mass_before[i]) order.push_back(static_cast<int>(i));
  const auto added = [&](int i) {
    return s.mass_after[static_cast<size_t>(i)] - s.mass_before[static_cast<size_t>(i)];
  };
  const size_t k = std::min(order.size(), static_cast<size_t>(std::max(options.top, 0)));
  std::partial_sort(order.begin(), order.begin() + static_cast<long>(k), order.end(),
                    [&](int a, int c) { return added(a) > added(c) || (added(a) == added(c) && a < c); });
  order.resize(k);
  const std::vector<WorstNode> why = describe_nodes(model, model.spec().rest, dt_target, order);
  for (size_t j = 0; j < k; ++j) {
    const size_t i = static_cast<size_t>(order[j]);
    s.top.push_back({order[j], s.mass_before[i], s.mass_after[i],
                     s.mass_after[i] / s.mass_before[i], why[j].cause});
  }
  for (size_t i = 0; i < model.mass.size(); ++i) {
    // Eq. 5: 2 sqrt(m_i kappa_i) grows as sqrt(m'_i / m_i).
    const double change = 100 * (std::sqrt(s.mass_after[i] / s.mass_before[i]) - 1);
    if (change > s.lower_bound_change) s.lower_bound_change = change, s.lower_bound_node = int(i);
  }
  s.scene.model.mass_scale = s.mass_scale;
  const SceneSpec& scaled = s.scene;
  stage("the lowest frequency before and after");
  const Model after = compile_model(scaled.model, params);
  s.frequency_before = lowest_frequency(model, options.max_factor_flops);
  s.frequency_after = lowest_frequency(after, options.max_factor_flops);
  // The certified ends are ~1e-10 relative wide: a change below that is none (the lowest
  // mode of a mesh whose scaled nodes are not in it, e.g. an anchored plane's floor).
  const double ratio = s.frequency_after / s.frequency_before - 1;
  s.frequency_change = std::abs(ratio) < 1e-9 ? 0.0 : 100 * ratio;
  if (options.verify && !s.result.over_cap) {
    stage("the run at dt* with the scaled masses");
    s.run = verify_run(scaled, params, run_rules, "run at dt* with the scaled masses");
    s.ran = true;
  }
  return s;
}

}  // namespace dampbound
