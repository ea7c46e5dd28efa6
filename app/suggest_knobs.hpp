#pragma once
// suggest --kappa-max and suggest --rayleigh: the stiffness ceilings and the Rayleigh pair from
// the spectrum (core/analysis/kappa_ceiling.hpp, rayleigh_design.hpp), and the stable range of
// each SPEC 10 damping kind (damping_limits.hpp), printed for people.
#include <string>

#include "core/analysis/rayleigh_design.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound::app {

/// --kappa-max: the factor ceiling of every stiffness and of each region, each run at 0.98x and
/// 1.02x (unless !verify), and the contact ceilings (into `vtu` as contact_stiffness_max when
/// given). Exit 1 when a run at 0.98x does not settle. `max_factor_flops` (--factor-budget):
/// FactorisationOverBudget before any factorisation over it.
int print_kappa_max(const SceneSpec& scene, const Params& params, const StopRules& rules,
                    bool verify, const std::string& vtu, double max_factor_flops);

/// --rayleigh Z[,Z2] [--band F1:F2] [--plot FILE.png]: exit 1 when no non-negative pair gives
/// the ratios or the pair is unstable at the scene's dt. `max_factor_flops` as above.
int print_rayleigh(const SceneSpec& scene, const Params& params, const std::string& ratios,
                   const std::string& band, const std::string& plot, double max_factor_flops);

/// SPEC 10: the exact stable range of each damping kind at params.dt, the others held, and a
/// run at the middle of each range (unless !verify); a kind over `max_factor_flops` says so.
void print_damping_kinds(const SceneSpec& scene, const Params& params, const StopRules& rules,
                         bool verify, double max_factor_flops);

/// Renders zeta(f) to a PNG; set where the headless EGL host is built (cmd_ui_rayleigh_plot.cpp),
/// null otherwise. Returns the renderer's name.
using RayleighPlotter = std::string (*)(const RayleighDesign& design, const std::string& path);
RayleighPlotter& rayleigh_plotter();

}  // namespace dampbound::app
