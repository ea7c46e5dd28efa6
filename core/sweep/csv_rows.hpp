#pragma once
// The rows of a sweep CSV checked against the sweep its header names: a row edited under an
// intact header (a value, an outcome, a class's shared result) is refused before a merge
// joins it into a file that looks whole.
#include <optional>
#include <string>

#include "core/sweep/csv.hpp"
#include "core/sweep/grid.hpp"

namespace dampbound {

/// The grid a header's definition describes (its axes read back with parse_axis); InputError
/// naming `path` when the definition is not one this build writes.
SweepGrid grid_of_header(const SweepHeader& header, const std::string& path);

/// Checks every row of `table` (read with keep_lines) against its header: the trial's
/// parameters are the grid's at that index (m, kappa, gamma, zeta, dt, policy, factor and the
/// damping axes, read back to the same double), the class is below the header's count, the
/// trials of one class carry one result with ran = 1 at its first trial only, and the
/// outcome agrees with the band of the definition (restored or settled below it, not
/// restored or not settled at the iteration limit and not above the divergence threshold). Throws InputError
/// naming `path` and the trial.
void check_sweep_rows(const SweepTable& table, const std::string& path);

}  // namespace dampbound
