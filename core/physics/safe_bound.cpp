#include "core/physics/safe_bound.hpp"

#include <limits>
#include <optional>

#include "core/physics/detail/numbers.hpp"
#include "core/physics/detail/spring_pass.hpp"
#include "dampbound/physics/closed_forms.hpp"

namespace dampbound {

int safe_row_sums(const Model& model, const std::vector<Vec3>& x, std::vector<double>& row_sum,
                  SpringPass* pass) {
  return detail::spring_pass(model, x, nullptr, &row_sum, pass).compressed;
}

double safe_dt(double m, double gamma, double row_sum) {
  // The positive root of R dt^2 + 2 c dt = 4: SPEC 7's formula with lambda_max -> R_i.
  return semi_implicit_dt_max(row_sum, gamma / m);
}

NodeSafeBounds::NodeSafeBounds(const Model& model, const std::vector<Vec3>& x) : model_(model) {
  compressed_ = safe_row_sums(model, x, row_sum_);
  if (model.spring_damping) damped_.emplace(model, x);
}

double NodeSafeBounds::gamma_safe(int node, double dt) const {
  return damped_ ? damped_->gamma_safe(node, dt)
                 : safe_gamma(model_.mass[static_cast<size_t>(node)], dt, row_sum(node));
}

double NodeSafeBounds::dt_safe(int node, double gamma) const {
  return damped_ ? damped_->dt_safe(node, gamma)
                 : safe_dt(model_.mass[static_cast<size_t>(node)], gamma, row_sum(node));
}

SafeBoundSummary safe_bound_summary(const Model& model, const std::vector<Vec3>& x, double dt) {
  SafeBoundSummary s;
  const NodeSafeBounds rows(model, x);
  s.compressed_springs = rows.compressed_springs();
  s.gamma_safe = s.dt_safe = kInf;
  for (size_t i = 0; i < model.mass.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    ++s.free_nodes;
    const int node = static_cast<int>(i);
    const double g = rows.gamma_safe(node, dt);
    const double scale = model.spec().gamma_scale[i];
    s.gamma_scaled = s.gamma_scaled || scale != 1;
    const double user = safe_user_gamma(g, scale);
    if (user < s.gamma_safe) {
      s.gamma_safe = user;
      s.gamma_node = node;
      s.row_sum = rows.row_sum(node);
    }
    const double h = rows.dt_safe(node, model.gamma[i]);
    s.gamma_over += !(model.gamma[i] < g);
    if (h < s.dt_safe) {
      s.dt_safe = h;
      s.dt_node = node;
    }
    if (model.lower_bound[i] > g) {
      s.infeasible.push_back(node);
      s.infeasible_dt.push_back(rows.dt_safe(node, model.lower_bound[i]));
    }
  }
  return s;
}

}  // namespace dampbound
