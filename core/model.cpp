#include "core/model.hpp"

#include <algorithm>
#include <cmath>

namespace dampbound {

int ModelSpec::anchor_count() const {
  return static_cast<int>(
      std::count_if(anchor_scale.begin(), anchor_scale.end(), [](double s) { return s > 0; }));
}

int add_node(ModelSpec& spec, const Vec3& position) {
  spec.rest.push_back(position);
  spec.mass_scale.push_back(1);
  spec.gamma_scale.push_back(1);
  spec.anchor_scale.push_back(0);
  spec.external_force.push_back(Vec3::Zero());
  spec.fixed.push_back(0);
  if (!spec.anchor_kd_scale.empty()) spec.anchor_kd_scale.push_back(1);
  return spec.node_count() - 1;
}

void add_spring(ModelSpec& spec, int i, int j, double kappa_scale) {
  Spring s;
  s.i = i;
  s.j = j;
  s.rest_length = (spec.rest[static_cast<size_t>(j)] - spec.rest[static_cast<size_t>(i)]).norm();
  s.kappa_scale = kappa_scale;
  spec.springs.push_back(s);
}

namespace {

/// Every per-node and per-spring value that depends on the params (SPEC 1 and 3), into the
/// model's vectors, sized here.
void apply_params(Model& model, const Params& params) {
  const size_t n = model.spec().rest.size();
  model.mass.resize(n);
  model.gamma.resize(n);
  model.anchor_kappa.resize(n);
  model.node_kappa.resize(n);
  model.lower_bound.resize(n);
  model.spring_kappa.resize(model.spec().springs.size());
  model.spring_weight.resize(model.spec().springs.size());
  model.spring_kd.resize(model.spec().springs.size());
  model.anchor_kd.resize(n);
  model.rayleigh_mass = params.rayleigh_mass;
  model.rayleigh_stiffness = params.rayleigh_stiffness;
  bool dashpots = false;
  for (size_t i = 0; i < n; ++i) {
    const double scale = model.spec().anchor_kd_scale.empty() ? 1.0 : model.spec().anchor_kd_scale[i];
    model.anchor_kd[i] = model.spec().anchor_scale[i] > 0 ? params.kd * scale : 0.0;
    dashpots = dashpots || model.anchor_kd[i] != 0;
  }
  for (size_t k = 0; k < model.spec().springs.size(); ++k) {
    model.spring_kd[k] = params.kd * model.spec().springs[k].kd_scale;
    dashpots = dashpots || model.spring_kd[k] != 0;
  }
  model.spring_damping =
      dashpots || model.rayleigh_mass != 0 || model.rayleigh_stiffness != 0;
  for (size_t i = 0; i < n; ++i) {
    model.mass[i] = params.m * model.spec().mass_scale[i];
    model.gamma[i] = params.gamma * model.spec().gamma_scale[i];
    model.anchor_kappa[i] = params.kappa * model.spec().anchor_scale[i];
    model.node_kappa[i] = model.anchor_kappa[i];
  }
  for (size_t k = 0; k < model.spec().springs.size(); ++k) {
    const Spring& s = model.spec().springs[k];
    const double kappa = params.kappa * s.kappa_scale;
    model.spring_kappa[k] = kappa;
    model.spring_weight[k] = 1.0 / std::sqrt(model.mass[static_cast<size_t>(s.i)] *
                                             model.mass[static_cast<size_t>(s.j)]);
    auto& ki = model.node_kappa[static_cast<size_t>(s.i)];
    auto& kj = model.node_kappa[static_cast<size_t>(s.j)];
    ki = std::max(ki, kappa);
    kj = std::max(kj, kappa);
  }
  // Paper eq. 5 with kappa_i = the largest stiffness incident to i (SPEC 3). A node with no
  // spring and no anchor has kappa_i = 0 and so a lower bound of 0.
  for (size_t i = 0; i < n; ++i)
    model.lower_bound[i] = 2.0 * std::sqrt(model.mass[i] * model.node_kappa[i]);
}

}  // namespace

Model compile_model(ModelSpec spec, const Params& params) {
  Model model;
  model.spec_ = std::move(spec);
  apply_params(model, params);
  const size_t n = model.spec().rest.size();
  // Incidence lists by counting sort: springs are visited in index order, so each node's
  // list is sorted. A spring from a node to itself is listed once (it has no direction).
  model.incident_offset.assign(n + 1, 0);
  for (const Spring& s : model.spec().springs) {
    ++model.incident_offset[static_cast<size_t>(s.i) + 1];
    if (s.j != s.i) ++model.incident_offset[static_cast<size_t>(s.j) + 1];
  }
  for (size_t i = 0; i < n; ++i) model.incident_offset[i + 1] += model.incident_offset[i];
  model.incident.resize(static_cast<size_t>(model.incident_offset[n]));
  std::vector<int> fill(model.incident_offset.begin(), model.incident_offset.end() - 1);
  for (int k = 0; k < model.spec().spring_count(); ++k) {
    const Spring& s = model.spec().springs[static_cast<size_t>(k)];
    model.incident[static_cast<size_t>(fill[static_cast<size_t>(s.i)]++)] = k;
    if (s.j != s.i) model.incident[static_cast<size_t>(fill[static_cast<size_t>(s.j)]++)] = ~k;
  }
  return model;
}

void reparameterise(Model& model, const Params& params) {
  apply_params(model, params);
}

ModelSpec without_springs(ModelSpec spec, const std::vector<int>& indices) {
  std::vector<std::uint8_t> cut(spec.springs.size(), 0);
  for (int k : indices)
    if (k >= 0 && k < spec.spring_count()) cut[static_cast<size_t>(k)] = 1;
  size_t kept = 0;
  for (size_t k = 0; k < spec.springs.size(); ++k)
    if (!cut[k]) spec.springs[kept++] = spec.springs[k];
  spec.springs.resize(kept);
  return spec;
}

State rest_state(const ModelSpec& spec) {
  State s;
  s.x = spec.rest;
  s.v.assign(spec.rest.size(), Vec3::Zero());
  return s;
}

}  // namespace dampbound
