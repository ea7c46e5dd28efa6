#pragma once
// The nodal damping ratio (SPEC 10): zeta_i = gamma_i / (2 sqrt(m_i kappa_i)), the user's
// gamma_i over the lower bound of paper eq. 5 with kappa_i as SPEC 3 defines it. Reported beside
// gamma, and accepted as input in its place (Params::zeta).
#include <limits>
#include <vector>

#include "dampbound/physics/model.hpp"

namespace dampbound {

/// zeta = gamma / gamma_lo for one node; NaN where gamma_lo = 0 (no spring and no anchor).
inline double damping_ratio(double gamma, double lower_bound) {
  return lower_bound > 0 ? gamma / lower_bound : std::numeric_limits<double>::quiet_NaN();
}

/// zeta_i = gamma_i / gamma_lo_i at every node (the user's gamma_i, before the policy); NaN
/// where gamma_lo_i = 0 (a node with no spring and no anchor has no ratio).
std::vector<double> damping_ratio(const Model& model);

/// The smallest and largest zeta_i over the free nodes that have one (NaN when none has).
struct DampingRatioRange {
  double min = 0, max = 0;
  bool uniform() const { return min == max; }
};
DampingRatioRange damping_ratio_range(const Model& model);

/// Turns a damping ratio given as input (params.zeta) into the gamma every downstream function
/// reads, so that gamma_i = zeta * 2 sqrt(m_i kappa_i) * gamma_scale_i at each node:
/// gamma_scale_i is multiplied by sqrt(mass_scale_i * kappa_scale_i), the node's lower bound
/// relative to 2 sqrt(m kappa) (kappa_i/kappa from the largest incident stiffness, SPEC 3), and
/// params.gamma = zeta * 2 sqrt(m kappa). params.zeta is cleared. Nothing happens without a zeta.
/// Call it once, after every override of m and kappa: a later change of m or kappa moves the
/// ratio (gamma_of_zeta() gives the gamma that keeps it).
void resolve_zeta(ModelSpec& spec, Params& params);

/// params.gamma = zeta * 2 sqrt(m kappa) and params.zeta cleared, for a spec that
/// resolve_zeta(spec, params) has already scaled (a scene's runs, or m and kappa set later).
void resolve_zeta(Params& params);

/// The uniform gamma that gives the ratio zeta on a model resolved by resolve_zeta():
/// zeta * 2 sqrt(m kappa).
double gamma_of_zeta(double zeta, const Params& params);

}  // namespace dampbound
