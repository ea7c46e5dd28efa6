#include "core/sweep/safe_edge.hpp"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/io/format.hpp"
#include "core/physics/safe_bound.hpp"
#include "core/sweep/summary.hpp"
#include "dampbound/physics/bounds.hpp"

namespace dampbound {

SafeUnit unit_safe_bound(const SceneSpec& scene) {
  Params p = scene.params;
  p.m = 1;
  p.kappa = 1;
  const Model model = compile_model(scene.model, p);
  std::vector<double> R;
  safe_row_sums(model, model.spec().rest, R);
  SafeUnit u;
  for (size_t i = 0; i < R.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    u.mass_scale.push_back(model.spec().mass_scale[i]);
    u.gamma_scale.push_back(model.spec().gamma_scale[i]);
    u.row_sum.push_back(R[i]);
  }
  return u;
}

namespace {

/// gamma_safe_i at (m, kappa, dt) from the unit row sums (SPEC 9).
double node_safe(const SafeUnit& u, size_t i, double m, double kappa, double dt) {
  return safe_gamma(m * u.mass_scale[i], dt, u.row_sum[i] * kappa / m);
}

std::string pct(std::uint64_t a, std::uint64_t b) {
  char buf[32];
  c_snprintf(buf, sizeof buf, "%.1f%%", b ? 100.0 * static_cast<double>(a) / static_cast<double>(b) : 0.0);
  return buf;
}

}  // namespace

double safe_edge(const SafeUnit& u, SafeAxis axis, double m, double kappa, double gamma,
                 double dt) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const bool lowest = axis == SafeAxis::m;  // m has a lower edge, the others an upper one
  double edge = lowest ? 0.0 : std::numeric_limits<double>::infinity();
  bool any = false;
  for (size_t i = 0; i < u.row_sum.size(); ++i) {
    const double ms = u.mass_scale[i], gs = u.gamma_scale[i], R = u.row_sum[i];
    double e = nan;  // node i's own edge
    switch (axis) {
      case SafeAxis::gamma:
        if (gs > 0) e = (2 * m * ms / dt - ms * dt * R * kappa / 2) / gs;
        break;
      case SafeAxis::m:
        e = (gamma * gs + ms * dt * R * kappa / 2) * dt / (2 * ms);
        break;
      case SafeAxis::kappa:
        if (R > 0) e = (2 * m * ms / dt - gamma * gs) * 2 / (ms * dt * R);
        break;
      case SafeAxis::dt: {
        // a dt^2 + b dt - c < 0 with a = ms R kappa / 2, b = gamma gs, c = 2 m ms.
        const double a = ms * R * kappa / 2, b = gamma * gs, c = 2 * m * ms;
        e = a > 0 ? (-b + std::sqrt(b * b + 4 * a * c)) / (2 * a) : (b > 0 ? c / b : nan);
        break;
      }
    }
    if (std::isnan(e)) continue;  // this node does not bound the parameter
    any = true;
    edge = lowest ? std::max(edge, e) : std::min(edge, e);
  }
  return any && edge > 0 && std::isfinite(edge) ? edge : nan;
}

bool safe_at_rest(const SafeUnit& u, double m, double kappa, double gamma, double dt) {
  for (size_t i = 0; i < u.row_sum.size(); ++i)
    if (!(gamma * u.gamma_scale[i] < node_safe(u, i, m, kappa, dt))) return false;
  return true;
}

bool safe_policy_guaranteed(const SafeUnit& u, double m, double kappa, double dt) {
  for (size_t i = 0; i < u.row_sum.size(); ++i)
    if (!(node_safe(u, i, m, kappa, dt) > 0)) return false;
  return true;
}

