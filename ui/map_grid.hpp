#pragma once
// The stability map's grid (GL-free): the parameter on each axis, the log window around the
// current point, its cells' trials, and running them with the batched sweep kernel
// (core/sweep/kernel.hpp). tests/ui/map_grid_test.cpp compares the cells with `sweep`.
#include <atomic>
#include <string>
#include <vector>

#include "core/sweep/kernel.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound::ui {

/// A parameter a map axis can vary (SPEC 10's dashpot and Rayleigh damping too).
enum class MapParam {
  m = 0,
  kappa = 1,
  gamma = 2,
  dt = 3,
  kd = 4,
  rayleigh_mass = 5,
  rayleigh_stiffness = 6
};
/// Every MapParam, in the order the axis menus list them.
inline constexpr MapParam kMapParams[] = {MapParam::m,  MapParam::kappa,
                                          MapParam::gamma, MapParam::dt,
                                          MapParam::kd, MapParam::rayleigh_mass,
                                          MapParam::rayleigh_stiffness};

/// True for the damping SPEC 10 adds (kd, rayleigh_mass, rayleigh_stiffness).
bool other_damping_axis(MapParam p);
/// True when `params` has dashpot or Rayleigh damping (SPEC 10).
bool has_other_damping(const Params& params);

/// "m", "kappa", "gamma", "dt", "kd", "rayleigh_mass" or "rayleigh_stiffness".
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

/// The parameters of each cell, in the order of map_trials().
std::vector<Params> map_cell_params(const Params& base, MapParam x, const std::vector<double>& xs,
                                    MapParam y, const std::vector<double>& ys);

/// Runs `trials` of `scene` (policy, integrator from `base`) with the batched kernel on the
/// calling thread. Empty when `cancel` became true. Throws std::invalid_argument when the
/// kernel cannot run the scene (batch_kernel_unsupported).
std::vector<TrialResult> run_map_trials(const SceneSpec& scene, const Params& base,
                                        const StopRules& rules,
                                        const std::vector<TrialParams>& trials,
                                        const std::atomic<bool>* cancel = nullptr);

/// The cells of a window whose axes or base have dashpot or Rayleigh damping (SPEC 10),
/// which the batched kernel does not apply: each cell through Session (the one step()), as
/// core's run_reference runs a sweep's trial. Empty when `cancel` became true.
std::vector<TrialResult> run_map_cells(const SceneSpec& scene, const std::vector<Params>& cells,
                                       const StopRules& rules,
                                       const std::atomic<bool>* cancel = nullptr);

/// Why the map cannot run `scene` at `centre` with `view`'s axes (empty: it can). Dashpot and
/// Rayleigh damping are run cell by cell (run_map_cells), not refused.
std::string map_unsupported(const SceneSpec& scene, const Params& centre, const MapView& view);
/// True when the window's cells run step() one by one (SPEC 10 damping on an axis or in the base).
bool map_runs_plain(const Params& centre, const MapView& view);

}  // namespace dampbound::ui
