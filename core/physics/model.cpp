#include "dampbound/physics/model.hpp"

#include <algorithm>
#include <cmath>
#include <locale>
#include <sstream>

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

namespace {

constexpr double kSmallest = 1e-150, kLargest = 1e150;

std::string shown(double x) {  // locale-free: a host's setlocale must not give "1,5e-200"
  std::ostringstream text;
  text.imbue(std::locale::classic());
  text.precision(6);
  text << x;
  return text.str();
}

/// A coefficient that may be 0 (allow_zero) or must be positive, inside [kSmallest, kLargest].
bool representable(double x, bool allow_zero) {
  if (allow_zero && x == 0) return true;
  return std::isfinite(x) && x >= kSmallest && x <= kLargest;
}

}  // namespace

std::optional<std::string> magnitude_problem(const Model& model, double dt) {
  const std::string range = " (dampbound keeps every number within 1e-150 .. 1e150 so that no "
                            "intermediate overflows; only ratios matter: change units)";
  if (!representable(dt, false)) return "dt = " + shown(dt) + " is out of range" + range;
  const struct {
    const char* name;
    double value;
  } uniform[] = {{"rayleigh_mass (alpha)", model.rayleigh_mass},
                 {"rayleigh_stiffness (beta)", model.rayleigh_stiffness}};
  for (const auto& u : uniform)
    if (!representable(u.value, true))
      return std::string(u.name) + " = " + shown(u.value) + " is out of range" + range;
  if (!(model.rayleigh_mass * dt <= kLargest))
    return "rayleigh_mass * dt = " + shown(model.rayleigh_mass * dt) +
           " overflows the step's terms: lower rayleigh_mass or dt" + range;
  for (size_t i = 0; i < model.mass.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    const std::string node = "node " + std::to_string(i) + "'s ";
    const double m = model.mass[i];
    if (!representable(m, false))
      return node + "mass " + shown(m) + " is out of range: change m or the node's mass scale" +
             range;
    if (!representable(model.gamma[i], true))
      return node + "gamma " + shown(model.gamma[i]) + " is out of range: change gamma or zeta" +
             range;
    if (!representable(model.node_kappa[i], true))
      return node + "stiffness " + shown(model.node_kappa[i]) +
             " is out of range: change kappa or the stiffness scales" + range;
    const struct {
      const char* what;
      double rate;
      const char* change;
    } rates[] = {{"kappa_i/m_i", model.node_kappa[i] / m, "kappa or m"},
                 {"gamma_i/m_i", model.gamma[i] / m, "gamma (zeta) or m"},
                 {"kd_a/m_i", model.anchor_kd[i] / m, "kd or m"},
                 {"beta kappa_i/m_i", model.rayleigh_stiffness * model.node_kappa[i] / m,
                  "rayleigh_stiffness"}};
    for (const auto& r : rates)
      if (!(r.rate <= kLargest && r.rate * dt <= kLargest && r.rate * dt * dt <= kLargest))
        return node + r.what + " = " + shown(r.rate) + " (times dt = " + shown(r.rate * dt) +
               ") overflows the step's terms: change " + r.change + " or dt" + range;
  }
  for (size_t k = 0; k < model.spring_kd.size(); ++k) {
    const std::string spring = "spring " + std::to_string(k) + "'s ";
    if (!representable(model.spring_kappa[k], false))
      return spring + "stiffness " + shown(model.spring_kappa[k]) +
             " is out of range: change kappa or its scale" + range;
    if (!representable(model.spring_kd[k], true))
      return spring + "dashpot kd " + shown(model.spring_kd[k]) +
             " is out of range: change kd or its scale" + range;
    const double w = model.spring_weight[k];
    if (!(w <= kLargest && model.spring_kd[k] * w * dt <= kLargest))
      return spring + "weight 1/sqrt(m_i m_j) = " + shown(w) +
             " overflows: change m or the mass scales of its nodes" + range;
  }
  return std::nullopt;
}

State rest_state(const ModelSpec& spec) {
  State s;
  s.x = spec.rest;
  s.v.assign(spec.rest.size(), Vec3::Zero());
  return s;
}

}  // namespace dampbound
