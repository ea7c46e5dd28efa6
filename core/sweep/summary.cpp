#include "core/sweep/summary.hpp"

#include <algorithm>

#include <cinttypes>
#include <cmath>
#include <cstdio>

#include "core/io/format.hpp"
#include "dampbound/analysis/linear_stability.hpp"

namespace dampbound {

double unit_stiffness_eigenvalue(const SceneSpec& scene) {
  Params p = scene.params;
  p.m = 1;
  p.kappa = 1;
  const Model model = compile_model(scene.model, p);
  return max_stiffness_eigenvalue(model, model.spec().rest);
}

bool linearly_unstable(double m, double kappa, double gamma, double dt, double lambda_unit) {
  return spec7_unstable(lambda_unit * kappa / m, gamma / m, dt);
}

std::optional<double> dashpot_stiffness_ratio(const SceneSpec& scene) {
  const ModelSpec& m = scene.model;
  std::optional<double> ratio;
  auto same = [&](double r) {
    if (!ratio) ratio = r;
    return *ratio == r;
  };
  for (const Spring& s : m.springs) {
    const double l = (m.rest[static_cast<size_t>(s.j)] - m.rest[static_cast<size_t>(s.i)]).norm();
    if (l != s.rest_length || !same(s.kd_scale / s.kappa_scale)) return std::nullopt;
  }
  for (size_t i = 0; i < m.anchor_scale.size(); ++i)
    if (m.anchor_scale[i] > 0 &&
        !same((m.anchor_kd_scale.empty() ? 1.0 : m.anchor_kd_scale[i]) / m.anchor_scale[i]))
      return std::nullopt;
  return ratio ? ratio : 1.0;
}

bool linearly_unstable(const SweepRow& r, double lambda_unit, double dashpot_ratio) {
  if (!has_spec10_damping(r)) return linearly_unstable(r.m, r.kappa, r.gamma, r.dt, lambda_unit);
  const double lambda = lambda_unit * r.kappa / r.m;
  const double c = r.gamma / r.m + r.rayleigh_mass +
                   (r.rayleigh_stiffness + dashpot_ratio * r.kd / r.kappa) * lambda;
  return spec7_unstable(lambda, c, r.dt);
}

std::optional<std::string> definition_value(const std::string& definition,
                                            const std::string& key) {
  const std::string needle = key + "=";
  size_t p = 0;
  while ((p = definition.find(needle, p)) != std::string::npos) {
    if (p == 0 || definition[p - 1] == ' ') {
      const size_t start = p + needle.size();
      const size_t end = definition.find(' ', start);
      return definition.substr(start, end == std::string::npos ? std::string::npos : end - start);
    }
    p += needle.size();
  }
  return std::nullopt;
}

std::vector<PredictionCheck> check_predictions(const std::vector<SweepRow>& rows,
                                               std::optional<DampingPolicy> policy, double lambda_unit,
                                               std::optional<double> dashpot_ratio) {
  std::vector<PredictionCheck> out;
  // Under the settled rule (SPEC 8) "restored" reads "settled": the claim is judged by the
  // rule the sweep ran under, and the text says which.
  const bool settled_rule = rows_rule(rows) == StopRule::settled;
  const auto good = [](const SweepRow& r) {
    return r.outcome == Outcome::restored || r.outcome == Outcome::settled;
  };
  const auto restored = good;
  const auto not_restored = [good](const SweepRow& r) { return !good(r); };
  const auto said = [settled_rule](std::string claim) {
    if (!settled_rule) return claim;
    for (size_t p = 0; (p = claim.find("restored", p)) != std::string::npos;)
      claim.replace(p, 8, "settled");
    return claim + " [settled rule]";
  };
  auto check = [&](const std::string& claim, auto applies, auto holds) {
    PredictionCheck c{said(claim), 0, 0};
    for (const SweepRow& r : rows)
      if (applies(r)) {
        ++c.of;
        c.held += holds(r) ? 1 : 0;
      }
    if (c.of) out.push_back(c);
  };
  const auto diverged = [](const SweepRow& r) { return r.outcome == Outcome::diverged; };
  const auto not_diverged = [](const SweepRow& r) { return r.outcome != Outcome::diverged; };
  // The paper's claims are about nodal damping alone: rows with SPEC 10 damping are left out.
  const auto nodal = [](const SweepRow& r) { return !has_spec10_damping(r); };
  if (policy == DampingPolicy::fixed) {
    check(
        "gamma < lower bound (zeta < 1, eq. 5) => not restored (paper sec. 4)",
        [&](const SweepRow& r) { return nodal(r) && r.zeta < 1; }, not_restored);
    check(
        "gamma >= lower bound (zeta >= 1) => restored within the limit (paper Fig. 1)",
        [&](const SweepRow& r) { return nodal(r) && r.zeta >= 1; }, restored);
  }
  if (policy == DampingPolicy::fixed && std::isfinite(lambda_unit) && lambda_unit > 0) {
    // SPEC 10's closed form where the rows have dashpot or Rayleigh damping; dashpots only
    // where they are proportional to K at rest (dashpot_ratio).
    const bool any_spec10 = std::any_of(rows.begin(), rows.end(), has_spec10_damping);
    const auto predicted = [&](const SweepRow& r) { return r.kd == 0 || dashpot_ratio.has_value(); };
    auto unstable = [&](const SweepRow& r) {
      return linearly_unstable(r, lambda_unit, dashpot_ratio.value_or(0));
    };
    check(any_spec10 ? "linearly unstable (with dashpot/Rayleigh damping) => diverged"
                     : "linearly unstable (gamma >= 2m/dt - m lambda_max dt/2) => diverged",
          [&](const SweepRow& r) { return predicted(r) && unstable(r); }, diverged);
    check(
        any_spec10 ? "linearly stable (with dashpot/Rayleigh damping) => not diverged"
                   : "linearly stable => not diverged",
        [&](const SweepRow& r) { return predicted(r) && !unstable(r); }, not_diverged);
  }
  if (policy == DampingPolicy::upper) {
    check(
        "factor <= 1 (damping at the upper bound, eq. 6) => restored (paper Fig. 2)",
        [](const SweepRow& r) { return r.factor <= 1; }, restored);
    check(
        "factor > 1 (damping above the upper bound) => diverged (paper Fig. 2)",
        [](const SweepRow& r) { return r.factor > 1; }, diverged);
  }
  if (policy == DampingPolicy::lower || policy == DampingPolicy::clamp)
    check(
        "damping kept within the bounds (policy " + std::string(to_string(*policy)) + ") => restored (paper sec. 5)",
        [](const SweepRow&) { return true; }, restored);
  return out;
}

StopRule rows_rule(const std::vector<SweepRow>& rows) {
  for (const SweepRow& r : rows)
    if (r.outcome == Outcome::settled || r.outcome == Outcome::not_settled)
      return StopRule::settled;
  return StopRule::first_entry;
}

Overturned count_overturned(const std::vector<SweepRow>& rows) {
  Overturned o;
  for (const SweepRow& r : rows) {
    if (r.first_entry == 0) continue;  // never entered: both rules say the same
    ++o.entered;
    if (r.outcome == Outcome::not_settled) ++o.left;
    if (r.outcome == Outcome::diverged) ++o.diverged;
  }
  return o;
}

std::vector<std::string> summary_lines(const std::vector<SweepRow>& rows,
                                       std::optional<DampingPolicy> policy, double lambda_unit,
                                       std::optional<double> dashpot_ratio) {
  std::uint64_t n[6] = {0, 0, 0, 0, 0, 0};
  for (const SweepRow& r : rows) ++n[static_cast<size_t>(r.outcome)];
  std::vector<std::string> lines;
  char buf[512];
  if (rows_rule(rows) == StopRule::settled) {
    const Overturned o = count_overturned(rows);
    std::uint64_t left = 0;  // not settled after an entry: the map's "entered, then left"
    for (const SweepRow& r : rows) left += r.outcome == Outcome::not_settled && r.first_entry > 0;
    c_snprintf(buf, sizeof buf,
                  "outcomes     %" PRIu64 " settled, %" PRIu64 " not settled (%" PRIu64
                  " of them entered the band, then left), %" PRIu64
                  " diverged (of %zu trials; settled rule)",
                  n[static_cast<size_t>(Outcome::settled)],
                  n[static_cast<size_t>(Outcome::not_settled)], left,
                  n[static_cast<size_t>(Outcome::diverged)], rows.size());
    lines.push_back(buf);
    c_snprintf(buf, sizeof buf,
                  "overturned   %" PRIu64 " of %" PRIu64
                  " first-entry restores (%.2f%%) did not settle: %" PRIu64
                  " left the band and were not back in at the limit, %" PRIu64 " diverged later",
                  o.left + o.diverged, o.entered,
                  o.entered ? 100.0 * static_cast<double>(o.left + o.diverged) /
                                  static_cast<double>(o.entered)
                            : 0.0,
                  o.left, o.diverged);
    lines.push_back(buf);
  } else {
    c_snprintf(buf, sizeof buf,
                  "outcomes     %" PRIu64 " restored, %" PRIu64 " not restored, %" PRIu64
                  " diverged (of %zu trials)",
                  n[static_cast<size_t>(Outcome::restored)],
                  n[static_cast<size_t>(Outcome::not_restored)],
                  n[static_cast<size_t>(Outcome::diverged)], rows.size());
    lines.push_back(buf);
  }
  for (const PredictionCheck& c : check_predictions(rows, policy, lambda_unit, dashpot_ratio)) {
    c_snprintf(buf, sizeof buf, "prediction   %s: held in %" PRIu64 " of %" PRIu64 " (%.1f%%)",
                  c.claim.c_str(), c.held, c.of,
                  100.0 * static_cast<double>(c.held) / static_cast<double>(c.of));
    lines.push_back(buf);
  }
  return lines;
}

}  // namespace dampbound
