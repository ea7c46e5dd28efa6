#pragma once
// The stability map's boundary lines (GL-free): the paper's lower bound (eq. 5), the exact
// linear limit (SPEC 7) and the safe bound (SPEC 9), each solved for one axis of the map's
// window along the other (tests/ui/map_bounds_test.cpp).
#include <vector>

#include "core/sweep/map.hpp"
#include "core/sweep/safe_edge.hpp"
#include "ui/map_grid.hpp"

namespace dampbound::ui {

/// The boundary lines of the window: the paper's lower bound gamma = 2 C sqrt(m kappa) with
/// C the worst node's sqrt(mass_scale * kappa_scale) / gamma_scale (eq. 5, SPEC 3), and, when
/// every free node has the same gamma_scale / mass_scale = r, the exact linear limit of the
/// paper's step lambda_unit kappa dt^2 + 2 r gamma dt = 4 m (SPEC 7; lambda_unit from
/// unit_stiffness_eigenvalue). Each is solved for one axis along the other, sampled on
/// `samples` log points.
struct MapBoundConstants {
  double lower = 0;        ///< C above (NaN: no node has a lower bound)
  double lambda_unit = 0;  ///< lambda_max at m = kappa = 1 (1/s^2); NaN: no exact line
  double rate_ratio = 1;   ///< r above; NaN when it differs between nodes
  SafeUnit safe;           ///< SPEC 9's row sums at rest (the safe bound's line; any scene)
};
MapBoundConstants map_bound_constants(const SceneSpec& scene);
std::vector<MapLine> map_bound_lines(const MapBoundConstants& k, const Params& base,
                                     const MapView& view, const std::vector<double>& x_edges,
                                     const std::vector<double>& y_edges, int samples = 200);

}  // namespace dampbound::ui
