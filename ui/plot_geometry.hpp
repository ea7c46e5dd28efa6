#pragma once
// The pure pixel geometry of a plot: clipping lines and polygons to the data area, min/max
// decimation of long series and bands, dashes, splitting at sharp turns. No GL context, no
// ImGui context (ImVec2 is plain data): unit-tested in plot_geometry_test.cpp.
#include "ui/plot_math.hpp"

#include <imgui.h>

#include <vector>

namespace dampbound::ui {

/// Clips segment a-b to rect (Liang-Barsky). Returns false when it lies fully outside;
/// otherwise a and b are moved onto the clipped ends.
bool clip_segment(double& ax, double& ay, double& bx, double& by, const PixelRect& rect);

/// Maps series points to pixels and splits them into polylines: an invalid point ends a
/// polyline, each segment is clipped to `clip`, and a segment that leaves `clip` ends the
/// polyline at the border (the next visible piece starts a new one).
std::vector<std::vector<ImVec2>> project_polylines(const std::vector<double>& x,
                                                   const std::vector<double>& y,
                                                   const AxisMap& mx, const AxisMap& my,
                                                   const PixelRect& clip);

/// Min/max decimation in pixel space: each run of consecutive points within one pixel column
/// (floor(x)) becomes its first, lowest, highest and last point, in their original order, so
/// every extreme survives. Output has at most 4 points per run.
std::vector<ImVec2> decimate_columns(const std::vector<ImVec2>& pts);

/// One band sample in pixels: x, and the screen y of the lower and upper curve. The band is
/// non-empty there when lo >= hi (screen y grows downwards). NaN x: a gap.
struct BandSample {
  double x = 0.0, lo = 0.0, hi = 0.0;
};

/// Column envelope of a band: each run of consecutive samples within one pixel column
/// becomes two samples (the run's first and last x) spanning from the highest hi to the lowest
/// lo of its non-empty samples; a run with no non-empty sample stays as its first and last
/// sample. Gaps (NaN) are kept. Shows every sub-pixel spike, at most 2 samples per column.
std::vector<BandSample> decimate_band_columns(const std::vector<BandSample>& samples);

/// Clips a convex polygon to rect (Sutherland-Hodgman); the result is convex, maybe empty.
std::vector<ImVec2> clip_polygon(const std::vector<ImVec2>& poly, const PixelRect& rect);

/// Splits a polyline where it turns back by more than ~120 degrees, so that thick-line joins
/// (miters) never spike; consecutive pieces share their joint point.
std::vector<std::vector<ImVec2>> split_sharp_turns(const std::vector<ImVec2>& pts);

/// Pieces of the polyline that are "on" in a dash pattern of `on` px drawn, `off` px skipped.
std::vector<std::vector<ImVec2>> dash_polyline(const std::vector<ImVec2>& pts, float on,
                                               float off);

}  // namespace dampbound::ui
