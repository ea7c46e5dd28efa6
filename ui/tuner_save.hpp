#pragma once
// The tuner's "Save as scene" (GL-free): the current scene with the current parameters, each
// pinned run as a [[run]] table and what each measured as an [[expect]] entry, written as
// TOML that `dampbound check FILE` replays headless. Also the scripted pins of
// `dampbound gui --pin`.
#include <string>
#include <vector>

#include "core/io/scene_write.hpp"
#include "ui/tuner.hpp"

namespace dampbound::ui {

/// The scene Save writes: the tuner's scene (its geometry, perturbations, protocol and cuts)
/// with the current parameters as [params]; each pin of this scene as a [[run]] labelled with
/// its name (made unique); an [[expect]] per pin and one for the current run, under the
/// tuner's verdict rule (the settled rule of SPEC 8). A run that is
/// replayable (Tuner::replayable) and has a verdict keeps its measured result; any other is
/// replayed headless to its verdict (one line in *notes says so). The source file's own
/// [[run]] and [[expect]] tables are replaced.
SceneSpec tuner_saved_scene(const Tuner& tuner, const ExpectTolerance& tolerance,
                            std::vector<std::string>* notes = nullptr);

/// Writes tuner_saved_scene() to `path` atomically (the folder must exist), with a header
/// comment saying how to check it. Returns a one-line summary. Throws InputError naming the
/// path when it cannot be written.
std::string save_tuner_scene(const Tuner& tuner, const std::string& path,
                             const ExpectTolerance& tolerance,
                             std::vector<std::string>* notes = nullptr);

/// A pin asked for on the command line (`--pin gamma=0.0005,dt=0.1`).
struct PinRequest {
  std::string name;    ///< "" = params_label()
  Params params;       ///< the run's parameters
  int max_iterations;  ///< the run's iteration limit
};

/// Parses "KEY=VALUE[,KEY=VALUE...]" over `base` (keys m, kappa, gamma, dt, policy, factor,
/// integrator, max_iterations, name). Throws InputError naming `flag` on a bad key or value.
PinRequest parse_pin_request(const std::string& text, const Params& base, int max_iterations,
                             const std::string& flag = "--pin");

/// Runs `request` from the scene's start to its verdict (or the trace cap), pins it, and puts
/// the tuner back on its own parameters at the start. Returns the pin.
Pin& pin_run(Tuner& tuner, const PinRequest& request);

}  // namespace dampbound::ui