std::vector<PredictorScore> divergence_confusion(const std::vector<SweepRow>& rows,
                                                 const SafeUnit& unit, double lambda_unit) {
  std::vector<PredictorScore> out = {
      {"paper runtime check (gamma_lo > gamma_hi at some node-step, sec. 5)", {}},
      {"safe check at rest (gamma_i >= gamma_safe_i at some node)", {}}};
  const bool exact = std::isfinite(lambda_unit) && lambda_unit > 0;
  if (exact) out.push_back({"exact linear limit at rest", {}});
  for (const SweepRow& r : rows) {
    if (has_spec10_damping(r)) continue;  // the unit safe bound is the nodal one
    const bool diverged = r.outcome == Outcome::diverged;
    const bool says[3] = {r.unstabilisable > 0, !safe_at_rest(unit, r.m, r.kappa, r.gamma, r.dt),
                          exact && linearly_unstable(r.m, r.kappa, r.gamma, r.dt, lambda_unit)};
    for (size_t k = 0; k < out.size(); ++k) {
      Confusion& c = out[k].c;
      ++(says[k] ? (diverged ? c.true_pos : c.false_pos) : (diverged ? c.false_neg : c.true_neg));
    }
  }
  return out;
}

std::string confusion_markdown(const std::vector<PredictorScore>& scores) {
  std::string s =
      "| predictor of divergence | says diverges, diverged | says diverges, did not | says "
      "stable, diverged | says stable, did not | wrong |\n|---|---|---|---|---|---|\n";
  for (const PredictorScore& p : scores) {
    const Confusion& c = p.c;
    const std::uint64_t all = c.true_pos + c.false_pos + c.false_neg + c.true_neg;
    char buf[256];
    c_snprintf(buf, sizeof buf, " | %" PRIu64 " | %" PRIu64 " | %" PRIu64 " | %" PRIu64 " | %s |\n",
                  c.true_pos, c.false_pos, c.false_neg, c.true_neg,
                  pct(c.false_pos + c.false_neg, all).c_str());
    s += "| " + p.predictor + buf;
  }
  return s;
}

std::vector<std::string> safe_summary_lines(const std::vector<SweepRow>& rows,
                                            std::optional<DampingPolicy> policy, const SafeUnit& unit,
                                            double lambda_unit) {
  std::vector<std::string> lines;
  char buf[512];
  const auto spec10 = std::count_if(rows.begin(), rows.end(), has_spec10_damping);
  if (spec10 > 0 && (policy == DampingPolicy::fixed || policy == DampingPolicy::safe)) {
    c_snprintf(buf, sizeof buf,
               "note         %lld trials with dashpot or Rayleigh damping are not scored below: "
               "the sweep's safe bound is the nodal one (bounds gives the damped one per scene)",
               static_cast<long long>(spec10));
    lines.push_back(buf);
  }
  if (policy == DampingPolicy::fixed) {
    for (const PredictorScore& p : divergence_confusion(rows, unit, lambda_unit)) {
      const Confusion& c = p.c;
      c_snprintf(buf, sizeof buf,
                    "divergence   %s: says diverges %" PRIu64 " (diverged %" PRIu64
                    "), says stable %" PRIu64 " (diverged %" PRIu64 ")",
                    p.predictor.c_str(), c.true_pos + c.false_pos, c.true_pos,
                    c.false_neg + c.true_neg, c.false_neg);
      lines.push_back(buf);
    }
  } else if (policy == DampingPolicy::safe) {
    std::uint64_t guaranteed = 0, guaranteed_div = 0, open = 0, open_div = 0;
    std::vector<const SweepRow*> surprises;
    for (const SweepRow& r : rows) {
      if (has_spec10_damping(r)) continue;  // the unit safe bound is the nodal one
      const bool g = safe_policy_guaranteed(unit, r.m, r.kappa, r.dt);
      const bool d = r.outcome == Outcome::diverged;
      (g ? guaranteed : open) += 1;
      (g ? guaranteed_div : open_div) += d;
      if (g && d) surprises.push_back(&r);
    }
    c_snprintf(buf, sizeof buf,
                  "safe policy  gamma_safe_i > 0 at every node (stability guaranteed at rest, "
                  "safe bound): %" PRIu64 " trials, %" PRIu64 " diverged",
                  guaranteed, guaranteed_div);
    lines.push_back(buf);
    c_snprintf(buf, sizeof buf,
                  "safe policy  gamma_safe_i <= 0 at some node (no damping guarantees it at this "
                  "dt): %" PRIu64 " trials, %" PRIu64 " diverged",
                  open, open_div);
    lines.push_back(buf);
    for (size_t k = 0; k < surprises.size() && k < 5; ++k) {
      const SweepRow& r = *surprises[k];
      c_snprintf(buf, sizeof buf,
                    "safe policy  diverged although guaranteed at rest: trial %" PRIu64
                    " m=%s kappa=%s dt=%s at iteration %d",
                    r.trial, format_number(r.m).c_str(), format_number(r.kappa).c_str(),
                    format_number(r.dt).c_str(), r.iterations);
      lines.push_back(buf);
    }
  }
  return lines;
}

