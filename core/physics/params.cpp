#include "dampbound/physics/params.hpp"

#include <cmath>
#include <stdexcept>

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

bool uses_user_gamma(DampingPolicy p) {
  switch (p) {
    case DampingPolicy::fixed:
    case DampingPolicy::clamp:
    case DampingPolicy::safe: return true;
    case DampingPolicy::upper:
    case DampingPolicy::lower: return false;
  }
  return true;
}

const IntegratorTraits& integrator_traits(Integrator i) {
  for (const IntegratorTraits& t : kIntegratorTable)
    if (t.id == i) return t;
  throw std::invalid_argument("integrator " + std::to_string(static_cast<int>(i)) +
                              " has no row in params.hpp's kIntegratorTable");
}

const char* to_string(Integrator i) {
  for (const IntegratorTraits& t : kIntegratorTable)
    if (t.id == i) return t.name;
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

std::string one_of(const std::vector<std::string>& names) {
  std::string out;
  for (size_t k = 0; k < names.size(); ++k)
    out += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
  return out;
}

std::optional<std::string> number_problem(double x, bool allow_zero) {
  if (!std::isfinite(x)) return std::string("must be finite");
  if (allow_zero ? x < 0 : x <= 0) return std::string(allow_zero ? "must be >= 0" : "must be > 0");
  return std::nullopt;
}

std::optional<std::string> validate(const Params& p) {
  const struct {
    const char* name;
    double value;
    bool allow_zero;
  } numbers[] = {{"m", p.m, false},         {"kappa", p.kappa, false},
                 {"gamma", p.gamma, true},  {"dt", p.dt, false},
                 {"factor", p.factor, true},   {"kd", p.kd, true},
                 {"rayleigh_mass", p.rayleigh_mass, true},
                 {"rayleigh_stiffness", p.rayleigh_stiffness, true}};
  for (const auto& n : numbers)
    if (const auto why = number_problem(n.value, n.allow_zero)) return std::string(n.name) + " " + *why;
  if (p.zeta)
    if (const auto why = number_problem(*p.zeta, true)) return "zeta " + *why;
  return std::nullopt;
}

}  // namespace dampbound
