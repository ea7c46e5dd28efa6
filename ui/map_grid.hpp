#pragma once
// The stability map's grid (GL-free): the parameter on each axis, the log window around the
// current point, its cells' trials, and running them with the batched sweep kernel
// (core/sweep/kernel.hpp). tests/ui/map_grid_test.cpp compares the cells with `sweep`.
#include <atomic>
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "core/sweep/kernel.hpp"

namespace dampbound::ui {

/// A parameter a map axis can vary.
enum class MapParam { m = 0, kappa = 1, gamma = 2, dt = 3 };

/// "m", "kappa", "gamma" or "dt".
const char* to_string(MapParam p);
/// The axis label with its unit, e.g. "gamma (mass unit/s)".
std::string map_axis_label(MapParam p);
/// The value of `p` in `params`, and `params` with it set.
double get_param(const Params& params, MapParam p);
void set_param(Params& params, MapParam p, double value);

/// What the map shows: two axes, and how far the window reaches around the current point.
struct MapView {
  MapParam x = MapParam::dt;     ///< horizontal axis
  MapParam y = MapParam::gamma;  ///< vertical axis
  double decades = 1.0;          ///< the window spans centre / 10^decades .. centre * 10^decades
  int finest = 32;               ///< cells per axis of the last (finest) pass
};

/// n cells on a log axis over [centre / 10^decades, centre * 10^decades]: n + 1 edges.
std::vector<double> map_log_edges(double centre, double decades, int n);
/// The geometric centre of each cell (sqrt of its edges' product): the value a cell's trial
/// runs with.
std::vector<double> map_cell_centres(const std::vector<double>& edges);

/// The trials of a grid: `base` with the x axis set to xs[ix] and the y axis to ys[iy]; row
/// major with rows along y (cell = iy * xs.size() + ix), as MapPanel cells.
std::vector<TrialParams> map_trials(const Params& base, MapParam x, const std::vector<double>& xs,
                                    MapParam y, const std::vector<double>& ys);

/// Runs `trials` of `scene` (policy, integrator from `base`) with the batched kernel on the
/// calling thread. Empty when `cancel` became true. Throws std::invalid_argument when the
/// kernel cannot run the scene (batch_kernel_unsupported).
std::vector<TrialResult> run_map_trials(const SceneSpec& scene, const Params& base,
                                        const StopRules& rules,
                                        const std::vector<TrialParams>& trials,
                                        const std::atomic<bool>* cancel = nullptr);

}  // namespace dampbound::ui