std::string safe_report_section(const std::vector<SweepRow>& fixed_rows,
                                const std::string& fixed_definition,
                                const std::vector<SweepRow>& safe_rows,
                                const std::string& safe_definition, const SafeUnit& unit,
                                double lambda_unit) {
  double r_unit = 0;
  for (double r : unit.row_sum) r_unit = std::max(r_unit, r);
  auto outcomes = [](const std::vector<SweepRow>& rows) {
    std::uint64_t n[6] = {0, 0, 0, 0, 0, 0};  // by Outcome
    for (const SweepRow& r : rows) ++n[static_cast<size_t>(r.outcome)];
    std::string text;
    for (Outcome o : {Outcome::restored, Outcome::not_restored, Outcome::settled,
                      Outcome::not_settled, Outcome::diverged}) {
      const std::uint64_t k = n[static_cast<size_t>(o)];
      if (k == 0 && o != Outcome::diverged) continue;
      text += std::to_string(k) + " " + to_string(o) + ", ";
    }
    return text + "of " + std::to_string(rows.size()) + " trials";
  };
  char num[64];
  c_snprintf(num, sizeof num, "%.6g", r_unit);
  std::string s = "\n## What guarantees stability\n\n";
  s += "The paper's runtime check (sec. 5) compares the lower bound of eq. 5 with the upper "
       "bound of eq. 6 at every node and step. The safe bound (docs/criteria.md) "
       "is a sufficient condition instead: with the tangent stiffness K positive "
       "semi-definite, the linearised step is stable where every free node has gamma_i < "
       "gamma_safe_i = 2 m_i/dt - m_i dt R_i/2, R_i the largest Gershgorin row sum of "
       "M^-1/2 K M^-1/2 over the node's rows (largest R_i on this mesh at rest: " +
       std::string(num) + " kappa/m";
  if (std::isfinite(lambda_unit)) {
    c_snprintf(num, sizeof num, "%.6g", lambda_unit);
    s += ", against lambda_max = " + std::string(num) + " kappa/m";
  }
  s += ").\n\nThe lower-bound sweep on a grid that spans the paper's whole kappa/m range "
       "(its smallest m and kappa, 0.0001, included; " + fixed_definition + "): " +
       outcomes(fixed_rows) +
       ". Each check as a predictor of divergence under this fixed damping (a check that "
       "says \"stable\" of a trial that diverged fails as a guarantee):\n\n";
  s += confusion_markdown(divergence_confusion(fixed_rows, unit, lambda_unit));
  s += "\nThe same grid under the `safe` policy (gamma clamped into [gamma_lo_i, "
       "gamma_safe_i] at every step; " + safe_definition + "): " + outcomes(safe_rows) +
       ".\n\n";
  for (const std::string& line : safe_summary_lines(safe_rows, DampingPolicy::safe, unit, lambda_unit))
    s += "    " + line + "\n";
  s += "\nData: `sweep-span.csv`, `sweep-safe.csv`.\n";
  return s;
}

}  // namespace dampbound
