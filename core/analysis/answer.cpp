#include "core/analysis/answer.hpp"

#include <cmath>

#include "core/io/format.hpp"
#include "core/io/report.hpp"

namespace dampbound {

namespace {

std::string num(double x) { return format_human(x); }

/// "dt < 0.504 s" (or "any dt" for inf, "no dt" for <= 0).
std::string below(const char* what, double limit, const char* unit) {
  if (std::isinf(limit) && limit > 0) return std::string("any ") + what;
  if (!(limit > 0)) return std::string("no ") + what;
  return std::string(what) + " < " + num(limit) + unit;
}

/// "[0, 0.0398)" or "no gamma" when empty.
std::string gamma_range(double lo, double hi) {
  if (!(lo < hi)) return "no gamma is stable";
  return "gamma in [" + num(lo) + ", " + (std::isinf(hi) ? std::string("inf") : num(hi)) + ")";
}

/// " at gamma = 0.002, dt = 0.05 s", or "" without parameters.
std::string at_params(const Params* p) {
  if (!p) return std::string();
  std::string out = " at gamma = " + num(p->gamma);
  // SPEC 10's damping shaped the verdict too: said where there is some.
  if (p->kd != 0) out += ", kd = " + num(p->kd);
  if (p->rayleigh_mass != 0) out += ", rayleigh_mass = " + num(p->rayleigh_mass);
  if (p->rayleigh_stiffness != 0) out += ", rayleigh_stiffness = " + num(p->rayleigh_stiffness);
  return out + ", dt = " + num(p->dt) + " s";
}

/// The over-budget analysis: what plain Lanczos and Gershgorin proved.
bool proved_unstable(const ExactStability& e) {
  const auto& u = e.unfactored;
  return (u.index_at_least >= 4) ||
         (std::isfinite(u.mode_unstable_from) && u.lambda_max_lo >= u.mode_unstable_from);
}

}  // namespace

std::vector<std::string> exact_answer(const ExactStability& e, const Params* p,
                                      const SafeBoundSummary* safe, const std::string& where) {
  std::vector<std::string> out;
  std::string safe_part;
  if (safe != nullptr && safe->free_nodes > 0)
    safe_part = "the safe bound guarantees it node by node for " +
                below("gamma", safe->gamma_safe, "") + " and " + below("dt", safe->dt_safe, " s");
  if (!e.computed()) {
    const std::string verdict =
        e.stable ? "stable" + at_params(p) + " (proved without a factorisation, " + where + ")"
        : proved_unstable(e)
            ? "UNSTABLE" + at_params(p) + " (proved without a factorisation, " + where + ")"
            : "not decided" + at_params(p) +
                  ": the exact analysis is over the factorisation budget (--factor-budget)";
    out.push_back(verdict);
    std::string limits;
    if (std::isfinite(e.unfactored.dt_stable_up_to) && e.unfactored.dt_stable_up_to > 0)
      limits = "dt <= " + num(e.unfactored.dt_stable_up_to) + " s is proved stable at this gamma";
    if (std::isfinite(e.unfactored.dt_unstable_from))
      limits += (limits.empty() ? "" : "; ") + std::string("dt >= ") +
                num(e.unfactored.dt_unstable_from) + " s is proved unstable";
    if (!safe_part.empty()) limits += (limits.empty() ? "" : "; ") + safe_part;
    if (!limits.empty()) out.push_back(limits);
    return out;
  }
  const std::string how = "exact linear analysis " + where;
  if (e.stable) {
    const bool marginal = std::isfinite(e.spectral_radius) && e.spectral_radius >= 1;
    out.push_back((marginal ? "marginally stable" : "stable") + at_params(p) + " (" + how +
                  (marginal ? "; rho = 1: some motion does not decay" : "") + ")");
    std::string limits = "limits: " + below("dt", e.dt_max, " s") + " at this gamma; " +
                         gamma_range(e.gamma_lo, e.gamma_hi) + " at this dt";
    if (!safe_part.empty()) limits += "; " + safe_part;
    out.push_back(limits);
    return out;
  }
  out.push_back("UNSTABLE" + at_params(p) + " (" + how + ")");
  std::string fix = "to fix: ";
  const bool dt_fix = e.dt_max > 0, gamma_fix = e.gamma_lo < e.gamma_hi;
  if (dt_fix) fix += below("dt", e.dt_max, " s") + " at this gamma";
  if (gamma_fix) fix += std::string(dt_fix ? ", or " : "") + gamma_range(e.gamma_lo, e.gamma_hi) + " at this dt";
  if (!dt_fix && !gamma_fix)
    fix += e.indefinite ? "no gamma or dt: K is indefinite at this state (compressed springs)"
                        : "no gamma at this dt and no dt at this gamma is stable";
  out.push_back(fix);
  return out;
}

std::vector<std::string> damping_answer(const DampingSuggestion& s) {
  std::vector<std::string> out;
  const std::string at = "at dt = " + num(s.dt) + " s";
  if (s.empty) {
    out.push_back("no damping satisfies every criterion " + at);
    out.push_back("the largest " + std::string(s.proved_only ? "proved stable" : "stable") +
                  " dt at gamma = " + num(s.gamma_min) + " is " + num(s.dt_max_at_gamma_min) +
                  " s (suggest --gamma " + num(s.gamma_min) + ")");
    return out;
  }
  std::string use = "use gamma = " + num(s.gamma_best) + " " + at + " (fastest settling";
  for (const VerifiedRun& r : s.runs)
    if (r.label == "fastest-settling gamma")
      use += r.verified() ? "; its run settled" : "; its run did NOT settle: do not use it as is";
  out.push_back(use + ")");
  std::string range = "stable for gamma in [" + num(s.gamma_min) + ", " + num(s.gamma_max) +
                      (s.proved_only ? "] (proved without a factorisation)" : ") by every criterion");
  if (s.safe_max > 0) range += "; the safe bound guarantees gamma < " + num(s.safe_max);
  out.push_back(range);
  return out;
}

std::vector<std::string> step_answer(const StepSuggestion& s) {
  std::vector<std::string> out;
  if (!(s.dt_all > 0))
    return {"no dt is stable at gamma = " + num(s.gamma) + " (" + s.dt_all_by +
                ": dt < " + num(s.dt_exact) + ")",
            "lower gamma: suggest with --dt gives the stable gamma range at a dt"};
  std::string use = "use dt <= " + num(s.dt_all) + " s at gamma = " + num(s.gamma) + " (every criterion";
  for (const VerifiedRun& r : s.runs)
    if (r.label == "largest dt every criterion accepts")
      use += r.verified() ? "; its run settled" : "; its run did NOT settle: do not use it as is";
  out.push_back(use + ")");
  out.push_back(std::string(s.proved_only ? "proved stable for dt <= " : "exact limit dt < ") +
                num(s.dt_exact) + " s; the safe bound guarantees dt < " + num(s.dt_safe) + " s");
  return out;
}

std::vector<std::string> substeps_answer(const SubstepSuggestion& s) {
  const std::string frame = " (frame " + num(s.frame_dt) + " s)";
  if (const SubstepCount* use = s.answer())
    return {substeps_text(use->n) + " per frame (dt = " + num(use->dt) + " s; its run settled)"};
  const bool over_budget = s.exact.n == 0 && s.note.rfind("exact limit not computed", 0) == 0;
  if (over_budget && s.safe.n > 0 && !s.safe.ran)
    return {substeps_text(s.safe.n) + " per frame by the safe bound (dt = " + num(s.safe.dt) +
            " s; not run: --no-verify); the exact limit is over the factorisation budget"};
  if (over_budget)
    return {"no substep count" + frame +
            ": the exact limit is over the factorisation budget and no count's run settled"};
  if (s.exact.n == 0)
    return {"no substep count" + frame + ": the exact limit needs more than " +
            substeps_text(kMaxSubsteps) + " per frame"};
  if (!s.exact.ran && !s.safe.ran)
    return {substeps_text(s.exact.n) + " per frame by the exact limit (dt = " + num(s.exact.dt) +
            " s; not run: --no-verify)"};
  return {"none verified: no count's run settled" + frame};
}

std::vector<std::string> run_answer(const RunResult& r, const StopRules& rules, const Params& p) {
  const int at = r.outcome == Outcome::settled ? r.settled_at : r.iterations;
  std::vector<std::string> out = {verdict_text(r, rules) + "; t = " + num(at * p.dt) + " s," +
                                  at_params(&p)};
  if (r.outcome == Outcome::diverged || r.outcome == Outcome::not_settled ||
      r.outcome == Outcome::not_restored)
    out.push_back(r.outcome == Outcome::diverged
                      ? "unstable as run: lower dt or change gamma (suggest gives the stable range)"
                      : "not settled in the run's time: more damping or more iterations "
                        "(suggest gives the stable range)");
  return out;
}

}  // namespace dampbound
