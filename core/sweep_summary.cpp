#include "core/sweep_summary.hpp"

#include <cinttypes>
#include <cmath>
#include <cstdio>

#include "core/linear_stability.hpp"

namespace dampbound {

double unit_stiffness_eigenvalue(const SceneSpec& scene) {
  Params p = scene.params;
  p.m = 1;
  p.kappa = 1;
  const Model model = make_model(scene, p);
  return max_stiffness_eigenvalue(model, model.rest);
}

bool linearly_unstable(double m, double kappa, double gamma, double dt, double lambda_unit) {
  const double lambda = lambda_unit * kappa / m;
  const double c_dt = gamma / m * dt;
  return !(c_dt < 2) || !(lambda * dt * dt < 4 - 2 * c_dt);
}

std::string definition_value(const std::string& definition, const std::string& key) {
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
  return {};
}

std::vector<PredictionCheck> check_predictions(const std::vector<SweepRow>& rows,
                                               const std::string& policy, double lambda_unit) {
  std::vector<PredictionCheck> out;
  auto check = [&](const std::string& claim, auto applies, auto holds) {
    PredictionCheck c{claim, 0, 0};
    for (const SweepRow& r : rows)
      if (applies(r)) {
        ++c.of;
        c.held += holds(r) ? 1 : 0;
      }
    if (c.of) out.push_back(c);
  };
  const auto restored = [](const SweepRow& r) { return r.outcome == Outcome::restored; };
  const auto not_restored = [](const SweepRow& r) { return r.outcome != Outcome::restored; };
  const auto diverged = [](const SweepRow& r) { return r.outcome == Outcome::diverged; };
  const auto not_diverged = [](const SweepRow& r) { return r.outcome != Outcome::diverged; };
  if (policy == "fixed") {
    check(
        "gamma < lower bound (zeta < 1, eq. 5) => not restored (paper sec. 4)",
        [](const SweepRow& r) { return r.zeta < 1; }, not_restored);
    check(
        "gamma >= lower bound (zeta >= 1) => restored within the limit (paper Fig. 1)",
        [](const SweepRow& r) { return r.zeta >= 1; }, restored);
  }
  if (policy == "fixed" && std::isfinite(lambda_unit) && lambda_unit > 0) {
    auto unstable = [lambda_unit](const SweepRow& r) {
      return linearly_unstable(r.m, r.kappa, r.gamma, r.dt, lambda_unit);
    };
    check("linearly unstable (gamma >= 2m/dt - m lambda_max dt/2, SPEC 7) => diverged", unstable,
          diverged);
    check(
        "linearly stable (SPEC 7) => not diverged", [&](const SweepRow& r) { return !unstable(r); },
        not_diverged);
  }
  if (policy == "upper") {
    check(
        "factor <= 1 (damping at the upper bound, eq. 6) => restored (paper Fig. 2)",
        [](const SweepRow& r) { return r.factor <= 1; }, restored);
    check(
        "factor > 1 (damping above the upper bound) => diverged (paper Fig. 2)",
        [](const SweepRow& r) { return r.factor > 1; }, diverged);
  }
  if (policy == "lower" || policy == "clamp")
    check(
        "damping kept within the bounds (policy " + policy + ") => restored (paper sec. 5)",
        [](const SweepRow&) { return true; }, restored);
  return out;
}

std::vector<std::string> summary_lines(const std::vector<SweepRow>& rows, const std::string& policy,
                                       double lambda_unit) {
  std::uint64_t n[4] = {0, 0, 0, 0};
  for (const SweepRow& r : rows) ++n[static_cast<size_t>(r.outcome)];
  std::vector<std::string> lines;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "outcomes     %" PRIu64 " restored, %" PRIu64 " not restored, %" PRIu64
                " diverged (of %zu trials)",
                n[static_cast<size_t>(Outcome::restored)],
                n[static_cast<size_t>(Outcome::not_restored)],
                n[static_cast<size_t>(Outcome::diverged)], rows.size());
  lines.push_back(buf);
  for (const PredictionCheck& c : check_predictions(rows, policy, lambda_unit)) {
    std::snprintf(buf, sizeof buf, "prediction   %s: held in %" PRIu64 " of %" PRIu64 " (%.1f%%)",
                  c.claim.c_str(), c.held, c.of,
                  100.0 * static_cast<double>(c.held) / static_cast<double>(c.of));
    lines.push_back(buf);
  }
  return lines;
}

}  // namespace dampbound
