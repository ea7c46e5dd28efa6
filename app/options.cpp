#include "app/options.hpp"

#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "core/analysis/linear_stability_exact.hpp"
#include "core/io/format.hpp"
#include "core/io/scene_file.hpp"
#include "dampbound/physics/error.hpp"

#ifndef DAMPBOUND_SOURCE_DIR
#define DAMPBOUND_SOURCE_DIR "."
#endif
#ifndef DAMPBOUND_SCENES_FROM_BIN
#define DAMPBOUND_SCENES_FROM_BIN "../share/dampbound/scenes"
#endif

namespace dampbound::app {

namespace {
CLI::Validator number_check(bool allow_zero) {
  return CLI::Validator(
      [allow_zero](std::string& s) -> std::string {
        // strtod, not stod: stod throws on a number that underflows (1e-320), which would
        // be reported as "not a number".
        errno = 0;
        char* end = nullptr;
        const double x = std::strtod(s.c_str(), &end);
        if (s.empty() || end != s.c_str() + s.size() || std::isspace(static_cast<unsigned char>(s[0])))
          return "'" + printable(s) + "' is not a number";
        // number_problem: the same rule and words as the API's validate(Params).
        if (errno == ERANGE && std::fabs(x) > 1) return "must be finite, got " + printable(s);
        if (const auto why = number_problem(x, allow_zero))
          return *why + (std::isfinite(x) ? "" : ", got " + printable(s));
        if (x != 0 && std::fabs(x) < 1e-300)
          return "'" + printable(s) + "' is too small to compute with (below 1e-300)";
        return {};
      },
      allow_zero ? "NUMBER>=0" : "NUMBER>0");
}
}  // namespace

const CLI::Validator& finite_positive() {
  static const CLI::Validator v = number_check(false);
  return v;
}
const CLI::Validator& finite_non_negative() {
  static const CLI::Validator v = number_check(true);
  return v;
}

void add_damping_flags(CLI::App* cmd, double& kd, double& rayleigh_mass,
                       double& rayleigh_stiffness, CLI::Option* opts[3]) {
  opts[0] = cmd->add_option("--kd", kd,
                            "dashpot along every spring and anchor, kd_ij = kd * kd_scale "
                            "(mass unit/s)")
                ->check(finite_non_negative());
  opts[1] = cmd->add_option("--rayleigh-mass", rayleigh_mass,
                            "Rayleigh alpha: force -alpha m_i v_i (1/s)")
                ->check(finite_non_negative());
  opts[2] = cmd->add_option("--rayleigh-stiffness", rayleigh_stiffness,
                            "Rayleigh beta: force -beta (K(x) v)_i (s)")
                ->check(finite_non_negative());
}

void apply_damping_flags(CLI::Option* const opts[3], double kd, double rayleigh_mass,
                         double rayleigh_stiffness, Params& p) {
  if (opts[0] && opts[0]->count()) p.kd = kd;
  if (opts[1] && opts[1]->count()) p.rayleigh_mass = rayleigh_mass;
  if (opts[2] && opts[2]->count()) p.rayleigh_stiffness = rayleigh_stiffness;
}

void ParamFlags::add_to(CLI::App* cmd, bool with_rules) {
  m_opt = cmd->add_option("--m", m, "node mass (mass unit; all nodes, times their mass_scale)")
              ->check(finite_positive());
  kappa_opt = cmd->add_option("--kappa", kappa, "spring and anchor stiffness (mass unit/s^2)")
                  ->check(finite_positive());
  gamma_opt = cmd->add_option("--gamma", gamma, "user's viscous damping (mass unit/s)")
                  ->check(finite_non_negative());
  zeta_opt = add_zeta_option(cmd, zeta, gamma_opt);
  dt_opt = cmd->add_option("--dt", dt, "time step (s)")->check(finite_positive());
  policy_opt = cmd->add_option("--policy", policy, "damping policy: fixed, clamp, upper, lower (the paper's), safe (the safe bound)")
                   ->check(CLI::IsMember(policy_names()));
  factor_opt = cmd->add_option("--factor", factor, "multiplier of the upper bound for --policy upper")
                   ->check(finite_non_negative());
  integrator_opt =
      cmd->add_option("--integrator", integrator, "time integrator (default: the paper's)")
          ->check(CLI::IsMember(integrator_names()));
  add_damping_to(cmd);
  if (with_rules)
    max_iter_opt = cmd->add_option("--max-iter", max_iter, "iteration limit of the protocol")
                       ->check(whole_range(1, 100000000));
}

void ParamFlags::add_damping_to(CLI::App* cmd) {
  CLI::Option* damping[3] = {};
  add_damping_flags(cmd, kd, rayleigh_mass, rayleigh_stiffness, damping);
  kd_opt = damping[0], rayleigh_mass_opt = damping[1], rayleigh_stiffness_opt = damping[2];
}

void ParamFlags::apply_damping(Params& p) const {
  CLI::Option* const damping[3] = {kd_opt, rayleigh_mass_opt, rayleigh_stiffness_opt};
  apply_damping_flags(damping, kd, rayleigh_mass, rayleigh_stiffness, p);
}

void ParamFlags::apply(Params& p, StopRules& rules) const {
  if (m_opt && m_opt->count()) p.m = m;
  if (kappa_opt && kappa_opt->count()) p.kappa = kappa;
  if (gamma_opt && gamma_opt->count()) {
    p.gamma = gamma;
    p.zeta.reset();
  }
  if (zeta_opt && zeta_opt->count()) p.zeta = zeta;
  if (dt_opt && dt_opt->count()) p.dt = dt;
  if (factor_opt && factor_opt->count()) p.factor = factor;
  if (policy_opt && policy_opt->count()) p.policy = *parse_policy(policy);
  if (integrator_opt && integrator_opt->count()) p.integrator = *parse_integrator(integrator);
  apply_damping(p);
  if (max_iter_opt && max_iter_opt->count()) rules.max_iterations = max_iter;
}

CLI::Option* add_zeta_option(CLI::App* cmd, double& zeta, CLI::Option* gamma) {
  CLI::Option* o = cmd->add_option("--zeta", zeta,
                                   "nodal damping ratio in place of --gamma: gamma_i = zeta * 2 "
                                   "sqrt(m_i kappa_i) at each node (kappa_i its stiffest spring "
                                   "or anchor; 1 = the lower bound of eq. 5)")
                       ->check(finite_non_negative());
  if (gamma) o->excludes(gamma);
  return o;
}

CLI::Option* add_rule_option(CLI::App* cmd, std::string& rule, const std::string& what_default) {
  return cmd
      ->add_option("--rule", rule,
                   "verdict rule: first-entry = the paper's, restored at the first "
                   "iteration below the 1% band; settled = step to the limit, settled only "
                   "where it stays below from some iteration on (" +
                       what_default + ")")
      ->check(CLI::IsMember({"first-entry", "settled"}));
}

CLI::Option* add_factor_budget_option(CLI::App* cmd, double& gflop) {
  gflop = kDefaultFactorBudget / 1e9;
  return cmd
      ->add_option("--factor-budget", gflop,
                   "the most one sparse factorisation of the exact analysis may take, in GFlop "
                   "(CHOLMOD's prediction, before any is done; SPEC 10's damped limits, the "
                   "ceilings, the Rayleigh pair and mass scaling too); over it the exact rows report "
                   "only what Lanczos, Gershgorin, the node-block splitting and a patch around the "
                   "top prove without one (default 200: ~25 s per "
                   "factorisation on 2 cores)")
      ->check(finite_positive());
}

StopRule stop_rule_of(const std::string& text) {
  return parse_stop_rule(text).value_or(StopRules{}.rule);
}

void parse_size(const std::string& text, const char* flag, int& width, int& height) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  // %5d: a longer number could overflow int (4294967360 would read as 64).
  if (std::sscanf(text.c_str(), "%5d%c%5d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 64 ||
      h < 64 || w > 8192 || h > 8192)
    throw InputError(std::string(flag) + ": '" + printable(text) +
                     "' is not a size WxH with each side in 64..8192");
  width = w;
  height = h;
}

std::string shipped_scenes_dir() {
  auto is_dir = [](const std::string& d) { return !d.empty() && ::access(d.c_str(), F_OK) == 0; };
  if (const char* env = std::getenv("DAMPBOUND_SCENES_DIR"); env && is_dir(env)) return env;
  // An installed dampbound: <prefix>/bin/dampbound finds <prefix>/share/dampbound/scenes.
  char exe[4096];
  const ssize_t len = ::readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (len > 0) {
    const std::string path(exe, static_cast<size_t>(len));
    const std::string installed =
        std::filesystem::path(path.substr(0, path.rfind('/') + 1) + DAMPBOUND_SCENES_FROM_BIN)
            .lexically_normal()
            .string();
    if (is_dir(installed)) return installed;
  }
  const std::string source = std::string(DAMPBOUND_SOURCE_DIR) + "/scenes";
  return is_dir(source) ? source : std::string();
}

SceneSpec load_scene_arg(const std::string& arg) {
  return load_scene(resolve_scene(arg, shipped_scenes_dir()));
}

void require_magnitudes(const ModelSpec& spec, const Params& params) {
  if (const auto why = magnitude_problem(compile_model(spec, params), params.dt))
    throw InputError(*why);
}

}  // namespace dampbound::app
