#pragma once
// Flags shared by the subcommands that run a scene: parameter overrides and scene loading.
#include <CLI/CLI.hpp>

#include <string>

#include "app/cli_words.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound::app {

/// CLI11 validators that reject NaN and infinity as well as out-of-range values.
const CLI::Validator& finite_positive();
const CLI::Validator& finite_non_negative();

/// SPEC 10's --kd --rayleigh-mass --rayleigh-stiffness on `cmd` (each >= 0, finite), into the
/// given doubles; the options come back in `opts` (for count()).
void add_damping_flags(CLI::App* cmd, double& kd, double& rayleigh_mass,
                       double& rayleigh_stiffness, CLI::Option* opts[3]);
/// Sets params' kd, rayleigh_mass, rayleigh_stiffness from the options that were given.
void apply_damping_flags(CLI::Option* const opts[3], double kd, double rayleigh_mass,
                         double rayleigh_stiffness, Params& p);

/// --m --kappa --gamma --dt --policy --factor --integrator --max-iter and SPEC 10's --kd
/// --rayleigh-mass --rayleigh-stiffness: each overrides the scene's value when given.
struct ParamFlags {
  double m = 0, kappa = 0, gamma = 0, zeta = 0, dt = 0, factor = 1;
  double kd = 0, rayleigh_mass = 0, rayleigh_stiffness = 0;
  CLI::Option *kd_opt = nullptr, *rayleigh_mass_opt = nullptr, *rayleigh_stiffness_opt = nullptr;
  std::string policy, integrator;
  int max_iter = 0;
  CLI::Option *m_opt = nullptr, *kappa_opt = nullptr, *gamma_opt = nullptr, *dt_opt = nullptr,
              *factor_opt = nullptr, *policy_opt = nullptr, *integrator_opt = nullptr,
              *max_iter_opt = nullptr, *zeta_opt = nullptr;

  /// Adds the flags to `cmd`. `with_rules` adds --max-iter. A command that words its flags
  /// its own way (bounds, suggest) adds them itself into these fields and options instead.
  void add_to(CLI::App* cmd, bool with_rules = true);
  /// Adds --kd, --rayleigh-mass and --rayleigh-stiffness (SPEC 10) alone.
  void add_damping_to(CLI::App* cmd);
  /// Overrides what was given on the command line (--gamma clears a zeta, --zeta sets one:
  /// resolve_zeta() turns it into gamma once the scene is known). Flags never added are skipped.
  void apply(Params& params, StopRules& rules) const;
  /// The SPEC 10 damping flags alone.
  void apply_damping(Params& params) const;
};

/// Adds `--zeta Z` (the nodal damping ratio, SPEC 10) to `cmd`, excluding `gamma` when given.
CLI::Option* add_zeta_option(CLI::App* cmd, double& zeta, CLI::Option* gamma = nullptr);

/// Adds `--rule first-entry|settled` (SPEC 8) to `cmd`, storing the text in `rule`;
/// `what_default` says which rule applies when the flag is not given.
CLI::Option* add_rule_option(CLI::App* cmd, std::string& rule, const std::string& what_default);
/// The rule named by add_rule_option's text (already validated by CLI11).
StopRule stop_rule_of(const std::string& text);

/// Adds `--factor-budget GFLOP` (default kDefaultFactorBudget: 200) to `cmd`: the most one
/// sparse factorisation of the exact analysis may cost before the analysis is skipped.
CLI::Option* add_factor_budget_option(CLI::App* cmd, double& gflop);

/// Parses "WxH" (e.g. 1200x700) given to `flag`; InputError naming the flag otherwise.
void parse_size(const std::string& text, const char* flag, int& width, int& height);

/// The folder of the shipped scenes: $DAMPBOUND_SCENES_DIR when set, else share/dampbound/scenes
/// beside an installed executable (found from /proc/self/exe), else the source tree's scenes/
/// (a build-tree run). "" when none exists.
std::string shipped_scenes_dir();

/// Loads a scene file; a file name without a slash that does not exist is also looked up in
/// shipped_scenes_dir(), with ".toml" appended when missing.
SceneSpec load_scene_arg(const std::string& arg);

/// InputError with magnitude_problem's line when the scene's numbers at `params` would
/// overflow an intermediate of the step or the analysis (include/dampbound/physics/model.hpp): no verdict is
/// printed beside an inf or a NaN.
void require_magnitudes(const ModelSpec& spec, const Params& params);

}  // namespace dampbound::app
