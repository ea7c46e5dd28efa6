#pragma once
// The stability map of a sweep as plain data: outcome cells over (kappa/m, zeta) or
// (kappa/m, factor) and over (m, kappa) per slice, with the paper's predicted boundary and the
// exact linear one (SPEC 7) as lines. Drawing it is the app's job (app/map_png.hpp), with the UI's
// plot widget.
#include <optional>
#include <string>
#include <vector>

#include "core/sweep/csv.hpp"

namespace dampbound {

/// What a map cell shows: the majority outcome of its trials. Under the settled rule (SPEC 8)
/// restored means settled, not_restored means never entered the band, and entered_left is a
/// trial that entered the band, then left it and was not back in at the limit.
enum class MapCell : signed char {
  empty = -1,
  restored = 0,
  not_restored = 1,
  diverged = 2,
  entered_left = 3
};

/// Which boundary a line is.
enum class MapLineKind { paper, exact_linear, dt_limit, safe };

struct MapLine {
  std::string label;
  MapLineKind kind = MapLineKind::paper;
  std::vector<double> x, y;
};

/// One heat map: cell (ix, iy) spans [x_edges[ix], x_edges[ix+1]] x [y_edges[iy],
/// y_edges[iy+1]]; cells are row-major with rows along y.
struct MapPanel {
  std::string title, x_label, y_label;
  bool x_log = false, y_log = false;
  std::vector<double> x_edges, y_edges;
  std::vector<MapCell> cells;
  std::vector<double> iterations;  ///< mean iteration of the restored (settled) trials of a cell
  std::vector<MapLine> lines;
};

struct StabilityMap {
  std::string title;
  std::vector<MapPanel> panels;
  int max_iterations = 0;            ///< the protocol's limit (restored cells are shaded up to it)
  StopRule rule = StopRule::first_entry;  ///< the rule of the sweep (SPEC 8)
  std::vector<std::string> summary;  ///< outcome counts and prediction checks
  bool side_by_side = false;         ///< panels in one row (MapOptions::axes), not the paper's layout
};

struct MapOptions {
  std::optional<double> dt;  ///< which dt to draw when the sweep has several (default: first)
  /// Panels of any two columns instead of the paper's layout: (x, y) names from
  /// map_axis_names(); every other swept column is held at trial 0's value.
  std::vector<std::pair<std::string, std::string>> axes;
  /// dashpot_stiffness_ratio() of the scene: the exact boundary of rows with dashpots.
  std::optional<double> dashpot_ratio;
  int ratio_bins = 200;      ///< log bins of kappa/m
  int grid_bins = 200;       ///< at most this many cells along m and along kappa
  int max_slices = 3;        ///< (m, kappa) panels, one per zeta or factor value
};

/// Builds the map from a sweep's rows and header. `lambda_unit` is
/// unit_stiffness_eigenvalue() of the sweep's scene (NaN: no exact linear lines).
StabilityMap build_stability_map(const SweepTable& table, double lambda_unit,
                                 const MapOptions& options = {});

/// The columns a map panel can take as an axis: m, kappa, kappa/m, gamma, zeta, dt, factor,
/// kd, rayleigh_mass, rayleigh_stiffness.
const std::vector<std::string>& map_axis_names();

}  // namespace dampbound
