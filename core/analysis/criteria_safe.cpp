#include "core/analysis/criteria_safe.hpp"
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// The per-node safe bound of SPEC 9 as criteria rows, beside the paper's and the exact ones.
#include <algorithm>
#include <cmath>
#include <string>

#include "core/analysis/criteria.hpp"
#include "core/io/format.hpp"
#include "core/physics/integrate.hpp"
#include "core/physics/safe_bound.hpp"

namespace dampbound {
namespace {

/// "; ratio to the exact limit r" when the exact analysis is the paper's step's.
std::string ratio_text(double safe, double exact, const ExactStability* e) {
  if (!e || !integrator_traits(e->integrator).paper_step || !std::isfinite(exact) ||
      exact == 0)
    return "";
  return "; " + format_human(safe / exact) + " of the exact limit " + format_human(exact);
}

}  // namespace

std::string safe_bound_scope(Integrator integrator) {
  if (integrator_traits(integrator).paper_step) return "";
  return std::string("derived for the paper's semi-implicit step, it guarantees nothing under ") +
         to_string(integrator);
}

std::vector<CriterionResult> safe_criteria(const Model& model, const State& state,
                                           const Params& params, const ExactStability* exact) {
  const SafeBoundSummary s = safe_bound_summary(model, state.x, params.dt);
  std::vector<CriterionResult> out;
  if (s.free_nodes == 0) return out;
  // With a compressed spring K may be indefinite: the motion itself can be unstable and no
  // damping bound helps (SPEC 9). Say so instead of a verdict.
  // SPEC 9 is derived for the paper's step (Q = 4I - 2dt C - dt^2 A). Under another
  // integrator the same numbers promise nothing: forward Euler, for one, grows at any dt when
  // a mode is undamped, and every gamma_i < gamma_safe_i allows that. Shown for reference.
  const bool paper_step = integrator_traits(params.integrator).paper_step;
  const bool no_guarantee = s.compressed_springs > 0 || !paper_step;
  std::string caveat =
      s.compressed_springs > 0
          ? "; " + std::to_string(s.compressed_springs) +
                " compressed springs: K may not be positive semi-definite, no guarantee"
          : "";
  if (!paper_step) caveat += "; " + safe_bound_scope(params.integrator);
  const CriterionVerdict unknown = CriterionVerdict::not_applicable;

  CriterionResult g;
  g.name = "safe damping bound";
  g.source = "safe bound (Gershgorin on Q = 4I - 2dt C - dt^2 A)";
  g.formula = "gamma_i < gamma_safe_i = 2 m_i/dt - m_i dt R_i / 2, R_i = max row sum of |A|";
  g.unit = "mass unit/s";
  g.value = s.gamma_safe;
  g.node = s.gamma_node;
  const int over = s.gamma_over;
  g.verdict = no_guarantee ? unknown : verdict_of(over == 0);
  g.test = std::to_string(over) + " of " + plural(s.free_nodes, "node") +
           " with gamma_i >= gamma_safe_i; smallest gamma_safe " +
           format_human(s.gamma_safe) +
           (s.gamma_scaled ? " (the user's gamma, gamma_i = gamma * gamma_scale_i)" : "") +
           " at node " + std::to_string(s.gamma_node) + " (R = " + format_human(s.row_sum) +
           ")" + ratio_text(s.gamma_safe, exact ? exact->gamma_hi : NAN, exact) + caveat;
  out.push_back(g);

  CriterionResult d;
  d.name = "safe dt bound";
  d.source = "safe bound";
  d.formula = "dt < dt_safe_i = (sqrt(c_i^2 + 4 R_i) - c_i) / R_i, c_i = gamma_i/m_i";
  d.unit = "s";
  d.value = s.dt_safe;
  d.node = s.dt_node;
  d.verdict = no_guarantee ? unknown : verdict_of(params.dt < s.dt_safe);
  d.test = "dt = " + format_human(params.dt) + (params.dt < s.dt_safe ? " < " : " >= ") + "dt_safe = " +
           format_human(s.dt_safe) + " (node " + std::to_string(s.dt_node) + ")" +
           ratio_text(s.dt_safe, exact ? exact->dt_max : NAN, exact) + caveat;
  out.push_back(d);

  CriterionResult c;
  c.name = "safe check: critical damping";
  c.source = "safe bound";
  c.formula = "critical damping guaranteed at node i when gamma_lo_i <= gamma_safe_i";
  c.unit = "nodes";
  c.value = static_cast<double>(s.infeasible.size());
  c.verdict = no_guarantee ? unknown : verdict_of(s.infeasible.empty());
  if (s.infeasible.empty()) {
    c.test = "gamma_lo_i <= gamma_safe_i at every free node";
  } else {
    c.node = s.infeasible.front();
    double dt_min = s.infeasible_dt.front();
    for (double h : s.infeasible_dt) dt_min = std::min(dt_min, h);
    c.test = std::to_string(s.infeasible.size()) + " of " + plural(s.free_nodes, "node") +
             " with gamma_lo > gamma_safe (first: node " + std::to_string(c.node) +
             ", feasible at dt < " + format_human(s.infeasible_dt.front()) + "); all at dt < " +
             format_human(dt_min);
  }
  c.test += caveat;
  out.push_back(c);
  return out;
}

}  // namespace dampbound
