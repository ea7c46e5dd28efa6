#include "core/params.hpp"

#include <cmath>

namespace dampbound {

const char* to_string(DampingPolicy p) {
  switch (p) {
    case DampingPolicy::fixed: return "fixed";
    case DampingPolicy::clamp: return "clamp";
    case DampingPolicy::upper: return "upper";
    case DampingPolicy::lower: return "lower";
    case DampingPolicy::safe: return "safe";
  }
  return "?";
}

const char* to_string(Integrator i) {
  switch (i) {
    case Integrator::semi_implicit_euler: return "semi-implicit-euler";
    case Integrator::forward_euler: return "forward-euler";
    case Integrator::verlet: return "verlet";
    case Integrator::rk4: return "rk4";
    case Integrator::implicit_euler: return "implicit-euler";
  }
  return "?";
}

std::optional<DampingPolicy> parse_policy(const std::string& s) {
  for (auto p : kPolicies)
    if (s == to_string(p)) return p;
  return std::nullopt;
}

std::optional<Integrator> parse_integrator(const std::string& s) {
  for (auto i : kIntegrators)
    if (s == to_string(i)) return i;
  return std::nullopt;
}

std::vector<std::string> policy_names() {
  std::vector<std::string> out;
  for (auto p : kPolicies) out.emplace_back(to_string(p));
  return out;
}

std::vector<std::string> integrator_names() {
  std::vector<std::string> out;
  for (auto i : kIntegrators) out.emplace_back(to_string(i));
  return out;
}

std::optional<std::string> validate(const Params& p) {
  auto positive = [](double x) { return std::isfinite(x) && x > 0; };
  if (!positive(p.m)) return "m must be a finite number > 0";
  if (!positive(p.kappa)) return "kappa must be a finite number > 0";
  if (!std::isfinite(p.gamma) || p.gamma < 0) return "gamma must be a finite number >= 0";
  if (!positive(p.dt)) return "dt must be a finite number > 0";
  if (!std::isfinite(p.kd) || p.kd < 0) return "kd must be a finite number >= 0";
  if (!std::isfinite(p.rayleigh_mass) || p.rayleigh_mass < 0)
    return "rayleigh_mass must be a finite number >= 0";
  if (!std::isfinite(p.rayleigh_stiffness) || p.rayleigh_stiffness < 0)
    return "rayleigh_stiffness must be a finite number >= 0";
  if (!std::isfinite(p.factor) || p.factor < 0) return "factor must be a finite number >= 0";
  return std::nullopt;
}

}  // namespace dampbound
