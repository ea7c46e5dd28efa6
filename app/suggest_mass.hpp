#pragma once
// dampbound suggest SCENE --mass-scale DT (or --frame-dt F --substeps N): SPEC 11's added
// mass for a target step, printed, as JSON, as a scaled scene and as a ParaView file.
#include <CLI/CLI.hpp>
#include <limits>
#include <string>

#include "dampbound/run/scene.hpp"

namespace dampbound::app {

struct MassScaleArgs {
  std::string scene_arg;   ///< as given on the command line (for the lines to copy)
  double dt_target = 0;    ///< dt* (s)
  double safety = 0.9;     ///< f
  double max_added = 5;    ///< the cap (% of the free mass)
  std::string write_scene; ///< the scaled scene (TOML), "" none
  std::string vtk;         ///< one .vtu of the scaled model at rest with added_mass, "" none
  bool json = false;
  bool verify = true;
  double max_factor_flops = std::numeric_limits<double>::infinity();  ///< --factor-budget
};

/// The flags of SPEC 11 on `cmd` (suggest): --mass-scale (excludes --dt and --frame-dt alone),
/// --substeps (needs --frame-dt), and the ones that go with either (--safety,
/// --max-added-mass, --write-scene, --vtk, --json).
struct MassScaleFlags {
  CLI::Option *target = nullptr, *substeps = nullptr, *only[5] = {};
};
MassScaleFlags add_mass_scale_flags(CLI::App* cmd, MassScaleArgs& mass, int& substeps,
                                    CLI::Option* dt_opt, CLI::Option* frame_dt_opt);

/// Exit 0 for nothing to add and for an answer whose run settled; 1 over the cap, where no
/// mass helps, or where the run did not settle.
int suggest_mass_scaling(const SceneSpec& scene, const Params& params, const StopRules& rules,
                         const MassScaleArgs& args);

}  // namespace dampbound::app
