#include "core/model.hpp"

#include <algorithm>
#include <cmath>

namespace dampbound {

int Model::anchor_count() const {
  return static_cast<int>(
      std::count_if(anchor_scale.begin(), anchor_scale.end(), [](double s) { return s > 0; }));
}

int add_node(Model& model, const Vec3& position) {
  model.rest.push_back(position);
  model.mass_scale.push_back(1);
  model.gamma_scale.push_back(1);
  model.anchor_scale.push_back(0);
  model.external_force.push_back(Vec3::Zero());
  model.fixed.push_back(0);
  return model.node_count() - 1;
}

void add_spring(Model& model, int i, int j, double kappa_scale) {
  Spring s;
  s.i = i;
  s.j = j;
  s.rest_length = (model.rest[static_cast<size_t>(j)] - model.rest[static_cast<size_t>(i)]).norm();
  s.kappa_scale = kappa_scale;
  model.springs.push_back(s);
}

void set_params(Model& model, const Params& params) {
  const size_t n = model.rest.size();
  model.mass.resize(n);
  model.gamma.resize(n);
  model.anchor_kappa.resize(n);
  model.node_kappa.assign(n, 0.0);
  model.lower_bound.resize(n);
  for (size_t i = 0; i < n; ++i) {
    model.mass[i] = params.m * model.mass_scale[i];
    model.gamma[i] = params.gamma * model.gamma_scale[i];
    model.anchor_kappa[i] = params.kappa * model.anchor_scale[i];
    model.node_kappa[i] = model.anchor_kappa[i];
  }
  for (Spring& s : model.springs) {
    s.kappa = params.kappa * s.kappa_scale;
    auto& ki = model.node_kappa[static_cast<size_t>(s.i)];
    auto& kj = model.node_kappa[static_cast<size_t>(s.j)];
    ki = std::max(ki, s.kappa);
    kj = std::max(kj, s.kappa);
  }
  // Paper eq. 5 with kappa_i = the largest stiffness incident to i (SPEC 3). A node with no
  // spring and no anchor has kappa_i = 0 and so a lower bound of 0.
  for (size_t i = 0; i < n; ++i)
    model.lower_bound[i] = 2.0 * std::sqrt(model.mass[i] * model.node_kappa[i]);
}

void remove_springs(Model& model, std::vector<int> indices, const Params& params) {
  std::sort(indices.begin(), indices.end());
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
  for (auto it = indices.rbegin(); it != indices.rend(); ++it)
    if (*it >= 0 && *it < model.spring_count())
      model.springs.erase(model.springs.begin() + *it);
  set_params(model, params);
}

State rest_state(const Model& model) {
  State s;
  s.x = model.rest;
  s.v.assign(model.rest.size(), Vec3::Zero());
  return s;
}

}  // namespace dampbound
